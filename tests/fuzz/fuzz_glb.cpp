// Fuzz target: a binary glTF file, as `wardmap render-map` reads any .glb (tinygltf, then our walk of
// its nodes, meshes, accessors and buffer views).
#include "semantics/render/map_render.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  const auto file = fuzz::write_input("map.glb", data, size);
  fuzz::refuses_only_with_input_error("read_map_scene", [&] { semantics::read_map_scene(file); });
  return 0;
}
