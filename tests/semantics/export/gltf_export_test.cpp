// map.glb: read back with tinygltf (names, extras, accessors, the up rotation, the cube's winding)
// and checked by the Khronos validator when node and its npm package are installed.
#include "semantics/export/gltf_export.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <set>

#include "slam/core/errors.h"
#include "tests/semantics/gltf_test_objects.h"
#include "tests/support/test_support.h"

namespace wardmap::semantics {
namespace {

namespace fs = std::filesystem;

using test::upright_box;

// 3 objects of 2 classes, a 50-pose trajectory and 2,000 points (fixed seed).
GltfMapContent sample_content() {
  GltfMapContent c;
  c.objects = {upright_box(3, "door", {2.0, 1.0, 1.025}, 0.3, {0.9, 0.06, 2.05}, 12),
               upright_box(7, "chair", {-1.0, 2.5, 0.45}, 0.0, {0.5, 0.5, 0.9}, 5),
               upright_box(11, "door", {6.0, -1.0, 1.025}, -1.2, {0.9, 0.06, 2.05}, 30)};
  for (int i = 0; i < 50; ++i) c.trajectory.emplace_back(0.2 * i, 0.5 * std::sin(0.1 * i), 1.5);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-5.0, 10.0), h(0.0, 3.0);
  for (int i = 0; i < 2000; ++i) c.points.emplace_back(u(rng), u(rng), h(rng));
  return c;
}

tinygltf::Model load(const fs::path& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, file.string())) << err;
  EXPECT_TRUE(err.empty()) << err;
  EXPECT_TRUE(warn.empty()) << warn;
  return m;
}

const tinygltf::Node* find_node(const tinygltf::Model& m, const std::string& name) {
  for (const tinygltf::Node& n : m.nodes)
    if (n.name == name) return &n;
  return nullptr;
}

// The floats of a VEC3 float accessor.
std::vector<Eigen::Vector3f> read_vec3(const tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor& a = m.accessors.at(accessor);
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(a.type, TINYGLTF_TYPE_VEC3);
  const tinygltf::BufferView& bv = m.bufferViews.at(a.bufferView);
  const unsigned char* p = m.buffers.at(bv.buffer).data.data() + bv.byteOffset + a.byteOffset;
  std::vector<Eigen::Vector3f> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) std::memcpy(out[i].data(), p + 12 * i, 12);
  return out;
}

Eigen::Quaterniond node_rotation(const tinygltf::Node& n) {
  if (n.rotation.empty()) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
}

fs::path validator_script() { return test::source_dir() / "tests/tools/validate_gltf.js"; }

// Why the validator cannot run here (empty when it can).
std::string validator_missing() {
  if (test::run_command("node --version") != 0)
    return "node is not installed: run scripts/setup.sh to get node and the glTF validator";
  if (!fs::exists(test::source_dir() / "tests/tools/node_modules/gltf-validator"))
    return "the npm package gltf-validator is not installed in tests/tools: run scripts/setup.sh";
  return {};
}

// The validator's report on `file` (also printed, so the test log shows the warnings); expects exit 0.
std::string run_validator(const fs::path& file) {
  std::string out;
  const int rc = test::run_command("node \"" + validator_script().string() + "\" \"" + file.string() + "\"", &out);
  std::cout << out;
  EXPECT_EQ(rc, 0) << out;
  return out;
}

#define SKIP_WITHOUT_VALIDATOR()                                                        \
  do {                                                                                  \
    if (const std::string why = validator_missing(); !why.empty()) GTEST_SKIP() << why; \
  } while (0)

int count_of(const std::string& report, const std::string& key) {
  const auto pos = report.find(key + ": ");
  if (pos == std::string::npos) return -1;
  return std::stoi(report.substr(pos + key.size() + 2));
}

TEST(GltfExport, ObjectsBecomeNamedNodesWithExtras) {
  const fs::path file = test::scratch_dir() / "map.glb";
  const GltfMapContent c = sample_content();
  write_map_glb(file, c);
  const tinygltf::Model m = load(file);

  EXPECT_EQ(m.asset.version, "2.0");
  EXPECT_EQ(m.asset.generator, "wardmap");
  ASSERT_EQ(m.buffers.size(), 1u);
  for (const tinygltf::BufferView& bv : m.bufferViews) EXPECT_EQ(bv.byteOffset % 4, 0u);

  for (const GltfObject& o : c.objects) {
    const tinygltf::Node* n = find_node(m, o.label + "_" + std::to_string(o.id));
    ASSERT_NE(n, nullptr) << o.label << "_" << o.id;
    ASSERT_TRUE(n->extras.IsObject());
    EXPECT_EQ(n->extras.Get("class").Get<std::string>(), o.label);
    EXPECT_EQ(n->extras.Get("id").Get<int>(), o.id);
    EXPECT_EQ(n->extras.Get("measurements").Get<int>(), o.measurements);
    ASSERT_EQ(n->translation.size(), 3u);
    ASSERT_EQ(n->scale.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_DOUBLE_EQ(n->translation[k], o.position[k]);
      EXPECT_DOUBLE_EQ(n->scale[k], o.size[k]);
    }
    EXPECT_NEAR(node_rotation(*n).angularDistance(o.rotation), 0.0, 1e-12);
    ASSERT_GE(n->mesh, 0);
    const tinygltf::Primitive& prim = m.meshes.at(n->mesh).primitives.at(0);
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
    EXPECT_EQ(m.accessors.at(prim.attributes.at("POSITION")).count, 24u);
    EXPECT_EQ(m.accessors.at(prim.indices).count, 36u);
    const tinygltf::Material& mat = m.materials.at(prim.material);
    EXPECT_EQ(mat.name, o.label);
    EXPECT_DOUBLE_EQ(mat.pbrMetallicRoughness.metallicFactor, 0.0);
    EXPECT_TRUE(mat.doubleSided);
    const Eigen::Vector4f colour = class_colour(o.label);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(mat.pbrMetallicRoughness.baseColorFactor[k], colour[k], 1e-6);
  }
  // Two classes: two box meshes and materials, shared by the two doors.
  EXPECT_EQ(find_node(m, "door_3")->mesh, find_node(m, "door_11")->mesh);
  EXPECT_NE(find_node(m, "door_3")->mesh, find_node(m, "chair_7")->mesh);

  const tinygltf::Node* traj = find_node(m, "trajectory");
  ASSERT_NE(traj, nullptr);
  const tinygltf::Primitive& tp = m.meshes.at(traj->mesh).primitives.at(0);
  EXPECT_EQ(tp.mode, TINYGLTF_MODE_LINE_STRIP);
  const std::vector<Eigen::Vector3f> tpos = read_vec3(m, tp.attributes.at("POSITION"));
  ASSERT_EQ(tpos.size(), 50u);
  for (std::size_t i = 0; i < tpos.size(); ++i) EXPECT_LT((tpos[i].cast<double>() - c.trajectory[i]).norm(), 1e-5);
  EXPECT_GE(tp.material, 0);

  const tinygltf::Node* pts = find_node(m, "map_points");
  ASSERT_NE(pts, nullptr);
  const tinygltf::Primitive& pp = m.meshes.at(pts->mesh).primitives.at(0);
  EXPECT_EQ(pp.mode, TINYGLTF_MODE_POINTS);
  EXPECT_EQ(m.accessors.at(pp.attributes.at("POSITION")).count, 2000u);

  // Every POSITION accessor carries min/max that bound its data exactly.
  for (const tinygltf::Mesh& mesh : m.meshes) {
    const int a = mesh.primitives.at(0).attributes.at("POSITION");
    const tinygltf::Accessor& acc = m.accessors.at(a);
    ASSERT_EQ(acc.minValues.size(), 3u);
    ASSERT_EQ(acc.maxValues.size(), 3u);
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = -lo;
    for (const Eigen::Vector3f& p : read_vec3(m, a)) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(acc.minValues[k], static_cast<double>(lo[k]));
      EXPECT_EQ(acc.maxValues[k], static_cast<double>(hi[k]));
    }
  }
}

TEST(GltfExport, RootRotatesUpOntoGltfY) {
  const fs::path dir = test::scratch_dir();
  for (const Eigen::Vector3d& up :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 2, 3)}) {
    GltfMapContent c = sample_content();
    c.up = up;
    const fs::path file = dir / "up.glb";
    write_map_glb(file, c);
    const tinygltf::Model m = load(file);
    ASSERT_EQ(m.scenes.size(), 1u);
    ASSERT_EQ(m.scenes[0].nodes.size(), 1u);
    const tinygltf::Node& root = m.nodes.at(m.scenes[0].nodes[0]);
    EXPECT_EQ(root.name, "wardmap_root");
    // Everything hangs under the root: 3 objects, the trajectory, the points.
    EXPECT_EQ(root.children.size(), 5u);
    std::set<int> kids(root.children.begin(), root.children.end());
    EXPECT_EQ(kids.size(), m.nodes.size() - 1);
    const Eigen::Vector3d mapped = node_rotation(root) * up.normalized();
    EXPECT_LT((mapped - Eigen::Vector3d::UnitY()).norm(), 1e-9) << "up " << up.transpose();
    EXPECT_NEAR(node_rotation(root).norm(), 1.0, 1e-12);
  }
}

TEST(GltfExport, CubeFacesWindCounterClockwiseFromOutside) {
  const fs::path file = test::scratch_dir() / "map.glb";
  write_map_glb(file, sample_content());
  const tinygltf::Model m = load(file);
  const tinygltf::Primitive& prim = m.meshes.at(find_node(m, "chair_7")->mesh).primitives.at(0);
  const std::vector<Eigen::Vector3f> pos = read_vec3(m, prim.attributes.at("POSITION"));
  const std::vector<Eigen::Vector3f> nrm = read_vec3(m, prim.attributes.at("NORMAL"));
  const tinygltf::Accessor& ia = m.accessors.at(prim.indices);
  ASSERT_EQ(ia.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  const tinygltf::BufferView& bv = m.bufferViews.at(ia.bufferView);
  std::vector<std::uint16_t> idx(ia.count);
  std::memcpy(idx.data(), m.buffers[0].data.data() + bv.byteOffset + ia.byteOffset, 2 * ia.count);
  for (std::size_t t = 0; t < idx.size(); t += 3) {
    const Eigen::Vector3f a = pos[idx[t]], b = pos[idx[t + 1]], c = pos[idx[t + 2]];
    const Eigen::Vector3f face = (b - a).cross(c - a);
    EXPECT_NEAR(face.norm(), 1.0f, 1e-6f);  // half of a unit square, times 2
    EXPECT_GT(face.dot(nrm[idx[t]]), 0.99f) << "triangle " << t / 3;
    EXPECT_GT(a.dot(nrm[idx[t]]), 0.49f);  // on the face the normal points out of
  }
}

TEST(GltfExport, EmptyMapIsStillAFile) {
  const fs::path file = test::scratch_dir() / "empty.glb";
  write_map_glb(file, GltfMapContent{});
  const tinygltf::Model m = load(file);
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.nodes.size(), 1u);
  EXPECT_TRUE(m.buffers.empty());
  EXPECT_TRUE(m.meshes.empty());
}

TEST(GltfExport, BadContentThrowsAndLeavesNoFile) {
  const fs::path dir = test::scratch_dir();
  GltfMapContent c = sample_content();
  c.points[5].x() = std::nan("");
  EXPECT_THROW(write_map_glb(dir / "bad.glb", c), InputError);
  c = sample_content();
  c.objects[1].rotation.coeffs().setZero();
  EXPECT_THROW(write_map_glb(dir / "bad.glb", c), InputError);
  c = sample_content();
  c.up.setZero();
  EXPECT_THROW(write_map_glb(dir / "bad.glb", c), InputError);
  EXPECT_THROW(write_map_glb(dir / "no_such_folder" / "map.glb", sample_content()), InputError);
  EXPECT_TRUE(fs::is_empty(dir)) << "a failed write left a file behind";
}

TEST(GltfExport, RewriteReplacesTheFileWhole) {
  const fs::path dir = test::scratch_dir();
  const fs::path file = dir / "map.glb";
  write_map_glb(file, sample_content());
  write_map_glb(file, GltfMapContent{});
  EXPECT_EQ(load(file).nodes.size(), 1u);
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1) << "temporary file left behind";
}

TEST(GltfExport, ClassColoursAreStableAndDistinct) {
  EXPECT_EQ(class_colour("door"), class_colour("door"));
  EXPECT_NE(class_colour("door"), class_colour("chair"));
  const Eigen::Vector4f a = class_colour("some_new_class"), b = class_colour("another_class");
  EXPECT_EQ(a, class_colour("some_new_class"));
  EXPECT_NE(a, b);
  for (const Eigen::Vector4f& c : {a, b, class_colour(""), class_colour("iv_pole")}) {
    EXPECT_TRUE((c.array() >= 0).all() && (c.array() <= 1).all()) << c.transpose();
    EXPECT_EQ(c[3], 1.0f);
  }
}

TEST(GltfValidator, FullMapHasNoErrors) {
  SKIP_WITHOUT_VALIDATOR();
  const fs::path file = test::scratch_dir() / "map.glb";
  write_map_glb(file, sample_content());
  const std::string out = run_validator(file);
  EXPECT_EQ(count_of(out, "numErrors"), 0) << out;
  if (count_of(out, "numWarnings") != 0) std::cout << "note: the validator gave warnings (see above)\n";
}

TEST(GltfValidator, EmptyMapHasNoErrors) {
  SKIP_WITHOUT_VALIDATOR();
  const fs::path file = test::scratch_dir() / "empty.glb";
  write_map_glb(file, GltfMapContent{});
  const std::string out = run_validator(file);
  EXPECT_EQ(count_of(out, "numErrors"), 0) << out;
  if (count_of(out, "numWarnings") != 0) std::cout << "note: the validator gave warnings (see above)\n";
}

TEST(GltfValidator, OnePoseTrajectoryAndNoPointsHasNoErrors) {
  SKIP_WITHOUT_VALIDATOR();
  GltfMapContent c;
  c.trajectory = {Eigen::Vector3d(1, 2, 3)};
  c.objects = sample_content().objects;
  c.objects[0].label = "some_unknown_class";
  const fs::path file = test::scratch_dir() / "one_pose.glb";
  write_map_glb(file, c);
  const std::string out = run_validator(file);
  EXPECT_EQ(count_of(out, "numErrors"), 0) << out;
}

}  // namespace
}  // namespace wardmap::semantics
