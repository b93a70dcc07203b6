// A picture of an object map: map.glb (../shared/docs/FORMATS.md) read back and drawn with VTK into
// a PNG (wardmap render-map). Reading needs no display; drawing needs an X display, which
// display_problem() checks first because Debian's VTK aborts without one (docs/TOOLCHAIN.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wardmap::semantics {

// One mapped object: its mesh (a unit box in wardmap's files) and the node's model matrix.
struct SceneObject {
  std::string label;                    // extras.class, else the node name before its last '_'
  int id = -1;                          // extras.id, or -1
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();  // mesh -> glTF world (+Y up)
  std::vector<Eigen::Vector3f> vertices;                // mesh coordinates
  std::vector<std::uint32_t> triangles;                 // 3 indices per triangle
  Eigen::Vector4f colour{0.7f, 0.7f, 0.7f, 1.0f};       // baseColorFactor, RGBA 0-1
};

// A line strip (the trajectory) or a point set (the map points), in glTF world coordinates.
struct ScenePolyline {
  std::string name;
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector4f colour{0.5f, 0.5f, 0.5f, 1.0f};
};

// The drawable content of a map.glb, everything in glTF's world frame (+Y up: wardmap's root node
// turns the map's up direction onto +Y).
struct MapScene {
  std::vector<SceneObject> objects;   // triangle meshes
  std::vector<ScenePolyline> lines;   // line strips
  std::vector<ScenePolyline> points;  // point primitives
};

// Reads a binary glTF file (wardmap's map.glb or any .glb with triangle, line-strip or point
// primitives). Throws wardmap::InputError naming the file when it is missing, is not a .glb or holds
// accessors that point outside its buffers.
MapScene read_map_scene(const std::filesystem::path& glb);

enum class MapView { Top, Oblique };

struct MapRenderOptions {
  int width = 1280, height = 960;
  MapView view = MapView::Top;
  std::string title;  // drawn at the top left; empty: none
};

// Why no picture can be drawn here (no DISPLAY, or an X server that does not answer), with what to
// do instead; nullopt when an X display is reachable.
std::optional<std::string> display_problem();

// Draws `scene` off-screen and writes it as a PNG (through a temporary name and a rename). Throws
// std::runtime_error when there is no display (the message of display_problem()) and
// wardmap::InputError naming `png` when it cannot be written.
void render_map_png(const MapScene& scene, const std::filesystem::path& png, const MapRenderOptions& options);

// "1 object", "3 objects": a count and its noun, plural with an s when the count is not 1.
std::string counted(size_t n, const std::string& noun);

}  // namespace wardmap::semantics
