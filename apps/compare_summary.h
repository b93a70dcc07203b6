// The summary `wardmap compare` prints under its table: on how many sequences the hierarchical
// association meets each target of an object map (accuracy, object count, position error) and
// beats the HDP-only baseline, naming the sequences that miss.
#pragma once

#include <string>
#include <vector>

#include "semantics/object_metrics.h"

namespace wardmap::apps {

struct CompareRow {
  std::string sequence;
  semantics::ObjectEvaluation hierarchical, hdp_only;
};

struct CompareTargets {
  double min_accuracy = 97.0;        // % association accuracy, at least
  double max_position_error = 0.15;  // m, mean landmark position error, at most
};

// Lines of text, each ending in a newline; empty for no rows.
std::string format_compare_summary(const std::vector<CompareRow>& rows, const CompareTargets& targets);

}  // namespace wardmap::apps
