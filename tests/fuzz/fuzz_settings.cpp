// Fuzz target: a settings file (ORB-SLAM3 keys and wardmap's sections), as `--settings` gives it.
#include "slam/io/settings.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  const auto file = fuzz::write_input("settings.yaml", data, size);
  fuzz::refuses_only_with_input_error("load_settings", [&] { slam::io::load_settings(file); });
  return 0;
}
