// Fuzz target: a model description (models/*.yaml: weights file, input, preprocessing, decoder,
// classes, landmark sets), with the shipped class list and landmark sets beside it so that the
// fuzzer reaches the keys after `classes`.
#include <filesystem>

#include "semantics/detection/model_description.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  static const bool classes_copied = [] {
    for (const char* name : {"coco80.names", "coco80_landmarks.yaml"})
      std::filesystem::copy_file(std::filesystem::path(WARDMAP_PROJECT_DIR) / "models" / name,
                                 fuzz::scratch_folder() / name, std::filesystem::copy_options::overwrite_existing);
    return true;
  }();
  (void)classes_copied;
  const auto file = fuzz::write_input("description.yaml", data, size);
  fuzz::refuses_only_with_input_error("load_model_description",
                                      [&] { semantics::load_model_description(file, fuzz::scratch_folder()); });
  return 0;
}
