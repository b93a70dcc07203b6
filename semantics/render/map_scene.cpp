// map.glb read back with tinygltf into world-space geometry.
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cstring>
#include <system_error>

#include "semantics/render/map_render.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace {

namespace fs = std::filesystem;

// Scenes nest nodes; a malformed file may loop. No real map is anywhere near this deep.
constexpr int kMaxNodeDepth = 64;

class SceneReader {
 public:
  SceneReader(const fs::path& file, const tinygltf::Model& model) : file_(file), m_(model) {}

  MapScene read() {
    std::vector<int> roots;
    if (!m_.scenes.empty()) {
      const int s = m_.defaultScene >= 0 && m_.defaultScene < static_cast<int>(m_.scenes.size()) ? m_.defaultScene : 0;
      roots = m_.scenes[s].nodes;
    } else {
      // No scene: every node that is nobody's child.
      std::vector<bool> child(m_.nodes.size(), false);
      for (const auto& n : m_.nodes)
        for (int c : n.children)
          if (c >= 0 && c < static_cast<int>(child.size())) child[c] = true;
      for (size_t i = 0; i < m_.nodes.size(); ++i)
        if (!child[i]) roots.push_back(static_cast<int>(i));
    }
    for (int r : roots) visit(r, Eigen::Matrix4d::Identity(), 0);
    return std::move(scene_);
  }

 private:
  [[noreturn]] void bad(const std::string& problem) const { throw InputError(file_.string(), problem); }

  static Eigen::Matrix4d local_matrix(const tinygltf::Node& n) {
    Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
    if (n.matrix.size() == 16) {
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) M(r, c) = n.matrix[4 * c + r];  // glTF: column-major
      return M;
    }
    if (n.translation.size() == 3) M.block<3, 1>(0, 3) = Eigen::Vector3d(n.translation[0], n.translation[1], n.translation[2]);
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (n.rotation.size() == 4) {
      const Eigen::Quaterniond q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // stored x, y, z, w
      if (q.norm() > 1e-12) R = q.normalized().toRotationMatrix();
    }
    Eigen::Vector3d s = Eigen::Vector3d::Ones();
    if (n.scale.size() == 3) s = Eigen::Vector3d(n.scale[0], n.scale[1], n.scale[2]);
    M.block<3, 3>(0, 0) = R * s.asDiagonal();
    return M;
  }

  void visit(int index, const Eigen::Matrix4d& parent, int depth) {
    if (index < 0 || index >= static_cast<int>(m_.nodes.size())) bad("node " + std::to_string(index) + " does not exist");
    if (depth > kMaxNodeDepth) bad("nodes nested deeper than " + std::to_string(kMaxNodeDepth) + " (a cycle?)");
    const tinygltf::Node& n = m_.nodes[index];
    const Eigen::Matrix4d world = parent * local_matrix(n);
    if (n.mesh >= 0) {
      if (n.mesh >= static_cast<int>(m_.meshes.size())) bad("node '" + n.name + "' uses a mesh that does not exist");
      for (const tinygltf::Primitive& p : m_.meshes[n.mesh].primitives) add_primitive(n, world, p);
    }
    for (int c : n.children) visit(c, world, depth + 1);
  }

  Eigen::Vector4f colour_of(const tinygltf::Primitive& p) const {
    Eigen::Vector4f c(0.7f, 0.7f, 0.7f, 1.0f);
    if (p.material >= 0 && p.material < static_cast<int>(m_.materials.size())) {
      const auto& f = m_.materials[p.material].pbrMetallicRoughness.baseColorFactor;
      if (f.size() == 4) c = Eigen::Vector4f(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
    }
    return c;
  }

  // The bytes of element i of an accessor, checked against its buffer.
  const unsigned char* element(const tinygltf::Accessor& a, size_t i, size_t element_size) const {
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(m_.bufferViews.size())) bad("an accessor has no buffer view");
    const tinygltf::BufferView& bv = m_.bufferViews[a.bufferView];
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(m_.buffers.size())) bad("a buffer view has no buffer");
    const auto& data = m_.buffers[bv.buffer].data;
    const size_t stride = bv.byteStride > 0 ? bv.byteStride : element_size;
    const size_t offset = bv.byteOffset + a.byteOffset + i * stride;
    if (offset + element_size > data.size() || a.byteOffset + i * stride + element_size > bv.byteLength)
      bad("an accessor reaches past the end of its buffer");
    return data.data() + offset;
  }

  std::vector<Eigen::Vector3f> read_vec3(int accessor) const {
    if (accessor < 0 || accessor >= static_cast<int>(m_.accessors.size())) bad("a POSITION accessor does not exist");
    const tinygltf::Accessor& a = m_.accessors[accessor];
    if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      bad("POSITION accessor " + std::to_string(accessor) + " is not a float VEC3");
    std::vector<Eigen::Vector3f> out(a.count);
    for (size_t i = 0; i < a.count; ++i) std::memcpy(out[i].data(), element(a, i, 12), 12);
    return out;
  }

  std::vector<std::uint32_t> read_indices(int accessor, size_t vertices) const {
    std::vector<std::uint32_t> out;
    if (accessor < 0) {  // non-indexed: the vertices in order
      for (size_t i = 0; i < vertices; ++i) out.push_back(static_cast<std::uint32_t>(i));
      return out;
    }
    if (accessor >= static_cast<int>(m_.accessors.size())) bad("an index accessor does not exist");
    const tinygltf::Accessor& a = m_.accessors[accessor];
    const int size = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                     : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                 : 0;
    if (a.type != TINYGLTF_TYPE_SCALAR || size == 0) bad("index accessor " + std::to_string(accessor) + " is not unsigned scalars");
    for (size_t i = 0; i < a.count; ++i) {
      const unsigned char* p = element(a, i, size);
      std::uint32_t v = 0;
      if (size == 1) v = *p;
      else if (size == 2) {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        v = s;
      } else
        std::memcpy(&v, p, 4);
      if (v >= vertices) bad("index accessor " + std::to_string(accessor) + " names a vertex that does not exist");
      out.push_back(v);
    }
    return out;
  }

  static std::string label_of(const tinygltf::Node& n) {
    if (n.extras.IsObject() && n.extras.Has("class") && n.extras.Get("class").IsString())
      return n.extras.Get("class").Get<std::string>();
    const auto cut = n.name.rfind('_');
    return cut == std::string::npos || cut == 0 ? (n.name.empty() ? "object" : n.name) : n.name.substr(0, cut);
  }

  static int id_of(const tinygltf::Node& n) {
    if (n.extras.IsObject() && n.extras.Has("id") && n.extras.Get("id").IsInt()) return n.extras.Get("id").Get<int>();
    return -1;
  }

  void add_primitive(const tinygltf::Node& n, const Eigen::Matrix4d& world, const tinygltf::Primitive& p) {
    const auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) return;  // nothing to draw
    const std::vector<Eigen::Vector3f> v = read_vec3(pos->second);
    if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1) {
      SceneObject o;
      o.label = label_of(n);
      o.id = id_of(n);
      o.world = world;
      o.vertices = v;
      o.triangles = read_indices(p.indices, v.size());
      o.triangles.resize(o.triangles.size() / 3 * 3);
      o.colour = colour_of(p);
      scene_.objects.push_back(std::move(o));
      return;
    }
    if (p.mode != TINYGLTF_MODE_LINE_STRIP && p.mode != TINYGLTF_MODE_POINTS) return;  // other modes: not drawn
    ScenePolyline line;
    line.name = n.name;
    line.colour = colour_of(p);
    for (std::uint32_t i : read_indices(p.indices, v.size()))
      line.points.push_back((world * v[i].cast<double>().homogeneous()).head<3>());
    (p.mode == TINYGLTF_MODE_LINE_STRIP ? scene_.lines : scene_.points).push_back(std::move(line));
  }

  const fs::path& file_;
  const tinygltf::Model& m_;
  MapScene scene_;
};

}  // namespace

MapScene read_map_scene(const fs::path& glb) {
  std::error_code ec;
  if (!fs::exists(glb, ec)) throw InputError(glb.string(), "not found");
  if (fs::is_directory(glb, ec)) throw InputError(glb.string(), "is a folder, not a .glb file");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  if (!loader.LoadBinaryFromFile(&model, &err, &warn, glb.string())) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(glb.string(), "not a binary glTF (.glb) file" + (err.empty() ? std::string() : " (" + err + ")"));
  }
  return SceneReader(glb, model).read();
}

}  // namespace wardmap::semantics
