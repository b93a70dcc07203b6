// The pluggable model of the Chinese-restaurant-franchise sampler (crf_sampler.h): how well an item
// (customer) fits a dish, given the items already eating it. Kept apart from the sampler so the
// semantic layer can implement it without seeing the sampler's internals.
#pragma once

#include <tuple>
#include <vector>

namespace wardmap::hdp {

// One item: `item` is its index inside group `group` (both from 0). Opaque to the sampler.
struct ItemRef {
  int group = -1;
  int item = -1;
  friend bool operator==(const ItemRef& a, const ItemRef& b) { return a.group == b.group && a.item == b.item; }
  friend bool operator!=(const ItemRef& a, const ItemRef& b) { return !(a == b); }
  friend bool operator<(const ItemRef& a, const ItemRef& b) {
    return std::tie(a.group, a.item) < std::tie(b.group, b.item);
  }
};

class CrfModel {
 public:
  virtual ~CrfModel() = default;

  // log f_k(x_item): how well item fits the dish whose current items are dish_members (never empty,
  // never containing item, sorted by (group, item)). Teh et al. 2006 Eq. 30 (the conditional density
  // of x_ji under dish k given all other items of k). May also carry any prior preference for
  // joining this dish (Assoc. III-A.2: max GMM probability, x1.5 overlap boost): the sampler adds
  // the CRF counts and concentrations itself.
  virtual double log_predictive(const ItemRef& item, const std::vector<ItemRef>& dish_members) const = 0;

  // log f_new(x_item): how well item fits a brand-new dish (prior predictive).
  virtual double log_predictive_new(const ItemRef& item) const = 0;

  // Joint fit of several items that move together (the customers of one table) to a dish with
  // dish_members (empty = a new dish). Default: the chain rule over items in the given order,
  //   sum_i log_predictive(items[i], dish_members + items[0..i-1])   (log_predictive_new when empty).
  // Override for a closed form or for speed.
  virtual double log_predictive_set(const std::vector<ItemRef>& items, const std::vector<ItemRef>& dish_members) const;

  // log p(x_members): the marginal likelihood of one dish's items (sorted), used only to score whole
  // states when choosing the MAP state. Default: log_predictive_set(members, {}).
  virtual double log_marginal(const std::vector<ItemRef>& members) const;

  // Cannot-link hook: true when a and b must never share a dish. Default: no constraint. (The
  // sampler's cannot_link_within_group option covers the "same group" case without calling this.)
  virtual bool cannot_link(const ItemRef& a, const ItemRef& b) const { return false; }
};

}  // namespace wardmap::hdp
