#include "apps/compare_summary.h"

#include <spdlog/fmt/fmt.h>

#include <functional>

namespace wardmap::apps {

namespace {

// "  what: N of M", then the sequences for which `met` is false, with `why` of each.
std::string count_line(const std::vector<CompareRow>& rows, const std::string& what,
                       const std::function<bool(const CompareRow&)>& met,
                       const std::function<std::string(const CompareRow&)>& why) {
  std::string misses;
  int n = 0;
  for (const auto& r : rows) {
    if (met(r)) {
      ++n;
      continue;
    }
    misses += (misses.empty() ? "; not on " : ", ") + r.sequence + " (" + why(r) + ")";
  }
  return "  " + what + ": " + std::to_string(n) + " of " + std::to_string(rows.size()) + misses + "\n";
}

}  // namespace

std::string format_compare_summary(const std::vector<CompareRow>& rows, const CompareTargets& targets) {
  if (rows.empty()) return {};
  const auto accuracy = [](const CompareRow& r) {
    return fmt::format("{:.2f} %", r.hierarchical.association_accuracy);
  };
  const auto against_baseline = [](const CompareRow& r) {
    return fmt::format("{:.2f} against {:.2f} %", r.hierarchical.association_accuracy, r.hdp_only.association_accuracy);
  };
  std::string s = "hierarchical association on " + std::to_string(rows.size()) + " sequence" +
                  (rows.size() == 1 ? "" : "s") + ":\n";
  s += count_line(
      rows, fmt::format("accuracy >= {:g} %", targets.min_accuracy),
      [&](const CompareRow& r) { return r.hierarchical.association_accuracy >= targets.min_accuracy; }, accuracy);
  s += count_line(
      rows, "object count equal to Object_GT",
      [](const CompareRow& r) { return r.hierarchical.landmarks == r.hierarchical.objects_seen; },
      [](const CompareRow& r) {
        return std::to_string(r.hierarchical.landmarks) + " for " + std::to_string(r.hierarchical.objects_seen);
      });
  s += count_line(
      rows, fmt::format("mean position error <= {:g} m", targets.max_position_error),
      [&](const CompareRow& r) { return r.hierarchical.position_error_mean <= targets.max_position_error; },
      [](const CompareRow& r) { return fmt::format("{:.3f} m", r.hierarchical.position_error_mean); });
  // Two runs at 100 % cannot differ in accuracy: those ties are counted apart, with their
  // position errors.
  const auto tied = [](const CompareRow& r) {
    return r.hierarchical.association_accuracy == r.hdp_only.association_accuracy;
  };
  s += count_line(
      rows, "accuracy above HDP-only",
      [](const CompareRow& r) { return r.hierarchical.association_accuracy > r.hdp_only.association_accuracy; },
      against_baseline);
  int ties = 0, ties_closer = 0;
  for (const auto& r : rows)
    if (tied(r)) {
      ++ties;
      if (r.hierarchical.position_error_mean < r.hdp_only.position_error_mean) ++ties_closer;
    }
  if (ties > 0)
    s += "  of those not above, tied with HDP-only: " + std::to_string(ties) + ", " + std::to_string(ties_closer) +
         " of them with the smaller position error\n";
  s += count_line(
      rows, "mean position error smaller than HDP-only's",
      [](const CompareRow& r) { return r.hierarchical.position_error_mean < r.hdp_only.position_error_mean; },
      [](const CompareRow& r) {
        return fmt::format("{:.3f} against {:.3f} m", r.hierarchical.position_error_mean,
                           r.hdp_only.position_error_mean);
      });
  double acc = 0, acc_hdp = 0, err = 0, err_hdp = 0;
  for (const auto& r : rows) {
    acc += r.hierarchical.association_accuracy / rows.size();
    acc_hdp += r.hdp_only.association_accuracy / rows.size();
    err += r.hierarchical.position_error_mean / rows.size();
    err_hdp += r.hdp_only.position_error_mean / rows.size();
  }
  s += fmt::format("  means, hierarchical / HDP-only: accuracy {:.2f} / {:.2f} %, position error {:.3f} / {:.3f} m\n",
                   acc, acc_hdp, err, err_hdp);
  return s;
}

}  // namespace wardmap::apps
