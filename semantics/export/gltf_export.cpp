#include "semantics/export/gltf_export.h"

#include <tiny_gltf.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <system_error>
#include <utility>

#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace {

namespace fs = std::filesystem;

// How the map is drawn. Boxes are matte and not metallic: glTF's default metallicFactor of 1 draws
// them black in viewers without an environment map (docs/TOOLCHAIN.md).
struct GltfStyle {
  double roughness = 0.8;
  Eigen::Vector4f trajectory_colour{1.0f, 0.55f, 0.0f, 1.0f};  // orange
  Eigen::Vector4f points_colour{0.55f, 0.55f, 0.55f, 1.0f};    // grey
  float hash_saturation = 0.65f;                               // colours of classes outside the table
  float hash_value = 0.85f;
};
const GltfStyle kStyle;

const char* const kRootName = "wardmap_root";
const char* const kTrajectoryName = "trajectory";
const char* const kPointsName = "map_points";

// The largest GLB the format can describe (its length fields are 32-bit), less the headers.
constexpr std::size_t kMaxBinBytes = std::numeric_limits<std::uint32_t>::max() - 1024u * 1024u;

std::uint32_t fnv1a(const std::string& s) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : s) {
    h ^= c;
    h *= 16777619u;
  }
  return h;
}

Eigen::Vector4f hsv_to_rgba(float h, float s, float v) {
  const float sector = h * 6.0f;
  const int i = static_cast<int>(std::floor(sector)) % 6;
  const float f = sector - std::floor(sector);
  const float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0:
      return {v, t, p, 1.0f};
    case 1:
      return {q, v, p, 1.0f};
    case 2:
      return {p, v, t, 1.0f};
    case 3:
      return {p, q, v, 1.0f};
    case 4:
      return {t, p, v, 1.0f};
    default:
      return {v, p, q, 1.0f};
  }
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

std::string node_name(const GltfObject& o) {
  return (o.label.empty() ? "object" : o.label) + "_" + std::to_string(o.id);
}

// Rejects content that would make an invalid or meaningless file, naming the offending item.
void check_content(const fs::path& file, const GltfMapContent& c) {
  if (!finite(c.up) || c.up.norm() < 1e-12)
    throw InputError(file.string(), "the up vector must be finite and non-zero");
  for (const GltfObject& o : c.objects) {
    const std::string what = "object " + node_name(o) + ": ";
    if (!finite(o.position)) throw InputError(file.string(), what + "position is not finite");
    if (!o.rotation.coeffs().allFinite() || o.rotation.norm() < 1e-12)
      throw InputError(file.string(), what + "rotation must be a finite, non-zero quaternion");
    if (!finite(o.size) || (o.size.array() < 0).any())
      throw InputError(file.string(), what + "size must be finite and not negative");
  }
  for (std::size_t i = 0; i < c.trajectory.size(); ++i)
    if (!finite(c.trajectory[i]))
      throw InputError(file.string(), "trajectory position " + std::to_string(i) + " is not finite");
  for (std::size_t i = 0; i < c.points.size(); ++i)
    if (!finite(c.points[i])) throw InputError(file.string(), "map point " + std::to_string(i) + " is not finite");
  // 12 bytes per position; the cube's 648 bytes are noise next to this bound.
  if ((c.trajectory.size() + c.points.size()) > kMaxBinBytes / 12 - 1024)
    throw InputError(file.string(), "the map is too large for one glTF binary (over 4 GiB of vertex data)");
}

// Builds the one buffer of the file and the views and accessors into it.
class GltfBuilder {
 public:
  explicit GltfBuilder(tinygltf::Model* model) : model_(model) {}

  // A VEC3 float accessor (with min/max, which the validator requires for POSITION).
  int add_vec3(const std::vector<Eigen::Vector3f>& v, bool with_bounds) {
    const int view = add_view(v.data(), v.size() * sizeof(float) * 3, TINYGLTF_TARGET_ARRAY_BUFFER);
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = v.size();
    if (with_bounds && !v.empty()) {
      Eigen::Vector3f lo = v.front(), hi = v.front();
      for (const Eigen::Vector3f& p : v) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      a.minValues = {lo.x(), lo.y(), lo.z()};
      a.maxValues = {hi.x(), hi.y(), hi.z()};
    }
    model_->accessors.push_back(a);
    return static_cast<int>(model_->accessors.size()) - 1;
  }

  int add_indices(const std::vector<std::uint16_t>& idx) {
    const int view = add_view(idx.data(), idx.size() * sizeof(std::uint16_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.count = idx.size();
    model_->accessors.push_back(a);
    return static_cast<int>(model_->accessors.size()) - 1;
  }

  // Adds the buffer to the model (nothing when no view was made: glTF forbids empty buffers).
  void finish() {
    if (data_.empty()) return;
    tinygltf::Buffer b;
    b.data = std::move(data_);
    model_->buffers.push_back(std::move(b));
  }

 private:
  // Appends bytes at a 4-byte aligned offset (glTF wants vertex data aligned to its components,
  // and 4 keeps every view valid for any accessor).
  int add_view(const void* src, std::size_t n, int target) {
    data_.resize((data_.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView bv;
    bv.buffer = 0;
    bv.byteOffset = data_.size();
    bv.byteLength = n;
    bv.target = target;
    const auto* p = static_cast<const unsigned char*>(src);
    data_.insert(data_.end(), p, p + n);
    data_.resize((data_.size() + 3) / 4 * 4, 0);
    model_->bufferViews.push_back(bv);
    return static_cast<int>(model_->bufferViews.size()) - 1;
  }

  tinygltf::Model* model_;
  std::vector<unsigned char> data_;
};

// The unit cube [-0.5, 0.5]^3: 4 vertices per face with the face's outward normal, 2 triangles per
// face, counter-clockwise seen from outside. Node scale makes it the object's size.
struct UnitCube {
  std::vector<Eigen::Vector3f> positions, normals;
  std::vector<std::uint16_t> indices;
};

UnitCube make_unit_cube() {
  UnitCube c;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      const Eigen::Vector3f n = sign * Eigen::Vector3f::Unit(axis);
      // In-face axes with u x v = n, so the corner order below runs counter-clockwise around n.
      Eigen::Vector3f u = Eigen::Vector3f::Unit((axis + 1) % 3), v = Eigen::Vector3f::Unit((axis + 2) % 3);
      if (sign < 0) std::swap(u, v);
      const auto base = static_cast<std::uint16_t>(c.positions.size());
      const std::array<std::array<float, 2>, 4> corners{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
      for (const auto& k : corners) {
        c.positions.push_back(0.5f * (n + k[0] * u + k[1] * v));
        c.normals.push_back(n);
      }
      for (int i : {0, 1, 2, 0, 2, 3}) c.indices.push_back(static_cast<std::uint16_t>(base + i));
    }
  }
  return c;
}

std::vector<Eigen::Vector3f> to_float(const std::vector<Eigen::Vector3d>& v) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(v.size());
  for (const Eigen::Vector3d& p : v) out.push_back(p.cast<float>());
  return out;
}

int add_material(tinygltf::Model* m, const std::string& name, const Eigen::Vector4f& rgba) {
  tinygltf::Material mat;
  mat.name = name;
  mat.pbrMetallicRoughness.baseColorFactor = {rgba[0], rgba[1], rgba[2], rgba[3]};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = kStyle.roughness;
  mat.doubleSided = true;
  m->materials.push_back(mat);
  return static_cast<int>(m->materials.size()) - 1;
}

int add_mesh(tinygltf::Model* m, const std::string& name, tinygltf::Primitive prim) {
  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(std::move(prim));
  m->meshes.push_back(std::move(mesh));
  return static_cast<int>(m->meshes.size()) - 1;
}

int add_node(tinygltf::Model* m, tinygltf::Node node) {
  m->nodes.push_back(std::move(node));
  return static_cast<int>(m->nodes.size()) - 1;
}

// A trajectory or a point set: positions drawn as a line strip (mode 3) or points (mode 0).
int add_polyline_node(tinygltf::Model* m, GltfBuilder* b, const std::string& name,
                      const std::vector<Eigen::Vector3d>& positions, int mode, const Eigen::Vector4f& colour) {
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = b->add_vec3(to_float(positions), true);
  prim.material = add_material(m, name, colour);
  prim.mode = mode;
  tinygltf::Node node;
  node.name = name;
  node.mesh = add_mesh(m, name, std::move(prim));
  return add_node(m, std::move(node));
}

std::vector<double> xyzw(const Eigen::Quaterniond& q) { return {q.x(), q.y(), q.z(), q.w()}; }

tinygltf::Model build_model(const GltfMapContent& content) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "wardmap";
  GltfBuilder b(&m);

  std::vector<int> children;
  if (!content.objects.empty()) {
    const UnitCube cube = make_unit_cube();
    const int pos = b.add_vec3(cube.positions, true);
    const int nrm = b.add_vec3(cube.normals, false);
    const int idx = b.add_indices(cube.indices);
    // One material and one box mesh per class, in order of first appearance; the meshes share the
    // cube's accessors.
    std::map<std::string, int> class_mesh;
    for (const GltfObject& o : content.objects) {
      auto it = class_mesh.find(o.label);
      if (it == class_mesh.end()) {
        const std::string cls = o.label.empty() ? "object" : o.label;
        tinygltf::Primitive prim;
        prim.attributes["POSITION"] = pos;
        prim.attributes["NORMAL"] = nrm;
        prim.indices = idx;
        prim.material = add_material(&m, cls, class_colour(o.label));
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        it = class_mesh.emplace(o.label, add_mesh(&m, "box_" + cls, std::move(prim))).first;
      }
      tinygltf::Node node;
      node.name = node_name(o);
      node.mesh = it->second;
      node.translation = {o.position.x(), o.position.y(), o.position.z()};
      node.rotation = xyzw(o.rotation.normalized());
      node.scale = {o.size.x(), o.size.y(), o.size.z()};
      tinygltf::Value::Object extras;
      extras["class"] = tinygltf::Value(o.label);
      extras["id"] = tinygltf::Value(o.id);
      extras["measurements"] = tinygltf::Value(o.measurements);
      node.extras = tinygltf::Value(extras);
      children.push_back(add_node(&m, std::move(node)));
    }
  }
  // A strip needs two vertices: a one-pose trajectory is drawn as a point.
  if (!content.trajectory.empty())
    children.push_back(add_polyline_node(
        &m, &b, kTrajectoryName, content.trajectory,
        content.trajectory.size() >= 2 ? TINYGLTF_MODE_LINE_STRIP : TINYGLTF_MODE_POINTS, kStyle.trajectory_colour));
  if (!content.points.empty())
    children.push_back(
        add_polyline_node(&m, &b, kPointsName, content.points, TINYGLTF_MODE_POINTS, kStyle.points_colour));

  tinygltf::Node root;
  root.name = kRootName;
  root.rotation = xyzw(Eigen::Quaterniond::FromTwoVectors(content.up.normalized(), Eigen::Vector3d::UnitY()));
  root.children = children;
  const int root_index = add_node(&m, std::move(root));

  tinygltf::Scene scene;
  scene.name = "wardmap";
  scene.nodes = {root_index};
  m.scenes.push_back(scene);
  m.defaultScene = 0;

  b.finish();
  return m;
}

}  // namespace

Eigen::Vector4f class_colour(const std::string& label) {
  // The synthetic hospital's classes and the common landmark classes of models/coco80_landmarks.yaml.
  static const std::map<std::string, Eigen::Vector4f> kTable = {
      {"door", {0.55f, 0.35f, 0.17f, 1.0f}},       {"chair", {0.12f, 0.47f, 0.71f, 1.0f}},
      {"bed", {0.17f, 0.63f, 0.17f, 1.0f}},        {"cabinet", {0.58f, 0.40f, 0.74f, 1.0f}},
      {"wheelchair", {0.84f, 0.15f, 0.16f, 1.0f}}, {"iv_pole", {0.09f, 0.75f, 0.81f, 1.0f}},
      {"vehicle", {0.89f, 0.47f, 0.76f, 1.0f}},    {"person", {1.0f, 0.50f, 0.05f, 1.0f}},
      {"table", {0.74f, 0.74f, 0.13f, 1.0f}},      {"couch", {0.40f, 0.26f, 0.60f, 1.0f}},
      {"tv", {0.25f, 0.25f, 0.25f, 1.0f}},         {"potted_plant", {0.30f, 0.69f, 0.29f, 1.0f}},
  };
  if (auto it = kTable.find(label); it != kTable.end()) return it->second;
  const float hue = static_cast<float>(fnv1a(label) % 3600u) / 3600.0f;
  return hsv_to_rgba(hue, kStyle.hash_saturation, kStyle.hash_value);
}

void write_map_glb(const fs::path& file, const GltfMapContent& content) {
  check_content(file, content);
  const tinygltf::Model model = build_model(content);

  // Unique per process and call, beside the target so the rename stays on one file system.
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = fs::path(file.string() + ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(file.string(), "cannot write (check that its folder exists and is writable)");
    tinygltf::TinyGLTF writer;
    const bool ok = writer.WriteGltfSceneToStream(&model, out, false, true);
    out.close();
    if (!ok || out.fail()) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw InputError(file.string(), "writing failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError(file.string(), "cannot replace the file: " + ec.message());
  }
}

}  // namespace wardmap::semantics
