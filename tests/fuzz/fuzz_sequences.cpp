// Fuzz target: the text files of the dataset layouts wardmap reads (TUM RGB-D, KITTI odometry,
// 7-Scenes, EuRoC). Tiny datasets of each (tests/slam/io/fixtures.h) are written once; the first
// byte of an input picks one of their files, the rest replaces it, the sequence is opened (index,
// calibration and ground truth parsed and matched), and the file is put back.
#include <array>
#include <filesystem>
#include <string>

#include "slam/io/sequence.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/slam/io/fixtures.h"

namespace {

namespace fs = std::filesystem;

struct Target {
  const char* dataset;  // folder under the scratch folder, opened as a sequence
  const char* file;     // the file inside it that the input replaces
};

constexpr std::array<Target, 12> kTargets{{
    {"tum", "rgb.txt"},
    {"tum", "depth.txt"},
    {"tum", "groundtruth.txt"},
    {"tum", "settings.yaml"},  // a dataset's own calibration beside it (absent from the fixture)
    {"kitti", "sequences/05/times.txt"},
    {"kitti", "sequences/05/calib.txt"},
    {"kitti", "poses/05.txt"},
    {"7scenes", "frame-000001.pose.txt"},
    {"7scenes", "camera-intrinsics.txt"},
    {"euroc", "mav0/cam0/data.csv"},
    {"euroc", "mav0/cam0/sensor.yaml"},
    {"euroc", "mav0/state_groundtruth_estimate0/data.csv"},
}};

// The datasets are made in pristine/ and copied to live/, where the inputs go.
const fs::path& datasets() {
  static const fs::path live = [] {
    const fs::path r = wardmap::fuzz::scratch_folder();
    wardmap::test::make_tum(r / "pristine" / "tum");
    wardmap::test::make_kitti(r / "pristine" / "kitti");
    wardmap::test::make_seven_scenes(r / "pristine" / "7scenes");
    wardmap::test::make_euroc(r / "pristine" / "euroc");
    fs::copy(r / "pristine", r / "live", fs::copy_options::recursive);
    return r / "live";
  }();
  return live;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wardmap;
  if (size == 0) return 0;
  const Target& t = kTargets[data[0] % kTargets.size()];
  const fs::path root = datasets() / t.dataset;
  const fs::path file = fuzz::write_input(std::string("live/") + t.dataset + "/" + t.file, data + 1, size - 1);
  fuzz::refuses_only_with_input_error("open_sequence", [&] {
    auto reader = slam::io::open_sequence(root);
    for (size_t i = 0; i < reader->size(); ++i) {
      (void)reader->timestamp(i);
      (void)reader->gt_pose(i);
    }
  });
  // Put the fixture's file back (or remove the one it does not have).
  const fs::path pristine = datasets().parent_path() / "pristine" / t.dataset / t.file;
  if (fs::exists(pristine))
    fs::copy_file(pristine, file, fs::copy_options::overwrite_existing);
  else
    fs::remove(file);
  return 0;
}
