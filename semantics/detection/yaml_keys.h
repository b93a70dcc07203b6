// Small helpers for reading YAML keys with errors that name the file, the full key and its line.
// Internal to the detection module.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "slam/core/errors.h"

namespace wardmap::semantics::detail {

inline long yaml_line(const YAML::Node& n) { return n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }

inline std::string yaml_text(const YAML::Node& n) {
  std::ostringstream s;
  s << n;
  return s.str();
}

// Reads node as T; throws InputError "key 'full_key': expected <what>, got '<text>'".
template <class T>
T yaml_as(const YAML::Node& n, const std::string& full_key, const std::filesystem::path& file, const char* what) {
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(file.string(), "key '" + full_key + "': expected " + what + ", got '" + yaml_text(n) + "'",
                     yaml_line(n));
  }
}

// Overwrites value when parent[key] exists.
template <class T>
void yaml_read_optional(const YAML::Node& parent, const std::string& prefix, const std::string& key, T& value,
                        const std::filesystem::path& file, const char* what) {
  if (!parent || !parent.IsMap()) return;
  const YAML::Node n = parent[key];
  if (n) value = yaml_as<T>(n, prefix.empty() ? key : prefix + "." + key, file, what);
}

// parent[key], or InputError "missing key 'full_key'".
inline YAML::Node yaml_required(const YAML::Node& parent, const std::string& prefix, const std::string& key,
                                const std::filesystem::path& file) {
  const std::string full = prefix.empty() ? key : prefix + "." + key;
  if (!parent || !parent.IsMap() || !parent[key])
    throw InputError(file.string(), "missing key '" + full + "'", parent ? yaml_line(parent) : 0);
  return parent[key];
}

}  // namespace wardmap::semantics::detail
