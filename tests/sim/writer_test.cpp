// The written sequence: exact formats, byte-identical reruns, seeds that change the layout, and no
// half-written output.
#include "sim/writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "slam/core/errors.h"
#include "tests/sim/sim_test_util.h"

namespace wardmap::sim {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
std::vector<std::string> lines(const fs::path& p) {
  std::vector<std::string> out;
  std::istringstream in(read(p));
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// FNV-1a 64 over every file's relative path and bytes, in path order.
uint64_t hash_folder(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(fs::relative(e.path(), dir));
  std::sort(files.begin(), files.end());
  uint64_t h = 1469598103934665603ull;
  for (const auto& f : files)
    for (const std::string& s : {f.string(), read(dir / f)})
      for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

void synth(const std::string& name, uint32_t seed, int frames, const fs::path& out, Variant v = Variant::kQuick) {
  SequenceOptions o;
  o.variant = v;
  o.seed = seed;
  o.max_frames = frames;
  o.width = 320;
  o.height = 240;
  Sequence seq(testing::builtin(name), o);
  write_sequence(seq, out);
}

TEST(Writer, FormatsFollowFormatsMd) {
  const fs::path dir = wardmap::test::scratch_dir() / "seq";
  SequenceOptions o;
  o.variant = Variant::kQuick;
  o.width = 320;
  o.height = 240;
  // the stretch of corridor_loss with the lights failing
  o.max_frames = 40;
  Sequence seq(testing::builtin("corridor_loss"), o);
  write_sequence(seq, dir);

  const auto rgb = lines(dir / "rgb.txt"), depth = lines(dir / "depth.txt"), gt = lines(dir / "groundtruth.txt");
  ASSERT_EQ(rgb.size(), 43u);
  ASSERT_EQ(depth.size(), 43u);
  ASSERT_EQ(gt.size(), 43u);
  EXPECT_EQ(gt[0], "# ground truth trajectory");
  EXPECT_EQ(gt[2], "# timestamp tx ty tz qx qy qz qw");
  EXPECT_EQ(rgb[3], "1000.000000 rgb/1000.000000.png");
  EXPECT_EQ(rgb[4], "1000.033333 rgb/1000.033333.png");
  EXPECT_EQ(depth[5], "1000.066667 depth/1000.066667.png");
  for (size_t i = 3; i < gt.size(); ++i) {
    std::istringstream l(gt[i]);
    double v[8];
    for (double& x : v) ASSERT_TRUE(l >> x) << gt[i];
    EXPECT_NEAR(v[0], 1000.0 + (i - 3) / 30.0, 1e-6);
    EXPECT_NEAR(Eigen::Vector4d(v[4], v[5], v[6], v[7]).norm(), 1.0, 1e-5);
    EXPECT_EQ(gt[i].substr(0, gt[i].find(' ')), rgb[i].substr(0, rgb[i].find(' ')));
  }
  const cv::Mat d = cv::imread((dir / "depth" / "1000.033333.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(d.type(), CV_16UC1);
  EXPECT_EQ(d.cols, 320);
  const cv::Mat c = cv::imread((dir / "rgb" / "1000.033333.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(c.type(), CV_8UC3);

  EXPECT_EQ(read(dir / "settings.yaml").substr(0, 10), "%YAML:1.0\n");
  cv::FileStorage fsr((dir / "settings.yaml").string(), cv::FileStorage::READ);
  ASSERT_TRUE(fsr.isOpened());
  EXPECT_EQ(static_cast<std::string>(fsr["Camera.type"]), "PinHole");
  EXPECT_DOUBLE_EQ(static_cast<double>(fsr["Camera1.fx"]), seq.camera().fx);
  EXPECT_DOUBLE_EQ(static_cast<double>(fsr["Camera1.cy"]), seq.camera().cy);
  EXPECT_EQ(static_cast<int>(fsr["Camera.width"]), 320);
  EXPECT_EQ(static_cast<int>(fsr["Camera.fps"]), 30);
  EXPECT_EQ(static_cast<int>(fsr["Camera.RGB"]), 1);
  EXPECT_DOUBLE_EQ(static_cast<double>(fsr["RGBD.DepthMapFactor"]), 5000.0);
  for (const char* k : {"Camera1.k1", "Camera1.k2", "Camera1.p1", "Camera1.p2"}) EXPECT_FALSE(fsr[k].empty()) << k;

  const auto objects = nlohmann::json::parse(read(dir / "objects.json"));
  ASSERT_EQ(objects["objects"].size(), seq.scene().objects.size());
  const auto& o0 = objects["objects"][0];
  EXPECT_EQ(o0["id"], 1);
  EXPECT_EQ(o0["class"], "door");
  EXPECT_EQ(o0["position"].size(), 3u);
  EXPECT_EQ(o0["rotation_xyzw"].size(), 4u);
  EXPECT_EQ(o0["size"].size(), 3u);

  const auto ann = lines(dir / "annotations.jsonl");
  ASSERT_EQ(ann.size(), 40u);
  Frame f;
  for (int i : {0, 17, 39}) {
    const auto j = nlohmann::json::parse(ann[static_cast<size_t>(i)]);
    EXPECT_NEAR(j["timestamp"].get<double>(), seq.timestamp(i), 1e-6);
    seq.render(i, f, true);
    ASSERT_EQ(j["objects"].size(), f.annotations.size());
    for (size_t k = 0; k < f.annotations.size(); ++k) {
      const auto& a = j["objects"][k];
      EXPECT_EQ(a["id"], f.annotations[k].id);
      EXPECT_EQ(a["class"], to_string(f.annotations[k].cls));
      for (int q = 0; q < 4; ++q) EXPECT_EQ(a["box"][static_cast<size_t>(q)], f.annotations[k].box[q]);
      EXPECT_NEAR(a["visible"].get<double>(), f.annotations[k].visible, 1e-4);
    }
  }
  const auto ch = lines(dir / "challenges.txt");
  ASSERT_EQ(ch.size(), 2u);  // header + the dark stretch (the others start after frame 40)
  EXPECT_EQ(ch[0], "# t_begin t_end kind");
  EXPECT_NE(ch[1].find(" dark"), std::string::npos);
  // nothing left beside the output
  for (const auto& e : fs::directory_iterator(dir.parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos);
}

TEST(Writer, SameSeedSameBytesOtherSeedOtherLayout) {
  const fs::path base = wardmap::test::scratch_dir();
  synth("ward", 7, 12, base / "a");
  synth("ward", 7, 12, base / "b");
  synth("ward", 8, 12, base / "c");
  EXPECT_EQ(hash_folder(base / "a"), hash_folder(base / "b"));
  EXPECT_NE(read(base / "a" / "objects.json"), read(base / "c" / "objects.json"));
  EXPECT_NE(read(base / "a" / "rgb" / "1000.000000.png"), read(base / "c" / "rgb" / "1000.000000.png"));
  // same scenario character: same objects and classes
  const auto a = nlohmann::json::parse(read(base / "a" / "objects.json"));
  const auto c = nlohmann::json::parse(read(base / "c" / "objects.json"));
  ASSERT_EQ(a["objects"].size(), c["objects"].size());
  for (size_t i = 0; i < a["objects"].size(); ++i) EXPECT_EQ(a["objects"][i]["class"], c["objects"][i]["class"]);
}

TEST(Writer, ReplacesEarlierOutputButNotOtherFolders) {
  const fs::path base = wardmap::test::scratch_dir();
  synth("aisle_straight", 1, 3, base / "out");
  synth("aisle_straight", 2, 5, base / "out");
  EXPECT_EQ(lines(base / "out" / "rgb.txt").size(), 8u);
  fs::create_directories(base / "precious");
  std::ofstream(base / "precious" / "thesis.tex") << "do not delete";
  EXPECT_THROW(synth("aisle_straight", 1, 3, base / "precious"), InputError);
  EXPECT_TRUE(fs::exists(base / "precious" / "thesis.tex"));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(base)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names.size(), 2u);
}

}  // namespace
}  // namespace wardmap::sim
