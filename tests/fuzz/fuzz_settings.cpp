// Fuzz target: a settings file (ORB-SLAM3 keys and wardmap's sections), as `--settings` gives it,
// read as run reads it: the camera, then the tracking/mapping, semantics and detection options. An
// input whose first line is "#set KEY=VALUE" (a YAML comment) also gives that line as `--set`.
#include <string>
#include <vector>

#include "semantics/detection/detector_options.h"
#include "semantics/options.h"
#include "slam/front/front_options.h"
#include "slam/io/settings.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto file = fuzz::write_input("settings.yaml", text);
  fuzz::refuses_only_with_input_error("settings", [&] {
    std::vector<slam::io::SettingOverride> overrides;
    if (text.rfind("#set ", 0) == 0)
      overrides.push_back(slam::io::parse_setting_override(text.substr(5, text.find('\n') - 5)));
    const slam::io::Settings settings = slam::io::load_settings(file, overrides);
    slam::load_front_options(settings);
    semantics::load_semantic_options(settings.section("semantics"), file);
    semantics::detector_options_from_yaml(settings.section("detection"), file);
  });
  return 0;
}
