#include "slam/eval/trajectory_eval.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "slam/core/umeyama.h"

namespace wardmap::slam::eval {

Alignment parse_alignment(const std::string& name) {
  if (name == "sim3") return Alignment::Sim3;
  if (name == "se3") return Alignment::SE3;
  if (name == "none") return Alignment::None;
  throw std::invalid_argument("unknown alignment '" + name + "' (allowed: sim3, se3, none)");
}

std::string to_string(Alignment a) {
  switch (a) {
    case Alignment::Sim3: return "sim3";
    case Alignment::SE3: return "se3";
    case Alignment::None: return "none";
  }
  return "?";
}

std::vector<std::pair<size_t, size_t>> associate(const Trajectory& gt, const Trajectory& est,
                                                 const AssociationOptions& options) {
  std::vector<std::pair<size_t, size_t>> pairs;
  if (options.by_index || gt.indexed || est.indexed) {
    // Indexed files carry frame numbers; timed ones are paired by position in the file.
    if (gt.indexed && est.indexed) {
      size_t i = 0, j = 0;
      while (i < gt.size() && j < est.size()) {
        if (gt.timestamps[i] < est.timestamps[j]) ++i;
        else if (est.timestamps[j] < gt.timestamps[i]) ++j;
        else pairs.emplace_back(i++, j++);
      }
    } else {
      for (size_t i = 0; i < std::min(gt.size(), est.size()); ++i) pairs.emplace_back(i, i);
    }
    return pairs;
  }
  // Candidate (dt, gt, est) for each estimate's nearest ground truth, then greedy by dt.
  struct Cand {
    double dt;
    size_t g, e;
  };
  std::vector<Cand> cands;
  const auto& ts = gt.timestamps;
  for (size_t e = 0; e < est.size(); ++e) {
    const double t = est.timestamps[e];
    auto it = std::lower_bound(ts.begin(), ts.end(), t);
    for (auto c : {it, it == ts.begin() ? it : it - 1}) {
      if (c == ts.end()) continue;
      const double dt = std::abs(*c - t);
      if (dt <= options.max_dt) cands.push_back({dt, static_cast<size_t>(c - ts.begin()), e});
    }
  }
  std::sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) {
    return a.dt != b.dt ? a.dt < b.dt : (a.e != b.e ? a.e < b.e : a.g < b.g);
  });
  std::vector<char> gt_used(gt.size(), 0), est_used(est.size(), 0);
  for (const Cand& c : cands) {
    if (gt_used[c.g] || est_used[c.e]) continue;
    gt_used[c.g] = est_used[c.e] = 1;
    pairs.emplace_back(c.g, c.e);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

ErrorStats error_stats(std::vector<double> errors) {
  ErrorStats s;
  if (errors.empty()) return s;
  const double n = static_cast<double>(errors.size());
  double sum = 0, sq = 0;
  for (double e : errors) sum += e, sq += e * e;
  s.mean = sum / n;
  s.rmse = std::sqrt(sq / n);
  s.std = std::sqrt(std::max(0.0, sq / n - s.mean * s.mean));
  std::sort(errors.begin(), errors.end());
  s.min = errors.front();
  s.max = errors.back();
  const size_t m = errors.size() / 2;
  s.median = errors.size() % 2 ? errors[m] : 0.5 * (errors[m - 1] + errors[m]);
  return s;
}

AteResult compute_ate(const Trajectory& gt, const Trajectory& est, const std::vector<std::pair<size_t, size_t>>& pairs,
                      Alignment alignment) {
  AteResult r;
  r.pairs = pairs.size();
  r.alignment = alignment;
  if (pairs.empty()) throw std::invalid_argument("no pose pairs: the estimate and the ground truth share no timestamps");
  Eigen::Matrix3Xd src(3, pairs.size()), dst(3, pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    dst.col(k) = gt.poses[pairs[k].first].translation();
    src.col(k) = est.poses[pairs[k].second].translation();
  }
  if (alignment == Alignment::Sim3) r.transform = umeyama_sim3(src, dst);
  else if (alignment == Alignment::SE3) r.transform = umeyama_se3(src, dst);
  r.scale = r.transform.scale();
  r.errors.resize(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k)
    r.errors[k] = (r.transform * Eigen::Vector3d(src.col(k)) - dst.col(k)).norm();
  r.stats = error_stats(r.errors);
  return r;
}

RpeResult compute_rpe(const Trajectory& gt, const Trajectory& est, const std::vector<std::pair<size_t, size_t>>& pairs,
                      int delta, double scale) {
  if (delta < 1) throw std::invalid_argument("RPE frame gap must be at least 1");
  RpeResult r;
  r.delta = delta;
  std::vector<double> et, er;
  for (size_t k = 0; k + delta < pairs.size(); ++k) {
    const SE3& g0 = gt.poses[pairs[k].first];
    const SE3& g1 = gt.poses[pairs[k + delta].first];
    const SE3& e0 = est.poses[pairs[k].second];
    const SE3& e1 = est.poses[pairs[k + delta].second];
    const SE3 dg = g0.inverse() * g1;
    SE3 de = e0.inverse() * e1;
    de = SE3(de.rotation(), de.translation() * scale);
    const SE3 err = dg.inverse() * de;
    et.push_back(err.translation().norm());
    er.push_back(rotation_angle(err.rotation()) * 180.0 / M_PI);
  }
  r.count = et.size();
  r.translation = error_stats(et);
  r.rotation_deg = error_stats(er);
  return r;
}

ScaleDriftResult compute_scale_drift(const Trajectory& gt, const Trajectory& est,
                                     const std::vector<std::pair<size_t, size_t>>& pairs, double window_seconds,
                                     double min_chord) {
  if (!(window_seconds > 0)) throw std::invalid_argument("scale drift window must be positive");
  ScaleDriftResult r;
  r.window_seconds = window_seconds;
  if (gt.indexed || pairs.size() < 2) return r;
  const double t0 = gt.timestamps[pairs.front().first];
  std::vector<double> raw;
  for (size_t i = 0, j = 1; j < pairs.size(); ++j) {
    const double ti = gt.timestamps[pairs[i].first], tj = gt.timestamps[pairs[j].first];
    if (tj - ti < window_seconds - 1e-9) continue;
    const double g = (gt.poses[pairs[j].first].translation() - gt.poses[pairs[i].first].translation()).norm();
    const double e = (est.poses[pairs[j].second].translation() - est.poses[pairs[i].second].translation()).norm();
    if (g >= min_chord) {
      r.times.push_back(0.5 * (ti + tj) - t0);
      raw.push_back(e / g);
    }
    i = j;
  }
  if (raw.size() < 3) return r;
  double mean = 0;
  for (double x : raw) mean += x;
  mean /= static_cast<double>(raw.size());
  if (!(mean > 0)) return r;
  for (double x : raw) r.ratios.push_back(x / mean);
  double tm = 0, ym = 0;
  for (size_t k = 0; k < raw.size(); ++k) tm += r.times[k], ym += r.ratios[k];
  tm /= static_cast<double>(raw.size());
  ym /= static_cast<double>(raw.size());
  double sxy = 0, sxx = 0;
  for (size_t k = 0; k < raw.size(); ++k) {
    sxy += (r.times[k] - tm) * (r.ratios[k] - ym);
    sxx += (r.times[k] - tm) * (r.times[k] - tm);
  }
  if (!(sxx > 0)) return r;
  const double slope = sxy / sxx;
  double ss = 0;
  for (size_t k = 0; k < raw.size(); ++k) {
    const double e = r.ratios[k] - (ym + slope * (r.times[k] - tm));
    ss += e * e;
  }
  r.slope_percent_per_second = 100.0 * slope;
  r.slope_se_percent_per_second = 100.0 * std::sqrt(ss / static_cast<double>(raw.size() - 2) / sxx);
  r.change_percent = r.slope_percent_per_second * (r.times.back() - r.times.front());
  r.valid = true;
  return r;
}

double median_gap(const std::vector<double>& t) {
  if (t.size() < 2) return 0.0;
  std::vector<double> g(t.size() - 1);
  for (size_t i = 0; i + 1 < t.size(); ++i) g[i] = t[i + 1] - t[i];
  std::nth_element(g.begin(), g.begin() + g.size() / 2, g.end());
  return g[g.size() / 2];
}

double tracking_rate(const Trajectory& gt, const Trajectory& est, const AssociationOptions& options) {
  if (gt.empty() || est.empty()) return 0.0;
  // Duration each ground-truth sample stands for: the gap to the next one (the last: the median gap).
  const double gt_gap = median_gap(gt.timestamps);
  std::vector<double> span(gt.size(), gt_gap > 0 ? gt_gap : 1.0);
  for (size_t i = 0; i + 1 < gt.size(); ++i) span[i] = gt.timestamps[i + 1] - gt.timestamps[i];
  const bool by_index = options.by_index || gt.indexed || est.indexed;
  if (by_index && gt.indexed != est.indexed)  // one side has no time: paired by position
    return 100.0 * static_cast<double>(std::min(gt.size(), est.size())) / static_cast<double>(gt.size());
  const double window = by_index ? 0.0 : std::max(options.max_dt, 0.5 * median_gap(est.timestamps));
  double tracked = 0, total = 0;
  const auto& te = est.timestamps;
  for (size_t i = 0; i < gt.size(); ++i) {
    total += span[i];
    const double t = gt.timestamps[i];
    auto it = std::lower_bound(te.begin(), te.end(), t - window - 1e-9);
    if (it != te.end() && *it <= t + window + 1e-9) tracked += span[i];
  }
  return 100.0 * tracked / total;
}

}  // namespace wardmap::slam::eval
