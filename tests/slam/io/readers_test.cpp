#include <gtest/gtest.h>

#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "slam/core/errors.h"
#include "slam/io/sequence.h"
#include "tests/slam/io/fixtures.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::io {
namespace {

namespace fs = std::filesystem;
using test::scratch_dir;
using test::write_text;

TEST(TumReader, AssociatesDepthWithinWindowAndAttachesGroundTruth) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  auto r = open_sequence(root);
  EXPECT_EQ(r->info().kind, DatasetKind::TumRgbd);
  ASSERT_EQ(r->size(), 3u);  // the frame without depth within 0.02 s is dropped
  EXPECT_NE(r->info().notes.find("1 colour frames without depth"), std::string::npos);
  const Frame f = r->read(2);
  EXPECT_DOUBLE_EQ(f.timestamp, 1.1);
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 13);
  EXPECT_FLOAT_EQ(f.depth.at<float>(5, 5), 4.0f);  // 20000 / 5000
  ASSERT_TRUE(f.gt_pose.has_value());
  EXPECT_DOUBLE_EQ(f.gt_pose->translation().x(), 3.0);
  EXPECT_EQ(r->info().width, 64);
  EXPECT_TRUE(r->info().has_depth);
  EXPECT_EQ(r->ground_truth().size(), 4u);
}

TEST(TumReader, SkipsDepthWhenNotDecoding) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  auto r = open_sequence(root);
  r->set_decode_depth(false);  // a monocular run
  const Frame f = r->read(2);
  EXPECT_TRUE(f.depth.empty());
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 13);
  EXPECT_TRUE(r->info().has_depth);  // the sequence still has it
  r->set_decode_depth(true);
  EXPECT_FLOAT_EQ(r->read(2).depth.at<float>(5, 5), 4.0f);
}

TEST(TumReader, DepthFactorFromTheCalibrationAfterOpening) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  ReaderOptions o;
  o.depth_factor = 1000;  // the calibration known before opening
  EXPECT_FLOAT_EQ(open_sequence(root, o)->read(2).depth.at<float>(5, 5), 20.0f);
  auto r = open_sequence(root);  // and after: wardmap run picks the settings from the sequence
  EXPECT_DOUBLE_EQ(r->info().depth_factor, 5000);
  r->set_depth_factor(1000);
  EXPECT_DOUBLE_EQ(r->info().depth_factor, 1000);
  EXPECT_FLOAT_EQ(r->read(2).depth.at<float>(5, 5), 20.0f);  // 20000 / 1000
}

TEST(KittiReader, ReadsTimesCalibrationAndPoses) {
  const fs::path root = scratch_dir();
  test::make_kitti(root);
  auto r = open_sequence(root);
  EXPECT_EQ(r->info().kind, DatasetKind::Kitti);
  ASSERT_EQ(r->size(), 3u);
  EXPECT_DOUBLE_EQ(r->timestamp(1), 0.1036);
  ASSERT_TRUE(r->info().calibration.has_value());
  EXPECT_DOUBLE_EQ(r->info().calibration->fx, 50.0);
  EXPECT_DOUBLE_EQ(r->info().calibration->cy, 23.5);
  const Frame f = r->read(2);
  EXPECT_EQ(f.image.channels(), 1);
  EXPECT_EQ(f.image.at<uchar>(0, 0), 22);
  ASSERT_TRUE(f.gt_pose);
  EXPECT_DOUBLE_EQ(f.gt_pose->translation().z(), 3.0);
  // The sequence folder itself opens the same way.
  EXPECT_EQ(open_sequence(root / "sequences" / "05")->size(), 3u);
}

TEST(KittiReader, WithoutTimesUsesTenHertz) {
  const fs::path root = scratch_dir();
  test::make_kitti(root, false, false);
  auto r = open_sequence(root);
  EXPECT_DOUBLE_EQ(r->timestamp(2), 0.2);
  EXPECT_FALSE(r->info().calibration.has_value());
}

TEST(KittiReader, FramesAreNumberedByTheirFileNames) {
  const fs::path root = scratch_dir();
  test::make_kitti(root);
  fs::remove(root / "sequences" / "05" / "image_0" / "000001.png");
  auto r = open_sequence(root);
  ASSERT_EQ(r->size(), 2u);
  // Frame 2 keeps its own timestamp and pose, not frame 1's.
  EXPECT_DOUBLE_EQ(r->timestamp(1), 0.2071);
  EXPECT_EQ(r->read(1).image.at<uchar>(0, 0), 22);
  ASSERT_TRUE(r->read(1).gt_pose);
  EXPECT_DOUBLE_EQ(r->read(1).gt_pose->translation().z(), 3.0);
  EXPECT_NE(r->info().notes.find("1 of frames 0-2 have no image"), std::string::npos) << r->info().notes;
  // A pose file shorter than the frames: the frames past its end have no ground truth, and a note says so.
  test::make_kitti(root);
  write_text(root / "poses" / "05.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 1.5\n");
  r = open_sequence(root);
  EXPECT_EQ(r->info().frames_with_ground_truth, 2u);
  EXPECT_NE(r->info().notes.find("05.txt has 2 poses, for frames 0-2"), std::string::npos) << r->info().notes;
}

TEST(TumReader, GroundTruthAtOtherTimesIsExplained) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  write_text(root / "groundtruth.txt", "500.0 0 0 0 0 0 0 1\n500.1 1 0 0 0 0 0 1\n");
  auto r = open_sequence(root);
  EXPECT_FALSE(r->info().has_ground_truth);
  EXPECT_EQ(r->info().ground_truth_unmatched,
            "none of the ground truth's 2 poses (500.000-500.100 s) falls on a frame (1.000-1.100 s)");
  test::make_tum(root);
  EXPECT_EQ(open_sequence(root)->info().ground_truth_unmatched, "");
}

TEST(TumReader, GroundTruthBeyondTheFramesIsLeftOut) {
  const fs::path root = scratch_dir();
  test::make_tum(root);  // frames at 1.0, 1.0333, 1.1 (30 Hz nominal: half a period is 1/60 s)
  write_text(root / "groundtruth.txt",
             "0.5 0 0 0 0 0 0 1\n0.985 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n1.034 1 0 0 0 0 0 1\n"
             "1.066 2 0 0 0 0 0 1\n1.1 3 0 0 0 0 0 1\n1.11 3 0 0 0 0 0 1\n1.2 4 0 0 0 0 0 1\n1.9 5 0 0 0 0 0 1\n");
  auto r = open_sequence(root);
  ASSERT_EQ(r->ground_truth().size(), 6u);  // 0.985 and 1.11 are within half a period
  EXPECT_DOUBLE_EQ(r->ground_truth().timestamps.front(), 0.985);
  EXPECT_DOUBLE_EQ(r->ground_truth().timestamps.back(), 1.11);
  EXPECT_NE(r->info().notes.find("ground-truth poses outside the frames left out: 1 before the first, 2 after the "
                                 "last (6 of 9 kept)"),
            std::string::npos)
      << r->info().notes;
  test::make_tum(root);  // within the frames: nothing to say
  EXPECT_EQ(open_sequence(root)->info().notes.find("ground truth"), std::string::npos);
}

TEST(SevenScenesReader, DepthInMillimetresAndInvalidMarker) {
  const fs::path root = scratch_dir();
  test::make_seven_scenes(root);
  auto r = open_sequence(root);
  EXPECT_EQ(r->info().kind, DatasetKind::SevenScenes);
  ASSERT_EQ(r->size(), 3u);
  EXPECT_DOUBLE_EQ(r->timestamp(2), 2.0 / 30.0);
  const Frame f = r->read(1);
  EXPECT_FLOAT_EQ(f.depth.at<float>(10, 10), 1.5f);
  EXPECT_FLOAT_EQ(f.depth.at<float>(0, 0), 0.0f);  // 65535 = invalid
  EXPECT_NEAR(f.gt_pose->translation().x(), 0.1, 1e-12);
  ASSERT_TRUE(r->info().calibration);
  EXPECT_DOUBLE_EQ(r->info().calibration->fx, 585.0);
}

TEST(SevenScenesReader, FramesByNumberGapsAndStretchesCopiedOut) {
  const fs::path root = scratch_dir();
  test::make_seven_scenes(root);
  for (const char* f : {"frame-000001.color.png", "frame-000001.depth.png", "frame-000001.pose.txt"})
    fs::remove(root / f);
  auto r = open_sequence(root);
  ASSERT_EQ(r->size(), 2u);  // before: the reader stopped at the gap, keeping frame 0 alone
  EXPECT_DOUBLE_EQ(r->timestamp(1), 2.0 / 30.0);
  EXPECT_NEAR(r->read(1).gt_pose->translation().x(), 0.2, 1e-12);
  EXPECT_NE(r->info().notes.find("1 of frames 0-2 have no colour image"), std::string::npos) << r->info().notes;
  // Without frame 0 (a stretch copied out of a recording) it is still 7-Scenes, with its depth.
  fs::remove(root / "frame-000000.color.png");
  r = open_sequence(root);
  EXPECT_EQ(r->info().kind, DatasetKind::SevenScenes);
  ASSERT_EQ(r->size(), 1u);
  EXPECT_TRUE(r->info().has_depth);
  test::make_seven_scenes(root);
  fs::remove(root / "frame-000002.pose.txt");
  EXPECT_NE(open_sequence(root)->info().notes.find("1 frames without pose.txt"), std::string::npos);
}

TEST(EurocReader, CameraGroundTruthComposesBodyPoseWithExtrinsics) {
  const fs::path root = scratch_dir();
  test::make_euroc(root);
  auto r = open_sequence(root);
  EXPECT_EQ(r->info().kind, DatasetKind::Euroc);
  ASSERT_EQ(r->size(), 3u);
  EXPECT_NEAR(r->timestamp(1) - r->timestamp(0), 0.05, 1e-6);
  const Frame f = r->read(2);
  ASSERT_TRUE(f.gt_pose);
  EXPECT_NEAR(f.gt_pose->translation().x(), 2.5, 1e-9);  // T_WB (x = 2) * T_BS (x = 0.5)
  ASSERT_TRUE(r->info().calibration);
  EXPECT_DOUBLE_EQ(r->info().calibration->k1, -0.28);
}

// sensor.yaml's resolution against the images: a pixel off is fitted with a note, far off an error.
TEST(EurocReader, SensorResolutionIsCheckedAgainstTheImages) {
  const fs::path root = scratch_dir();
  test::make_euroc(root);
  const fs::path sensor = root / "mav0" / "cam0" / "sensor.yaml";
  std::ifstream in(sensor);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto with_resolution = [&](const std::string& r) {
    std::string t = text;
    t.replace(t.find("resolution: [64, 48]"), 20, "resolution: " + r);
    write_text(sensor, t);
  };
  with_resolution("[64, 47]");
  auto r = open_sequence(root);
  ASSERT_TRUE(r->info().calibration);
  EXPECT_EQ(r->info().calibration->height, 48);
  EXPECT_NE(r->info().notes.find("resolution (width/height) 64x47 differ slightly from the sequence's images 64x48"),
            std::string::npos)
      << r->info().notes;
  with_resolution("[128, 96]");
  try {
    open_sequence(root);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              sensor.string() + ": resolution (width/height) 128x96 do not match the sequence's images 64x48");
  }
}

TEST(ImageFolderReader, NaturalOrderAndRate) {
  const fs::path root = scratch_dir();
  for (int i : {1, 2, 10}) test::write_image(root / ("img" + std::to_string(i) + ".png"), i);
  ReaderOptions o;
  o.rate = 5;
  auto r = open_sequence(root, o);
  EXPECT_EQ(r->info().kind, DatasetKind::ImageFolder);
  ASSERT_EQ(r->size(), 3u);
  EXPECT_EQ(r->read(2).image.at<cv::Vec3b>(0, 0)[0], 10);
  EXPECT_DOUBLE_EQ(r->timestamp(2), 0.4);
}

TEST(VideoReader, DecodesFramesInOrderAndBySeeking) {
  const fs::path file = scratch_dir() / "clip.avi";
  {
    cv::VideoWriter w(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 15, {64, 48});
    if (!w.isOpened()) GTEST_SKIP() << "this OpenCV build cannot write MJPG video";
    for (int i = 0; i < 6; ++i) w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(i * 40)));
  }
  auto r = open_sequence(file);
  EXPECT_EQ(r->info().kind, DatasetKind::Video);
  ASSERT_EQ(r->size(), 6u);
  EXPECT_NEAR(r->info().fps, 15, 1e-6);
  EXPECT_NEAR(r->read(0).image.at<cv::Vec3b>(20, 20)[0], 0, 4);
  EXPECT_NEAR(r->read(1).image.at<cv::Vec3b>(20, 20)[0], 40, 4);
  EXPECT_NEAR(r->read(4).image.at<cv::Vec3b>(20, 20)[0], 160, 4);
}

TEST(Stretch, KeepsFramesAndTheirGroundTruthWithTheirTimestamps) {
  const fs::path root = scratch_dir();
  test::make_tum(root);  // frames at 1.0, 1.0333, 1.1 (with depth); ground truth at 1.0, 1.034, 1.066, 1.1
  ReaderOptions o;
  o.first_frame = 1;
  o.frame_count = 1;
  auto r = open_sequence(root, o);
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ(r->first_frame(), 1u);
  EXPECT_EQ(r->info().frame_count, 1u);
  EXPECT_DOUBLE_EQ(r->timestamp(0), 1.0333);  // the frame keeps its time
  const Frame f = r->read(0);
  EXPECT_EQ(f.index, 0u);
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 11);
  ASSERT_TRUE(f.gt_pose.has_value());
  EXPECT_DOUBLE_EQ(f.gt_pose->translation().x(), 1.0);
  // Only the ground truth within half a frame period (1/60 s) of the stretch: 1.034, not 1.0 or 1.066.
  ASSERT_EQ(r->ground_truth().size(), 1u);
  EXPECT_DOUBLE_EQ(r->ground_truth().timestamps[0], 1.034);
  EXPECT_NE(r->info().notes.find("frames 1-1 of 3"), std::string::npos) << r->info().notes;

  o.frame_count = 10;  // more than there are: to the end
  r = open_sequence(root, o);
  ASSERT_EQ(r->size(), 2u);
  EXPECT_DOUBLE_EQ(r->timestamp(1), 1.1);
  EXPECT_EQ(r->read(1).image.at<cv::Vec3b>(0, 0)[0], 13);
  EXPECT_EQ(r->ground_truth().size(), 3u);  // 1.034, 1.066, 1.1

  o.first_frame = 3;  // past the end: an error naming the sequence and its frame count
  try {
    open_sequence(root, o);
    FAIL() << "a first frame past the end was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(root.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("has 3 frames"), std::string::npos) << e.what();
  }
}

TEST(Stretch, KittiGroundTruthAndVideoPositions) {
  const fs::path root = scratch_dir();
  test::make_kitti(root);
  ReaderOptions o;
  o.first_frame = 2;
  auto r = open_sequence(root, o);
  ASSERT_EQ(r->size(), 1u);
  EXPECT_DOUBLE_EQ(r->timestamp(0), 0.2071);
  EXPECT_EQ(r->read(0).image.at<uint8_t>(0, 0), 22);
  ASSERT_EQ(r->ground_truth().size(), 1u);
  EXPECT_DOUBLE_EQ(r->ground_truth().poses[0].translation().z(), 3.0);

  const fs::path file = scratch_dir() / "clip.avi";
  {
    cv::VideoWriter w(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 15, {64, 48});
    if (!w.isOpened()) GTEST_SKIP() << "this OpenCV build cannot write MJPG video";
    for (int i = 0; i < 6; ++i) w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(i * 40)));
  }
  o.first_frame = 2;
  o.frame_count = 3;
  r = open_sequence(file, o);
  ASSERT_EQ(r->size(), 3u);
  EXPECT_NEAR(r->timestamp(0), 2.0 / 15, 1e-9);
  EXPECT_NEAR(r->read(0).image.at<cv::Vec3b>(20, 20)[0], 80, 4);   // the video's frame 2
  EXPECT_NEAR(r->read(2).image.at<cv::Vec3b>(20, 20)[0], 160, 4);  // frame 4, by seeking
  EXPECT_NEAR(r->read(1).image.at<cv::Vec3b>(20, 20)[0], 120, 4);  // frame 3, seeking back
  EXPECT_THROW(r->read(3), std::out_of_range);  // past the stretch: the caller's mistake, as for every layout
}

TEST(SequenceDetection, FormatOverridesAndUnknownLayoutFails) {
  const fs::path root = scratch_dir();
  EXPECT_THROW(open_sequence(root), InputError);  // empty folder
  try {
    open_sequence(root);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown layout"), std::string::npos);
  }
  test::make_seven_scenes(root);
  ReaderOptions o;
  o.kind = DatasetKind::ImageFolder;
  EXPECT_EQ(open_sequence(root, o)->info().kind, DatasetKind::ImageFolder);
  EXPECT_THROW(open_sequence(root / "nope"), InputError);
}

// A part of a dataset given for the dataset: a file in it is refused, an image folder in it is read
// as an image folder; both name the dataset's folder.
TEST(SequenceDetection, APartOfADatasetNamesTheDataset) {
  const fs::path scratch = scratch_dir(), root = scratch / "tum";
  test::make_tum(root);
  const std::string hint =
      "it is inside the TUM RGB-D sequence " + fs::absolute(root).lexically_normal().string() + ": give that folder";
  try {
    open_sequence(root / "rgb.txt");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a file that is not a video"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(hint), std::string::npos) << e.what();
  }
  const auto folder = open_sequence(root / "rgb");
  EXPECT_EQ(folder->info().kind, DatasetKind::ImageFolder);
  EXPECT_NE(folder->info().notes.find(hint), std::string::npos) << folder->info().notes;
  // KITTI's image_0, two levels down from the layout's root and one from its sequence.
  const fs::path kitti = scratch / "kitti";
  test::make_kitti(kitti);
  EXPECT_NE(enclosing_dataset_hint(kitti / "sequences" / "05" / "image_0")
                .find("inside the KITTI odometry sequence " + fs::absolute(kitti / "sequences" / "05").string()),
            std::string::npos);
  // A folder of images of its own, and a forced kind, get no note.
  EXPECT_EQ(enclosing_dataset_hint(root), "");
  ReaderOptions o;
  o.kind = DatasetKind::ImageFolder;
  EXPECT_EQ(open_sequence(root / "rgb", o)->info().notes, "");
}

// Bad input: each names the file, the line where there is one, and the problem.
// The error of opening the sequence at `root` and reading its frame `frame`.
std::string error_of(const fs::path& root, size_t frame = 0) {
  try {
    open_sequence(root)->read(frame);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BadInput, MalformedLineNamesFileAndLine) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  write_text(root / "rgb.txt", "# c\n1.0 rgb/0.png\n1.03 rgb/my 1.png\n");
  EXPECT_EQ(error_of(root), (root / "rgb.txt").string() +
                                ":3: expected 'timestamp path', got 3 fields (a file name with a space in it? "
                                "The format has none)");
  write_text(root / "rgb.txt", "1.0 rgb/0.png\n1.03\n");
  EXPECT_EQ(error_of(root), (root / "rgb.txt").string() + ":2: expected 'timestamp path', got 1 field");
  write_text(root / "rgb.txt", "1.0 rgb/0.png\nabc rgb/1.png\n");
  EXPECT_EQ(error_of(root), (root / "rgb.txt").string() + ":2: timestamp: 'abc' is not a number");
}

TEST(BadInput, NonMonotonicTimestamp) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  write_text(root / "rgb.txt", "1.0 rgb/0.png\n1.1 rgb/1.png\n1.05 rgb/2.png\n");
  const std::string e = error_of(root);
  EXPECT_NE(e.find("rgb.txt:3: timestamp 1.05 is not after the previous one 1.1"), std::string::npos) << e;
}

TEST(BadInput, MissingImageOrDepthNamesItsIndexLine) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  fs::remove(root / "rgb" / "3.png");
  std::string e = error_of(root);
  EXPECT_NE(e.find("rgb.txt:7: listed file"), std::string::npos) << e;
  EXPECT_NE(e.find("3.png' not found"), std::string::npos) << e;
  test::make_tum(root);
  fs::remove(root / "depth" / "3.png");
  e = error_of(root);
  EXPECT_NE(e.find("depth.txt:7: listed file"), std::string::npos) << e;  // not rgb.txt's line
}

// Found by fuzz_sequences (tests/fuzz): a name the system cannot look up was a std::filesystem error
// naming no index line.
TEST(BadInput, ListedNameTooLongNamesItsIndexLine) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  std::ofstream(root / "rgb.txt", std::ios::app) << "1.2 rgb/" << std::string(300, 'x') << ".png\n";
  std::ofstream(root / "depth.txt", std::ios::app) << "1.2 depth/3.png\n";  // a colour frame without depth is dropped
  const std::string e = error_of(root);
  EXPECT_NE(e.find("rgb.txt:8: listed file"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot be looked up: File name too long"), std::string::npos) << e;
}

// Found by fuzz_sequences: a sensor.yaml that is not a map of keys escaped as a yaml-cpp exception.
TEST(BadInput, EurocSensorYamlThatIsNotKeys) {
  const fs::path root = scratch_dir();
  test::make_euroc(root);
  const fs::path sensor = root / "mav0" / "cam0" / "sensor.yaml";
  write_text(sensor, "- 1\n- 2\n");
  EXPECT_EQ(error_of(root), sensor.string() + ": expected keys (T_BS, intrinsics, resolution, ...), got a YAML list");
  write_text(sensor, "just text\n");
  EXPECT_EQ(error_of(root), sensor.string() + ": expected keys (T_BS, intrinsics, resolution, ...), got a YAML scalar");
  write_text(sensor, "resolution: [64.5, 48]\nintrinsics: [45.0, 46.0, 32.0, 24.0]\n");
  EXPECT_EQ(error_of(root), sensor.string() + ": key 'resolution': expected whole numbers of pixels");
  write_text(sensor, "resolution: [1e300, 48]\nintrinsics: [45.0, 46.0, 32.0, 24.0]\n");
  EXPECT_NE(error_of(root).find("key 'resolution': must be in [1, 65535], got 1e+300"), std::string::npos)
      << error_of(root);
}

TEST(BadInput, KittiImageNamesAndTimes) {
  const fs::path root = scratch_dir();
  test::make_kitti(root);
  const fs::path images = root / "sequences" / "05" / "image_0";
  test::write_image(images / "cover.png", 1, 64, 48, CV_8UC1);
  EXPECT_NE(error_of(root).find("cover.png: KITTI images are named by their frame number"), std::string::npos)
      << error_of(root);
  fs::remove(images / "cover.png");
  test::write_image(images / "02.png", 1, 64, 48, CV_8UC1);
  EXPECT_NE(error_of(root).find("the same frame number as"), std::string::npos) << error_of(root);
  fs::remove(images / "02.png");
  test::write_image(images / "000004.png", 1, 64, 48, CV_8UC1);
  EXPECT_NE(error_of(root).find("times.txt: has 3 timestamps, and the images go up to 000004.png"), std::string::npos)
      << error_of(root);
}

TEST(BadInput, DepthOfAnotherSizeThanItsImage) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  test::write_depth(root / "depth" / "1.png", 5000, 32, 24);
  EXPECT_EQ(error_of(root, 1), (root / "depth" / "1.png").string() +
                                   ": depth image is 32x24, its colour image 1.png is 64x48 (registered depth of the "
                                   "colour image's size is needed)");
}

TEST(BadInput, DepthImageListedAsColour) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  test::write_depth(root / "rgb" / "1.png", 5000);
  EXPECT_EQ(error_of(root, 1), (root / "rgb" / "1.png").string() +
                                   ": a 16-bit single-channel image where the colour image is expected (a depth image "
                                   "listed as colour?)");
  // Without depth beside it, a 16-bit grey image is a camera's own (read at 8 bits).
  test::write_depth(root / "folder" / "0.png", 5000);
  EXPECT_EQ(open_sequence(root / "folder")->read(0).image.type(), CV_8UC1);
}

TEST(BadInput, IndexThatIsAFolder) {
  const fs::path root = scratch_dir();
  test::make_tum(root);
  fs::remove(root / "depth.txt");
  fs::create_directories(root / "depth.txt");
  EXPECT_EQ(error_of(root), (root / "depth.txt").string() + ": is a folder, not a text file");  // was "read error"
}

TEST(BadInput, PosesThatAreNotRotations) {
  const fs::path root = scratch_dir();
  test::make_seven_scenes(root / "7scenes");  // a shear passes a determinant test alone
  write_text(root / "7scenes" / "frame-000001.pose.txt", "1 0.5 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
  EXPECT_NE(error_of(root / "7scenes").find("frame-000001.pose.txt: rotation block is not a rotation (determinant 1.0"),
            std::string::npos)
      << error_of(root / "7scenes");
  test::make_euroc(root / "euroc");
  write_text(root / "euroc" / "mav0" / "state_groundtruth_estimate0" / "data.csv",
             "#timestamp,p_x,p_y,p_z,q_w,q_x,q_y,q_z\n1403636579763555584,0,0,0,0,0,0,0\n");
  EXPECT_NE(error_of(root / "euroc").find("data.csv:2: quaternion is not unit length (norm 0.0"), std::string::npos)
      << error_of(root / "euroc");
}

TEST(BadInput, UnreadableImage) {
  const fs::path root = scratch_dir();
  test::make_seven_scenes(root);
  write_text(root / "frame-000001.color.png", "not a png");
  auto r = open_sequence(root);
  try {
    r->read(1);
    FAIL() << "no error";
  } catch (const FrameReadError& e) {  // one frame: a run skips it
    EXPECT_EQ(std::string(e.what()), (root / "frame-000001.color.png").string() + ": cannot decode the image (corrupt or not an image)");
    EXPECT_EQ(e.frame(), 1u);
    EXPECT_EQ(e.file(), (root / "frame-000001.color.png").string());
    EXPECT_EQ(e.problem(), "cannot decode the image (corrupt or not an image)");
  }
  EXPECT_EQ(r->read(2).index, 2u);  // the frames after it still read
  EXPECT_THROW(r->read(r->size()), std::out_of_range);  // past the end: the caller's mistake, no frame's
}

// A frame unlike the first (another size) found only when read: a FrameReadError of that frame.
TEST(BadInput, FrameOfAnotherSizeIsThatFramesError) {
  const fs::path root = scratch_dir();
  test::make_seven_scenes(root);
  auto r = open_sequence(root);
  cv::imwrite((root / "frame-000002.color.png").string(), cv::Mat(10, 12, CV_8UC3, cv::Scalar::all(80)));
  try {
    r->read(2);
    FAIL() << "no error";
  } catch (const FrameReadError& e) {
    EXPECT_EQ(e.frame(), 2u);
    EXPECT_NE(std::string(e.what()).find("frame-000002.color.png: image is 12x10, the sequence's first image is"),
              std::string::npos)
        << e.what();
  }
}

TEST(BadInput, MalformedCalibrationAndPoses) {
  const fs::path root = scratch_dir();
  test::make_kitti(root);
  write_text(root / "sequences" / "05" / "calib.txt", "P1: 1 2 3\n");
  EXPECT_NE(error_of(root).find("calib.txt: no 'P0:' line"), std::string::npos);
  test::make_kitti(root);
  write_text(root / "poses" / "05.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n");
  EXPECT_NE(error_of(root).find("05.txt:2: expected 12 values"), std::string::npos) << error_of(root);
}

}  // namespace
}  // namespace wardmap::slam::io
