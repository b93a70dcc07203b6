// Test helper: loading semantic settings that hold a bad value fails with an error naming its key.
#pragma once

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <exception>
#include <string>

#include "semantics/options.h"

namespace wardmap::test {

inline void expect_load_error_names(const std::string& yaml, const std::string& key) {
  try {
    semantics::load_semantic_options(YAML::Load(yaml), "s.yaml");
    ADD_FAILURE() << "accepted: " << yaml;
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

}  // namespace wardmap::test
