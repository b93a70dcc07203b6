// Fuzz target: a place-recognition vocabulary file (`--vocabulary`), binary.
#include "slam/place/vocabulary.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  const auto file = fuzz::write_input("vocabulary.bin", data, size);
  fuzz::refuses_only_with_input_error("Vocabulary::load", [&] { slam::place::Vocabulary::load(file); });
  return 0;
}
