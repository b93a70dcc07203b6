#include "apps/compare_summary.h"

#include <gtest/gtest.h>

namespace wardmap::apps {
namespace {

CompareRow row(const std::string& name, double acc, int landmarks, int seen, double err, double acc_hdp,
               double err_hdp) {
  CompareRow r;
  r.sequence = name;
  r.hierarchical.association_accuracy = acc;
  r.hierarchical.landmarks = landmarks;
  r.hierarchical.objects_seen = seen;
  r.hierarchical.position_error_mean = err;
  r.hdp_only.association_accuracy = acc_hdp;
  r.hdp_only.landmarks = seen;
  r.hdp_only.objects_seen = seen;
  r.hdp_only.position_error_mean = err_hdp;
  return r;
}

TEST(CompareSummary, NoRowsNoSummary) { EXPECT_EQ(format_compare_summary({}, {}), ""); }

TEST(CompareSummary, CountsEachTargetAndNamesTheMisses) {
  const std::vector<CompareRow> rows = {
      row("ward_slow_1", 99.5, 18, 18, 0.06, 96.0, 0.13),      // meets every target, above the baseline
      row("aisle_quick_2", 100.0, 10, 11, 0.08, 100.0, 0.12),  // a count short; tied at 100 %, closer
      row("aisle_slow_3", 96.5, 13, 13, 0.20, 97.0, 0.18),     // below on accuracy and position error
  };
  const std::string s = format_compare_summary(rows, {});
  EXPECT_EQ(s,
            "hierarchical association on 3 sequences:\n"
            "  accuracy >= 97 %: 2 of 3; not on aisle_slow_3 (96.50 %)\n"
            "  object count equal to Object_GT: 2 of 3; not on aisle_quick_2 (10 for 11)\n"
            "  mean position error <= 0.15 m: 2 of 3; not on aisle_slow_3 (0.200 m)\n"
            "  accuracy above HDP-only: 1 of 3; not on aisle_quick_2 (100.00 against 100.00 %), aisle_slow_3 (96.50 "
            "against 97.00 %)\n"
            "  of those not above, tied with HDP-only: 1, 1 of them with the smaller position error\n"
            "  mean position error smaller than HDP-only's: 2 of 3; not on aisle_slow_3 (0.200 against 0.180 m)\n"
            "  means, hierarchical / HDP-only: accuracy 98.67 / 97.67 %, position error 0.113 / 0.143 m\n");
}

TEST(CompareSummary, TargetsAreTheCallers) {
  const std::vector<CompareRow> rows = {row("ward_slow_1", 99.5, 18, 18, 0.06, 96.0, 0.13)};
  const std::string s = format_compare_summary(rows, {99.9, 0.05});
  EXPECT_NE(s.find("hierarchical association on 1 sequence:\n"), std::string::npos) << s;
  EXPECT_NE(s.find("accuracy >= 99.9 %: 0 of 1; not on ward_slow_1 (99.50 %)"), std::string::npos) << s;
  EXPECT_NE(s.find("mean position error <= 0.05 m: 0 of 1; not on ward_slow_1 (0.060 m)"), std::string::npos) << s;
  EXPECT_EQ(s.find("tied"), std::string::npos) << s;
}

}  // namespace
}  // namespace wardmap::apps
