// Fuzz target: a synthetic sequence's annotations.jsonl (the annotations detector's input).
#include "semantics/detection/annotations_detector.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  const auto file = fuzz::write_input("annotations.jsonl", data, size);
  fuzz::refuses_only_with_input_error("read_annotations", [&] { semantics::read_annotations(file); });
  return 0;
}
