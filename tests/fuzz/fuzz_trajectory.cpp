// Fuzz target: a pose file (TUM or KITTI, format detected), as `wardmap eval` and the readers take it;
// and the same bytes as a synthetic sequence's challenges.txt (numbers and a word a line), as
// `wardmap run` reads it.
#include "slam/eval/challenge_recovery.h"
#include "slam/io/trajectory_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  const auto file = fuzz::write_input("poses.txt", data, size);
  fuzz::refuses_only_with_input_error("read_trajectory", [&] { slam::io::read_trajectory(file); });
  fuzz::refuses_only_with_input_error("read_challenges", [&] { slam::eval::read_challenges(file); });
  return 0;
}
