// Fuzz target: the bytes of an ONNX model through the speed rewrites of onnx_fold.h, in the order
// load_onnx_net runs them. Their contract: return nullopt for a graph they do not rewrite, throw
// std::runtime_error for bytes that are not a protobuf message (load_onnx_net names the file then);
// never index out of range, loop, or throw anything else.
#include <stdexcept>
#include <string>

#include "semantics/detection/onnx_fold.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap::semantics;
  std::string model(reinterpret_cast<const char*>(data), size);
  try {
    if (auto folded = fold_space_to_depth_input(model)) model = folded->onnx;
    if (auto fused = fuse_silu(model)) model = *fused;
    if (auto cascaded = cascade_max_pools(model)) model = *cascaded;
    if (auto depthwise = replace_depthwise_convs(model)) model = *depthwise;
    if (auto pointwise = replace_pointwise_convs(model)) model = *pointwise;
    if (auto small = replace_small_input_convs(model)) model = *small;
    fold_output_transposes(model);
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    wardmap::fuzz::report_escape("onnx rewrites", "a std::exception other than std::runtime_error", &e);
  }
  return 0;
}
