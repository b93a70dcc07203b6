// Chinese-restaurant-franchise Gibbs sampler for a hierarchical Dirichlet process (Teh, Jordan, Beal
// & Blei 2006, Sec. 5.1) over grouped items: groups j are restaurants, items x_ji customers, global
// dishes k the shared clusters (Assoc. III-A.2: groups = keyframe groups, items = group objects,
// dishes = object landmarks). One sweep resamples the table t_ji of every item (Teh Eq. 32-33), then
// the dish k_jt of every table (Teh Eq. 34). The model is pluggable (crf_model.h).
// Randomness: std::mt19937_64 with our own uniform / categorical draws, so a seed gives the same
// result with any standard library.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "hdp/crf_model.h"

namespace wardmap::hdp {

struct CrfOptions {
  // The paper gives no values; 1.0 is the usual neutral choice.
  double alpha = 1.0;       // table level: propensity of a customer to open a new table
  double gamma = 1.0;       // dish level: propensity of a new table to order a new dish
  int burn_in_sweeps = 20;  // sweeps discarded before the MAP search
  int sweeps = 50;          // sweeps scored for the MAP state
  std::uint64_t seed = 1;
  bool cannot_link_within_group = false;  // two items of one group never share a dish
  bool resample_dishes = true;            // run the table-dish step (Teh Eq. 34) in each sweep
  // Empty when valid, else a sentence naming the offending field.
  std::optional<std::string> validate() const;
};

struct CrfResult {
  // dish[j][i]: the dish of item i of group j in the MAP state, numbered 0..num_dishes-1 in order of
  // first appearance scanning groups then items (so equal partitions give equal labels).
  std::vector<std::vector<int>> dish;
  int num_dishes = 0;
  double log_joint = 0;       // log p(x, t, k) of the MAP state
  int map_sweep = -1;         // 0-based sweep after burn-in it was seen at (-1: no scored sweep ran)
  std::vector<double> trace;  // log p(x, t, k) after initialisation and after every sweep
};

class CrfSampler {
 public:
  // group_sizes[j] = number of items in group j. The model must outlive the sampler.
  CrfSampler(const CrfModel& model, std::vector<int> group_sizes, const CrfOptions& options = {});

  // Seats every item. Items with initial_dishes[j][i] >= 0 (an arbitrary label shared across
  // groups) start at one table per (group, label) serving one dish per label - a warm start from a
  // previous run; the others (and any that would break a cannot-link) are then seated one by one
  // from the CRF conditional given the items seated so far. initial_dishes may be empty.
  void initialise(const std::vector<std::vector<int>>& initial_dishes = {});
  // One Gibbs sweep: every item's table, then (if enabled) every table's dish.
  void sweep();
  // initialise, burn-in, scored sweeps; returns the scored state with the highest log joint.
  CrfResult run(const std::vector<std::vector<int>>& initial_dishes = {});

  // log p(x, t, k) of the current state: CRF prior of tables and dishes (Teh Eq. 24-25 style
  // Ewens terms) plus the sum over dishes of model.log_marginal.
  double log_joint() const;
  // Current dish / table of every item, canonically numbered as in CrfResult::dish.
  std::vector<std::vector<int>> dishes() const;
  std::vector<std::vector<int>> tables() const;
  int num_dishes() const;
  int num_tables() const { return total_tables_; }

  // Uniform double in [0, 1) from 53 raw bits, and a categorical draw from log weights (exposed for
  // tests; -inf weights are never drawn, NaN throws).
  double uniform01();
  int sample_log_categorical(const std::vector<double>& log_weights);

 private:
  struct Table {
    int dish = -1;           // -1: free slot
    std::vector<int> items;  // item indices within the group
  };
  struct Dish {
    int num_tables = 0;            // m_k; 0: free slot
    std::vector<ItemRef> members;  // sorted
  };

  void sample_table(int j, int i);
  void sample_dish(int j, int t);
  void seat(int j, int i, int t);
  void unseat(int j, int i);
  int open_table(int j, int dish);
  int open_dish();
  void add_member(int k, const ItemRef& x);
  void remove_member(int k, const ItemRef& x);
  bool allowed(int k, const ItemRef& x) const;

  const CrfModel& model_;
  std::vector<int> group_sizes_;
  CrfOptions options_;
  std::mt19937_64 rng_;
  std::vector<std::vector<int>> table_of_;  // [j][i] -> table slot, -1 unseated
  std::vector<std::vector<Table>> tables_;  // [j][slot]
  std::vector<Dish> dishes_;
  int total_tables_ = 0;
};

}  // namespace wardmap::hdp
