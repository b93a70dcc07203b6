#include "slam/place/place_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wardmap::slam::place {

namespace {

template <typename T>
void check_range(T value, T lo, T hi, const char* key) {
  if (!(value >= lo && value <= hi))
    throw std::invalid_argument(std::string(key) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                "], got " + std::to_string(value));
}

}  // namespace

void PlaceOptions::validate() const { validate(PlaceOptionNames{}); }

void PlaceOptions::validate(const PlaceOptionNames& names) const {
  check_range(branching, 2, 64, names.branching);
  check_range(levels, 1, 8, names.levels);
  check_range(max_iterations, 1, 1000, names.max_iterations);
  check_range(min_common_ratio, 0.0, 1.0, "place.min_common_ratio");
  const double max_words = 16777216.0;  // word ids and file sizes stay small
  if (std::pow(static_cast<double>(branching), levels) > max_words)
    throw std::invalid_argument(std::string(names.levels) + ": at most 16777216 words (" + names.branching +
                                " to the power " + names.levels + "), got " + std::to_string(branching) + "^" +
                                std::to_string(levels));
}

}  // namespace wardmap::slam::place
