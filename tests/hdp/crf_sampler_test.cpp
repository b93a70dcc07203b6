#include "hdp/crf_sampler.h"
#include "tests/hdp/normal_model.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

namespace wardmap::hdp {
namespace {

struct Toy {
  std::vector<std::vector<Eigen::VectorXd>> data;
  std::vector<std::vector<int>> truth;
  std::vector<int> sizes;
};

// Four 2-D clusters (sigma 1, 10 apart) over 10 groups; each group sees 2-4 of them, 1-2 items each
// (or exactly one per cluster when one_per_cluster).
Toy make_toy(std::uint64_t seed, bool one_per_cluster) {
  const Eigen::Vector2d centres[4] = {{0, 0}, {10, 0}, {0, 10}, {10, 10}};
  Gauss g(seed);
  Toy toy;
  for (int j = 0; j < 10; ++j) {
    std::vector<Eigen::VectorXd> items;
    std::vector<int> labels;
    for (int k = 0; k < 4; ++k) {
      if ((j + k) % 5 == 4) continue;  // every group misses some clusters, every cluster spans groups
      const int copies = one_per_cluster ? 1 : 1 + (j * 7 + k) % 2;
      for (int c = 0; c < copies; ++c) {
        items.push_back(centres[k] + Eigen::Vector2d(g(), g()));
        labels.push_back(k);
      }
    }
    toy.sizes.push_back(static_cast<int>(items.size()));
    toy.data.push_back(items);
    toy.truth.push_back(labels);
  }
  return toy;
}

double adjusted_rand_index(const std::vector<std::vector<int>>& a, const std::vector<std::vector<int>>& b) {
  std::map<std::pair<int, int>, double> n;
  std::map<int, double> ra, rb;
  double total = 0;
  for (size_t j = 0; j < a.size(); ++j)
    for (size_t i = 0; i < a[j].size(); ++i) {
      n[{a[j][i], b[j][i]}] += 1;
      ra[a[j][i]] += 1;
      rb[b[j][i]] += 1;
      total += 1;
    }
  auto c2 = [](double x) { return x * (x - 1) / 2; };
  double index = 0, sa = 0, sb = 0;
  for (const auto& e : n) index += c2(e.second);
  for (const auto& e : ra) sa += c2(e.second);
  for (const auto& e : rb) sb += c2(e.second);
  const double expected = sa * sb / c2(total), max_index = 0.5 * (sa + sb);
  return (index - expected) / (max_index - expected);
}

NormalModel toy_model(const Toy& toy) { return NormalModel(toy.data, 1.0, 10.0, Eigen::Vector2d(5, 5)); }

TEST(CrfSampler, MapRecoversTheTruePartition) {
  for (std::uint64_t data_seed : {1u, 2u, 3u}) {
    const Toy toy = make_toy(data_seed, false);
    const NormalModel model = toy_model(toy);
    CrfOptions o;
    o.seed = 100 + data_seed;
    CrfSampler sampler(model, toy.sizes, o);
    const CrfResult r = sampler.run();
    EXPECT_EQ(r.num_dishes, 4) << "data seed " << data_seed;
    EXPECT_GE(adjusted_rand_index(r.dish, toy.truth), 0.95) << "data seed " << data_seed;
    EXPECT_EQ(r.trace.size(), static_cast<size_t>(1 + o.burn_in_sweeps + o.sweeps));
    EXPECT_GE(r.map_sweep, 0);
    EXPECT_DOUBLE_EQ(r.log_joint, r.trace[1 + o.burn_in_sweeps + r.map_sweep]);
  }
}

TEST(CrfSampler, SameSeedSameResultOtherSeedsDiffer) {
  const Toy toy = make_toy(4, false);
  const NormalModel model = toy_model(toy);
  CrfOptions o;
  o.seed = 77;
  const CrfResult a = CrfSampler(model, toy.sizes, o).run();
  const CrfResult b = CrfSampler(model, toy.sizes, o).run();
  EXPECT_EQ(a.dish, b.dish);
  EXPECT_EQ(a.trace, b.trace);  // bit for bit

  // The intermediate (table-level) state after one sweep varies with the seed.
  std::set<std::vector<std::vector<int>>> seen;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    o.seed = seed;
    CrfSampler s(model, toy.sizes, o);
    s.initialise();
    s.sweep();
    seen.insert(s.tables());
  }
  EXPECT_GT(seen.size(), 1u);
}

TEST(CrfSampler, CannotLinkWithinGroupIsRespected) {
  // One item per cluster per group, plus a second item of cluster 0 in groups 0 and 5: with the
  // constraint these two can never share a dish with their group mate.
  Toy toy = make_toy(5, true);
  for (int j : {0, 5}) {
    toy.data[j].push_back(toy.data[j][0] + Eigen::Vector2d(0.1, -0.1));
    toy.truth[j].push_back(4);  // a distinct object in the truth
    ++toy.sizes[j];
  }
  const NormalModel model = toy_model(toy);
  CrfOptions o;
  o.cannot_link_within_group = true;
  o.seed = 3;
  CrfSampler sampler(model, toy.sizes, o);
  sampler.initialise();
  for (int s = 0; s < 30; ++s) {
    sampler.sweep();
    for (const auto& row : sampler.dishes()) {
      const std::set<int> distinct(row.begin(), row.end());
      ASSERT_EQ(distinct.size(), row.size()) << "sweep " << s;
    }
  }
  const CrfResult r = sampler.run();
  for (const auto& row : r.dish) EXPECT_EQ(std::set<int>(row.begin(), row.end()).size(), row.size());
  // Without the extra items this is the clean 4-cluster case.
  const Toy clean = make_toy(5, true);
  const NormalModel clean_model = toy_model(clean);
  const CrfResult rc = CrfSampler(clean_model, clean.sizes, o).run();
  EXPECT_EQ(rc.num_dishes, 4);
  EXPECT_GE(adjusted_rand_index(rc.dish, clean.truth), 0.95);
}

TEST(CrfSampler, ModelCannotLinkHookIsRespected) {
  const Toy toy = make_toy(6, true);
  NormalModel model = toy_model(toy);
  model.forbidden = {{ItemRef{0, 0}, ItemRef{1, 0}}};  // same true cluster, forced apart
  CrfOptions o;
  o.seed = 9;
  const CrfResult r = CrfSampler(model, toy.sizes, o).run();
  EXPECT_NE(r.dish[0][0], r.dish[1][0]);
  EXPECT_EQ(toy.truth[0][0], toy.truth[1][0]);
}

TEST(CrfSampler, WarmStartKeepsAGoodStateAndFixesConflicts) {
  const Toy toy = make_toy(7, false);
  const NormalModel model = toy_model(toy);
  CrfOptions o;
  o.burn_in_sweeps = 0;
  o.sweeps = 0;
  const CrfResult r = CrfSampler(model, toy.sizes, o).run(toy.truth);
  EXPECT_EQ(r.dish, CrfSampler(model, toy.sizes, o).run(toy.truth).dish);
  EXPECT_DOUBLE_EQ(adjusted_rand_index(r.dish, toy.truth), 1.0);
  // Under the within-group constraint the duplicated labels must be re-seated elsewhere.
  o.cannot_link_within_group = true;
  CrfSampler s(model, toy.sizes, o);
  s.initialise(toy.truth);
  for (const auto& row : s.dishes()) EXPECT_EQ(std::set<int>(row.begin(), row.end()).size(), row.size());
}

// Restricted-growth strings: every set partition of n elements.
std::vector<std::vector<int>> set_partitions(int n) {
  std::vector<std::vector<int>> out;
  std::vector<int> a(n, 0);
  std::function<void(int, int)> rec = [&](int i, int max_label) {
    if (i == n) {
      out.push_back(a);
      return;
    }
    for (int l = 0; l <= max_label + 1; ++l) {
      a[i] = l;
      rec(i + 1, std::max(max_label, l));
    }
  };
  if (n == 0)
    out.push_back({});
  else
    rec(0, -1);
  return out;
}

// Exact posterior over dish partitions by enumerating every (table, dish) state of a tiny problem.
std::map<std::vector<std::vector<int>>, double> exact_posterior(const CrfModel& model, const std::vector<int>& sizes,
                                                                double alpha, double gamma, bool cannot_link) {
  std::map<std::vector<std::vector<int>>, double> post;
  std::vector<std::vector<std::vector<int>>> per_group;
  for (int n : sizes) per_group.push_back(set_partitions(n));
  std::function<void(size_t, std::vector<std::vector<int>>&)> over_tables = [&](size_t j,
                                                                                std::vector<std::vector<int>>& t) {
    if (j < sizes.size()) {
      for (const auto& p : per_group[j]) {
        t.push_back(p);
        over_tables(j + 1, t);
        t.pop_back();
      }
      return;
    }
    // Tables, globally numbered; their customers.
    std::vector<std::vector<ItemRef>> customers;
    double lp = 0;
    for (size_t g = 0; g < t.size(); ++g) {
      const int m = t[g].empty() ? 0 : *std::max_element(t[g].begin(), t[g].end()) + 1;
      std::vector<std::vector<ItemRef>> c(m);
      for (int i = 0; i < static_cast<int>(t[g].size()); ++i) c[t[g][i]].push_back(ItemRef{static_cast<int>(g), i});
      for (const auto& cc : c) lp += std::lgamma(static_cast<double>(cc.size()));
      lp += m * std::log(alpha) + std::lgamma(alpha) - std::lgamma(alpha + t[g].size());
      customers.insert(customers.end(), c.begin(), c.end());
    }
    const int T = static_cast<int>(customers.size());
    for (const auto& k : set_partitions(T)) {
      const int K = *std::max_element(k.begin(), k.end()) + 1;
      std::vector<std::vector<ItemRef>> members(K);
      std::vector<int> m(K, 0);
      for (int tt = 0; tt < T; ++tt) {
        ++m[k[tt]];
        members[k[tt]].insert(members[k[tt]].end(), customers[tt].begin(), customers[tt].end());
      }
      double l = lp + K * std::log(gamma) + std::lgamma(gamma) - std::lgamma(gamma + T);
      bool ok = true;
      for (int d = 0; d < K; ++d) {
        std::sort(members[d].begin(), members[d].end());
        for (size_t a = 0; a + 1 < members[d].size(); ++a)
          if (cannot_link && members[d][a].group == members[d][a + 1].group) ok = false;
        l += std::lgamma(static_cast<double>(m[d])) + model.log_marginal(members[d]);
      }
      if (!ok) continue;
      // Canonical dish labels of the items.
      std::vector<std::vector<int>> lab(sizes.size());
      for (size_t g = 0; g < sizes.size(); ++g) lab[g].assign(sizes[g], -1);
      for (int d = 0; d < K; ++d)
        for (const ItemRef& r : members[d]) lab[r.group][r.item] = d;
      std::map<int, int> canon;
      for (auto& row : lab)
        for (int& v : row) v = canon.emplace(v, static_cast<int>(canon.size())).first->second;
      post[lab] += std::exp(l);
    }
  };
  std::vector<std::vector<int>> t;
  over_tables(0, t);
  double z = 0;
  for (const auto& e : post) z += e.second;
  for (auto& e : post) e.second /= z;
  return post;
}

void expect_matches_exact_posterior(bool resample_dishes, bool cannot_link) {
  // 1-D items, clusters overlapping enough that several partitions have real mass.
  const std::vector<std::vector<Eigen::VectorXd>> data = {
      {Eigen::VectorXd::Constant(1, 0.0), Eigen::VectorXd::Constant(1, 1.5)},
      {Eigen::VectorXd::Constant(1, 0.4), Eigen::VectorXd::Constant(1, 2.0)},
      {Eigen::VectorXd::Constant(1, 1.0)}};
  const std::vector<int> sizes = {2, 2, 1};
  const NormalModel model(data, 1.0, 2.0, Eigen::VectorXd::Constant(1, 1.0));
  CrfOptions o;
  o.alpha = 1.3;
  o.gamma = 0.8;
  o.seed = 12345;
  o.resample_dishes = resample_dishes;
  o.cannot_link_within_group = cannot_link;
  const auto exact = exact_posterior(model, sizes, o.alpha, o.gamma, cannot_link);
  CrfSampler s(model, sizes, o);
  s.initialise();
  std::map<std::vector<std::vector<int>>, double> freq;
  const int n = 60000;
  for (int i = 0; i < 200; ++i) s.sweep();
  for (int i = 0; i < n; ++i) {
    s.sweep();
    freq[s.dishes()] += 1.0 / n;
  }
  double worst = 0;
  for (const auto& [p, pr] : exact) worst = std::max(worst, std::abs(pr - freq[p]));
  for (const auto& [p, f] : freq) EXPECT_TRUE(exact.count(p)) << "sampled a state of zero probability";
  EXPECT_LT(worst, 0.015) << "resample_dishes " << resample_dishes << " cannot_link " << cannot_link;
}

TEST(CrfSampler, GibbsChainMatchesTheExactPosterior) {
  expect_matches_exact_posterior(true, false);
  expect_matches_exact_posterior(false, false);
  expect_matches_exact_posterior(true, true);
}

TEST(CrfSampler, OwnRandomNumbersAreLibraryIndependent) {
  CrfOptions o;
  o.seed = 5489;  // mt19937_64's first output for this seed is fixed by the C++ standard
  const Toy toy = make_toy(1, true);
  const NormalModel model = toy_model(toy);
  CrfSampler s(model, toy.sizes, o);
  EXPECT_EQ(s.uniform01(), static_cast<double>(14514284786278117030ull >> 11) * 0x1.0p-53);
  // Categorical draws follow the weights and never pick an impossible option.
  const std::vector<double> w = {std::log(1.0), -std::numeric_limits<double>::infinity(), std::log(3.0)};
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 40000; ++i) ++counts[s.sample_log_categorical(w)];
  EXPECT_EQ(counts[1], 0);
  EXPECT_NEAR(counts[2] / 40000.0, 0.75, 0.01);
}

TEST(CrfSampler, OptionsNameTheBadField) {
  CrfOptions o;
  o.gamma = 0;
  ASSERT_TRUE(o.validate().has_value());
  EXPECT_NE(o.validate()->find("gamma"), std::string::npos);
  const Toy toy = make_toy(1, true);
  const NormalModel model = toy_model(toy);
  EXPECT_THROW(CrfSampler(model, toy.sizes, o), std::invalid_argument);
}

}  // namespace
}  // namespace wardmap::hdp
