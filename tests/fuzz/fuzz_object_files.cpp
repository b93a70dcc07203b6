// Fuzz target: objects.json (a sequence's truth or a run's map) and measurements.jsonl, as
// `wardmap eval-objects` reads them; the same bytes go to both readers.
#include "semantics/object_map_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  const auto objects = fuzz::write_input("objects.json", data, size);
  fuzz::refuses_only_with_input_error("read_objects_json", [&] { semantics::read_objects_json(objects); });
  const auto measurements = fuzz::write_input("measurements.jsonl", data, size);
  fuzz::refuses_only_with_input_error("read_measurements_jsonl",
                                      [&] { semantics::read_measurements_jsonl(measurements); });
  return 0;
}
