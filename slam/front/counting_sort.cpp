#include "slam/front/counting_sort.h"

namespace wardmap::slam {

void counting_sort(const std::vector<int>& keys, int n_buckets, std::vector<int>& start, std::vector<int>& order) {
  start.assign(static_cast<size_t>(n_buckets) + 1, 0);
  for (int k : keys)
    if (k >= 0) ++start[static_cast<size_t>(k) + 1];
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  order.resize(static_cast<size_t>(start.back()));
  // Placing advances start[k] to bucket k's end, which is start[k + 1] before placing: shift back.
  for (size_t i = 0; i < keys.size(); ++i)
    if (keys[i] >= 0) order[static_cast<size_t>(start[static_cast<size_t>(keys[i])]++)] = static_cast<int>(i);
  for (size_t b = start.size() - 1; b > 0; --b) start[b] = start[b - 1];
  start[0] = 0;
}

}  // namespace wardmap::slam
