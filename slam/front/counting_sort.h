// A stable counting sort of item indices by a small integer key (a grid cell, an image row, a
// column of nodes): the grouping step the feature grid, the FAST merge and the quadtree share.
#pragma once

#include <cstddef>
#include <vector>

namespace wardmap::slam {

// Groups the items 0..keys.size()-1 by key, each key in [0, n_buckets) or negative (the item is
// left out). Afterwards bucket b holds order[start[b] .. start[b + 1]), in ascending item index;
// `start` has n_buckets + 1 entries and `order` the items kept. Both are overwritten.
void counting_sort(const std::vector<int>& keys, int n_buckets, std::vector<int>& start, std::vector<int>& order);

}  // namespace wardmap::slam
