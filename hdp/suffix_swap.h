// A move for grouped data whose groups are ordered in time (keyframe groups), made on a sampled
// state: two dishes exchange all their items from group c on. Item-by-item Gibbs moves cannot make
// it when the two dishes' items are seen together (a cannot-link keeps them apart in every group):
// two neighbouring objects that swapped landmarks over a run of groups stay swapped. Each
// exchange is kept when it raises the sum of the two dishes' log marginals (CrfModel::log_marginal)
// and breaks no cannot-link; the CRF's table and dish counts are left as they are.
#pragma once

#include <vector>

#include "hdp/crf_model.h"

namespace wardmap::hdp {

struct SuffixSwapOptions {
  int max_rounds = 5;     // passes over all dish pairs; a pass that keeps no exchange ends the search
  double min_gain = 1.0;  // nats: smaller gains are left (the sampled state is kept when unsure)
};

// dish[j][i]: dish of item i of group j (labels 0..num_dishes-1, -1: none), modified in place.
// Returns the number of exchanges kept.
int improve_by_suffix_swaps(const CrfModel& model, std::vector<std::vector<int>>& dish, int num_dishes,
                            const SuffixSwapOptions& options = {});

}  // namespace wardmap::hdp
