// Tiny datasets written into a scratch folder, one per layout.
#pragma once

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

namespace wardmap::test {

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// A 64x48 textured image whose pixel (0,0) encodes `tag`.
inline void write_image(const std::filesystem::path& p, int tag, int w = 64, int h = 48, int type = CV_8UC3) {
  std::filesystem::create_directories(p.parent_path());
  cv::Mat img(h, w, type, cv::Scalar::all(40));
  cv::circle(img, {w / 2, h / 2}, h / 4, cv::Scalar::all(200), -1);
  if (type == CV_8UC3) img.at<cv::Vec3b>(0, 0) = cv::Vec3b(tag, tag, tag);
  else img.at<uchar>(0, 0) = static_cast<uchar>(tag);
  cv::imwrite(p.string(), img);
}

inline void write_depth(const std::filesystem::path& p, uint16_t value, int w = 64, int h = 48) {
  std::filesystem::create_directories(p.parent_path());
  cv::Mat d(h, w, CV_16UC1, cv::Scalar(value));
  d.at<uint16_t>(0, 0) = 65535;
  cv::imwrite(p.string(), d);
}

// TUM RGB-D: 4 colour frames at 30 Hz; the third has no depth within 0.02 s.
inline void make_tum(const std::filesystem::path& root) {
  std::string rgb = "# color images\n# file: 'x'\n# timestamp filename\n", depth = rgb;
  const double t[4] = {1.0, 1.0333, 1.0667, 1.1};
  const double td[4] = {1.005, 1.035, 1.09, 1.101};  // 1.0667 has none within 0.02 s
  for (int i = 0; i < 4; ++i) {
    const std::string n = std::to_string(i);
    write_image(root / "rgb" / (n + ".png"), 10 + i);
    write_depth(root / "depth" / (n + ".png"), 5000 * (i + 1));
    rgb += std::to_string(t[i]) + " rgb/" + n + ".png\n";
    depth += std::to_string(td[i]) + " depth/" + n + ".png\n";
  }
  write_text(root / "rgb.txt", rgb);
  write_text(root / "depth.txt", depth);
  write_text(root / "groundtruth.txt",
             "# ground truth\n1.0 0 0 0 0 0 0 1\n1.034 1 0 0 0 0 0 1\n1.066 2 0 0 0 0 0 1\n1.1 3 0 0 0 0 0 1\n");
}

// KITTI odometry: dataset root with sequences/05 (3 frames), calib.txt and poses/05.txt.
inline void make_kitti(const std::filesystem::path& root, bool with_times = true, bool with_calib = true) {
  const auto seq = root / "sequences" / "05";
  for (int i = 0; i < 3; ++i) {
    char n[16];
    std::snprintf(n, sizeof n, "%06d.png", i);
    write_image(seq / "image_0" / n, 20 + i, 64, 48, CV_8UC1);
  }
  if (with_times) write_text(seq / "times.txt", "0.000000e+00\n1.036000e-01\n2.071000e-01\n");
  if (with_calib)
    write_text(seq / "calib.txt", "P0: 50.0 0 31.5 0 0 51.0 23.5 0 0 0 1 0\nP1: 50.0 0 31.5 -20 0 51.0 23.5 0 0 0 1 0\n");
  write_text(root / "poses" / "05.txt",
             "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 1.5\n1 0 0 0 0 1 0 0 0 0 1 3\n");
}

// 7-Scenes: 3 frames, depth in mm with 65535 invalid.
inline void make_seven_scenes(const std::filesystem::path& root) {
  for (int i = 0; i < 3; ++i) {
    char n[32];
    std::snprintf(n, sizeof n, "frame-%06d.", i);
    write_image(root / (std::string(n) + "color.png"), 30 + i);
    write_depth(root / (std::string(n) + "depth.png"), 1500);
    write_text(root / (std::string(n) + "pose.txt"),
               "1 0 0 " + std::to_string(0.1 * i) + "\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
  }
  write_text(root / "camera-intrinsics.txt", "585 0 32\n0 585 24\n0 0 1\n");
}

// EuRoC: 3 frames, sensor.yaml with T_BS, ground truth of the body.
inline void make_euroc(const std::filesystem::path& root) {
  const auto cam = root / "mav0" / "cam0";
  std::string csv = "#timestamp [ns],filename\n";
  for (int i = 0; i < 3; ++i) {
    const long long t = 1403636579763555584LL + i * 50000000LL;
    write_image(cam / "data" / (std::to_string(t) + ".png"), 40 + i, 64, 48, CV_8UC1);
    csv += std::to_string(t) + "," + std::to_string(t) + ".png\n";
  }
  write_text(cam / "data.csv", csv);
  write_text(cam / "sensor.yaml",
             "sensor_type: camera\nrate_hz: 20\nresolution: [64, 48]\ncamera_model: pinhole\n"
             "intrinsics: [45.0, 46.0, 32.0, 24.0]\ndistortion_model: radial-tangential\n"
             "distortion_coefficients: [-0.28, 0.07, 0.0002, 0.00002]\n"
             "T_BS:\n  cols: 4\n  rows: 4\n  data: [1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n");
  std::string gt = "#timestamp,p_x,p_y,p_z,q_w,q_x,q_y,q_z,v_x,v_y,v_z\n";
  for (int i = 0; i < 3; ++i)
    gt += std::to_string(1403636579763555584LL + i * 50000000LL) + "," + std::to_string(i) + ",0,0,1,0,0,0,0,0,0\n";
  write_text(root / "mav0" / "state_groundtruth_estimate0" / "data.csv", gt);
}

}  // namespace wardmap::test
