#include "hdp/suffix_swap.h"

#include <algorithm>

namespace wardmap::hdp {

namespace {

// Whether any item of `a` and any item of `b` must not share a dish.
bool conflict(const CrfModel& model, const std::vector<ItemRef>& a, const std::vector<ItemRef>& b) {
  for (const auto& x : a)
    for (const auto& y : b)
      if (model.cannot_link(x, y)) return true;
  return false;
}

std::vector<ItemRef> merged(const std::vector<ItemRef>& a, const std::vector<ItemRef>& b) {
  std::vector<ItemRef> out;
  out.reserve(a.size() + b.size());
  std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// Items of every dish, sorted by (group, item).
std::vector<std::vector<ItemRef>> members_of(const std::vector<std::vector<int>>& dish, int num_dishes) {
  std::vector<std::vector<ItemRef>> members(static_cast<size_t>(num_dishes));
  for (size_t j = 0; j < dish.size(); ++j)
    for (size_t i = 0; i < dish[j].size(); ++i)
      if (dish[j][i] >= 0)
        members[static_cast<size_t>(dish[j][i])].push_back({static_cast<int>(j), static_cast<int>(i)});
  return members;
}

}  // namespace

int improve_by_suffix_swaps(const CrfModel& model, std::vector<std::vector<int>>& dish, int num_dishes,
                            const SuffixSwapOptions& options) {
  int kept = 0;
  for (int round = 0; round < options.max_rounds; ++round) {
    std::vector<std::vector<ItemRef>> members = members_of(dish, num_dishes);
    std::vector<double> marginal(static_cast<size_t>(num_dishes), 0.0);
    for (int k = 0; k < num_dishes; ++k)
      if (!members[k].empty()) marginal[k] = model.log_marginal(members[k]);
    int kept_this_round = 0;
    for (int a = 0; a < num_dishes; ++a)
      for (int b = a + 1; b < num_dishes; ++b) {
        const auto& A = members[a];
        const auto& B = members[b];
        if (A.empty() || B.empty()) continue;
        // Cuts: groups c at which both dishes have items before and from c on.
        const int lo = std::max(A.front().group, B.front().group) + 1;
        const int hi = std::min(A.back().group, B.back().group);
        double best_gain = options.min_gain;
        int best_cut = -1;
        for (int c = lo; c <= hi; ++c) {
          const auto split = [c](const std::vector<ItemRef>& v) {
            return std::lower_bound(v.begin(), v.end(), ItemRef{c, 0});
          };
          const auto sa = split(A), sb = split(B);
          if (sa == A.begin() || sa == A.end() || sb == B.begin() || sb == B.end()) continue;
          const std::vector<ItemRef> a_head(A.begin(), sa), a_tail(sa, A.end()), b_head(B.begin(), sb),
              b_tail(sb, B.end());
          if (conflict(model, a_head, b_tail) || conflict(model, b_head, a_tail)) continue;
          const double gain = model.log_marginal(merged(a_head, b_tail)) + model.log_marginal(merged(b_head, a_tail)) -
                              marginal[a] - marginal[b];
          if (gain > best_gain) best_gain = gain, best_cut = c;
        }
        if (best_cut < 0) continue;
        for (size_t j = static_cast<size_t>(best_cut); j < dish.size(); ++j)
          for (auto& d : dish[j])
            if (d == a)
              d = b;
            else if (d == b)
              d = a;
        ++kept_this_round;
        // The two dishes' new items before pairing them with others.
        members = members_of(dish, num_dishes);
        marginal[a] = model.log_marginal(members[a]);
        marginal[b] = model.log_marginal(members[b]);
      }
    kept += kept_this_round;
    if (kept_this_round == 0) break;
  }
  return kept;
}

}  // namespace wardmap::hdp
