#include "hdp/crf_model.h"

#include <algorithm>

namespace wardmap::hdp {

double CrfModel::log_predictive_set(const std::vector<ItemRef>& items, const std::vector<ItemRef>& dish_members) const {
  std::vector<ItemRef> members = dish_members;
  double sum = 0;
  for (const ItemRef& x : items) {
    sum += members.empty() ? log_predictive_new(x) : log_predictive(x, members);
    members.insert(std::lower_bound(members.begin(), members.end(), x), x);
  }
  return sum;
}

double CrfModel::log_marginal(const std::vector<ItemRef>& members) const { return log_predictive_set(members, {}); }

}  // namespace wardmap::hdp
