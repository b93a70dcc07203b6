#include "hdp/crf_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace wardmap::hdp {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

// log(sum exp(v)) over finite-or--inf entries.
double log_sum_exp(const std::vector<double>& v) {
  double hi = kNegInf;
  for (double x : v) hi = std::max(hi, x);
  if (!std::isfinite(hi)) return hi;
  double s = 0;
  for (double x : v) s += std::exp(x - hi);
  return hi + std::log(s);
}

// log Gamma(x), safe on several threads: std::lgamma writes the global signgam (a data race when
// chains run in parallel, found by ThreadSanitizer); lgamma_r (glibc, POSIX extension) does not.
double log_gamma(double x) {
  int sign = 0;
  return ::lgamma_r(x, &sign);
}

}  // namespace

std::optional<std::string> CrfOptions::validate() const {
  std::ostringstream err;
  if (!(alpha > 0 && std::isfinite(alpha)))
    err << "alpha must be positive and finite (got " << alpha << ")";
  else if (!(gamma > 0 && std::isfinite(gamma)))
    err << "gamma must be positive and finite (got " << gamma << ")";
  else if (burn_in_sweeps < 0)
    err << "burn_in_sweeps must be >= 0 (got " << burn_in_sweeps << ")";
  else if (sweeps < 0)
    err << "sweeps must be >= 0 (got " << sweeps << ")";
  if (err.tellp() == 0) return std::nullopt;
  return err.str();
}

CrfSampler::CrfSampler(const CrfModel& model, std::vector<int> group_sizes, const CrfOptions& options)
    : model_(model), group_sizes_(std::move(group_sizes)), options_(options), rng_(options.seed) {
  if (auto err = options_.validate()) throw std::invalid_argument("CrfOptions: " + *err);
  for (int n : group_sizes_)
    if (n < 0) throw std::invalid_argument("CrfSampler: a group size is negative");
  table_of_.resize(group_sizes_.size());
  tables_.resize(group_sizes_.size());
  for (size_t j = 0; j < group_sizes_.size(); ++j) table_of_[j].assign(group_sizes_[j], -1);
}

double CrfSampler::uniform01() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }

int CrfSampler::sample_log_categorical(const std::vector<double>& log_weights) {
  double hi = kNegInf;
  for (double w : log_weights) {
    if (std::isnan(w)) throw std::runtime_error("CrfSampler: the model returned NaN");
    hi = std::max(hi, w);
  }
  if (!std::isfinite(hi)) {
    if (hi > 0) throw std::runtime_error("CrfSampler: the model returned +inf");
    return static_cast<int>(log_weights.size()) - 1;  // nothing possible: the last option (a new one)
  }
  std::vector<double> cum(log_weights.size());
  double total = 0;
  for (size_t i = 0; i < log_weights.size(); ++i) cum[i] = (total += std::exp(log_weights[i] - hi));
  const double u = uniform01() * total;
  for (size_t i = 0; i < cum.size(); ++i)
    if (u < cum[i] && log_weights[i] > kNegInf) return static_cast<int>(i);
  for (size_t i = cum.size(); i-- > 0;)  // rounding at the top end: the last possible option
    if (log_weights[i] > kNegInf) return static_cast<int>(i);
  return static_cast<int>(log_weights.size()) - 1;
}

void CrfSampler::add_member(int k, const ItemRef& x) {
  auto& m = dishes_[k].members;
  m.insert(std::lower_bound(m.begin(), m.end(), x), x);
}

void CrfSampler::remove_member(int k, const ItemRef& x) {
  auto& m = dishes_[k].members;
  m.erase(std::lower_bound(m.begin(), m.end(), x));
}

bool CrfSampler::allowed(int k, const ItemRef& x) const {
  for (const ItemRef& y : dishes_[k].members) {
    if (options_.cannot_link_within_group && y.group == x.group) return false;
    if (model_.cannot_link(x, y)) return false;
  }
  return true;
}

int CrfSampler::open_dish() {
  for (int k = 0; k < static_cast<int>(dishes_.size()); ++k)
    if (dishes_[k].num_tables == 0) return k;
  dishes_.emplace_back();
  return static_cast<int>(dishes_.size()) - 1;
}

int CrfSampler::open_table(int j, int dish) {
  auto& ts = tables_[j];
  int t = 0;
  while (t < static_cast<int>(ts.size()) && ts[t].dish >= 0) ++t;
  if (t == static_cast<int>(ts.size())) ts.emplace_back();
  ts[t].dish = dish;
  ++dishes_[dish].num_tables;
  ++total_tables_;
  return t;
}

void CrfSampler::seat(int j, int i, int t) {
  Table& table = tables_[j][t];
  table.items.push_back(i);
  table_of_[j][i] = t;
  add_member(table.dish, ItemRef{j, i});
}

void CrfSampler::unseat(int j, int i) {
  const int t = table_of_[j][i];
  if (t < 0) return;
  Table& table = tables_[j][t];
  table.items.erase(std::find(table.items.begin(), table.items.end(), i));
  remove_member(table.dish, ItemRef{j, i});
  table_of_[j][i] = -1;
  if (table.items.empty()) {
    --dishes_[table.dish].num_tables;
    --total_tables_;
    table.dish = -1;
  }
}

// Teh et al. Eq. 32-33: p(t_ji = t) ~ n_jt f_k(x) for an existing table, alpha p(x | new table) for a
// new one; a new table then draws its dish ~ m_k f_k(x) or gamma f_new(x). Dishes that would break a
// cannot-link have probability 0.
void CrfSampler::sample_table(int j, int i) {
  unseat(j, i);
  const ItemRef x{j, i};
  const int K = static_cast<int>(dishes_.size());
  std::vector<double> f(K, kNegInf);
  for (int k = 0; k < K; ++k)
    if (dishes_[k].num_tables > 0 && allowed(k, x)) f[k] = model_.log_predictive(x, dishes_[k].members);
  const double f_new = model_.log_predictive_new(x);

  // Dish choice for a new table: log m_k + f_k, ..., log gamma + f_new (last).
  std::vector<double> dish_w(K + 1, kNegInf);
  for (int k = 0; k < K; ++k)
    if (f[k] > kNegInf) dish_w[k] = std::log(static_cast<double>(dishes_[k].num_tables)) + f[k];
  dish_w[K] = std::log(options_.gamma) + f_new;
  const double log_new_table =
      std::log(options_.alpha) + log_sum_exp(dish_w) - std::log(total_tables_ + options_.gamma);

  const auto& ts = tables_[j];
  std::vector<double> table_w(ts.size() + 1, kNegInf);
  for (size_t t = 0; t < ts.size(); ++t)
    if (ts[t].dish >= 0) table_w[t] = std::log(static_cast<double>(ts[t].items.size())) + f[ts[t].dish];
  table_w.back() = log_new_table;
  int t = sample_log_categorical(table_w);
  if (t == static_cast<int>(ts.size())) {
    const int choice = sample_log_categorical(dish_w);
    const int k = choice == K ? open_dish() : choice;
    t = open_table(j, k);
  }
  seat(j, i, t);
}

// Teh et al. Eq. 34: p(k_jt = k) ~ m_k^{-jt} f_k(x_jt), gamma f_new(x_jt) for a new dish.
void CrfSampler::sample_dish(int j, int t) {
  Table& table = tables_[j][t];
  if (table.dish < 0) return;
  std::vector<ItemRef> customers;
  for (int i : table.items) customers.push_back(ItemRef{j, i});
  std::sort(customers.begin(), customers.end());
  const int old = table.dish;
  for (const ItemRef& c : customers) remove_member(old, c);
  --dishes_[old].num_tables;
  --total_tables_;

  const int K = static_cast<int>(dishes_.size());
  std::vector<double> w(K + 1, kNegInf);
  for (int k = 0; k < K; ++k) {
    if (dishes_[k].num_tables == 0) continue;
    bool ok = true;
    for (const ItemRef& c : customers) ok = ok && allowed(k, c);
    if (ok)
      w[k] = std::log(static_cast<double>(dishes_[k].num_tables)) +
             model_.log_predictive_set(customers, dishes_[k].members);
  }
  w[K] = std::log(options_.gamma) + model_.log_predictive_set(customers, {});
  const int choice = sample_log_categorical(w);
  // Reusing the emptied dish slot for "new" keeps labels stable when a lone table stays alone.
  const int k = choice == K ? (dishes_[old].num_tables == 0 ? old : open_dish()) : choice;
  table.dish = k;
  ++dishes_[k].num_tables;
  ++total_tables_;
  for (const ItemRef& c : customers) add_member(k, c);
}

void CrfSampler::initialise(const std::vector<std::vector<int>>& initial_dishes) {
  for (auto& row : table_of_) std::fill(row.begin(), row.end(), -1);
  for (auto& ts : tables_) ts.clear();
  dishes_.clear();
  total_tables_ = 0;
  const int J = static_cast<int>(group_sizes_.size());
  std::vector<std::pair<int, int>> later;
  std::map<int, int> dish_of_label;
  for (int j = 0; j < J; ++j) {
    std::map<int, int> table_of_label;
    for (int i = 0; i < group_sizes_[j]; ++i) {
      const int label = (j < static_cast<int>(initial_dishes.size()) && i < static_cast<int>(initial_dishes[j].size()))
                            ? initial_dishes[j][i]
                            : -1;
      if (label < 0) {
        later.emplace_back(j, i);
        continue;
      }
      auto dk = dish_of_label.find(label);
      if (dk == dish_of_label.end()) dk = dish_of_label.emplace(label, open_dish()).first;
      auto tk = table_of_label.find(label);
      if (tk != table_of_label.end()) {
        if (!allowed(dk->second, ItemRef{j, i})) {
          later.emplace_back(j, i);
          continue;
        }
        seat(j, i, tk->second);
        continue;
      }
      if (dishes_[dk->second].num_tables > 0 && !allowed(dk->second, ItemRef{j, i})) {
        later.emplace_back(j, i);
        continue;
      }
      const int t = open_table(j, dk->second);
      table_of_label.emplace(label, t);
      seat(j, i, t);
    }
  }
  for (const auto& [j, i] : later) sample_table(j, i);
}

void CrfSampler::sweep() {
  const int J = static_cast<int>(group_sizes_.size());
  for (int j = 0; j < J; ++j)
    for (int i = 0; i < group_sizes_[j]; ++i) sample_table(j, i);
  if (!options_.resample_dishes) return;
  for (int j = 0; j < J; ++j)
    for (int t = 0; t < static_cast<int>(tables_[j].size()); ++t) sample_dish(j, t);
}

double CrfSampler::log_joint() const {
  const double a = options_.alpha, g = options_.gamma;
  double lp = 0;
  for (size_t j = 0; j < tables_.size(); ++j) {
    int n = 0, m = 0;
    for (const Table& t : tables_[j]) {
      if (t.dish < 0) continue;
      ++m;
      n += static_cast<int>(t.items.size());
      lp += log_gamma(static_cast<double>(t.items.size()));  // (n_jt - 1)!
    }
    lp += m * std::log(a) + log_gamma(a) - log_gamma(a + n);
  }
  int K = 0;
  for (const Dish& d : dishes_) {
    if (d.num_tables == 0) continue;
    ++K;
    lp += log_gamma(static_cast<double>(d.num_tables)) + model_.log_marginal(d.members);  // (m_k - 1)!
  }
  lp += K * std::log(g) + log_gamma(g) - log_gamma(g + total_tables_);
  return lp;
}

std::vector<std::vector<int>> CrfSampler::dishes() const {
  std::map<int, int> label;
  std::vector<std::vector<int>> out(group_sizes_.size());
  for (size_t j = 0; j < group_sizes_.size(); ++j)
    for (int i = 0; i < group_sizes_[j]; ++i) {
      const int t = table_of_[j][i];
      if (t < 0) {
        out[j].push_back(-1);
        continue;
      }
      const int k = tables_[j][t].dish;
      out[j].push_back(label.emplace(k, static_cast<int>(label.size())).first->second);
    }
  return out;
}

std::vector<std::vector<int>> CrfSampler::tables() const {
  std::vector<std::vector<int>> out(group_sizes_.size());
  for (size_t j = 0; j < group_sizes_.size(); ++j) {
    std::map<int, int> label;
    for (int i = 0; i < group_sizes_[j]; ++i) {
      const int t = table_of_[j][i];
      out[j].push_back(t < 0 ? -1 : label.emplace(t, static_cast<int>(label.size())).first->second);
    }
  }
  return out;
}

int CrfSampler::num_dishes() const {
  int K = 0;
  for (const Dish& d : dishes_) K += d.num_tables > 0;
  return K;
}

CrfResult CrfSampler::run(const std::vector<std::vector<int>>& initial_dishes) {
  CrfResult r;
  initialise(initial_dishes);
  r.trace.push_back(log_joint());
  for (int s = 0; s < options_.burn_in_sweeps; ++s) {
    sweep();
    r.trace.push_back(log_joint());
  }
  r.dish = dishes();
  r.num_dishes = num_dishes();
  r.log_joint = r.trace.back();
  for (int s = 0; s < options_.sweeps; ++s) {
    sweep();
    const double lp = log_joint();
    r.trace.push_back(lp);
    if (r.map_sweep < 0 || lp > r.log_joint) {
      r.dish = dishes();
      r.num_dishes = num_dishes();
      r.log_joint = lp;
      r.map_sweep = s;
    }
  }
  return r;
}

}  // namespace wardmap::hdp
