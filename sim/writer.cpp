#include "sim/writer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "slam/core/errors.h"

namespace wardmap::sim {

namespace fs = std::filesystem;

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
std::string num(double v) { return fmt("%.6f", std::abs(v) < 5e-7 ? 0.0 : v); }

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream o(file, std::ios::binary);
  o << text;
  if (!o.good()) throw InputError(file.string(), "cannot write file");
}

Eigen::Quaterniond canonical(Eigen::Quaterniond q) {
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return q;
}

}  // namespace

std::string format_timestamp(double t) { return fmt("%.6f", t); }

cv::Mat depth_to_png16(const cv::Mat& depth_m) {
  cv::Mat out(depth_m.size(), CV_16UC1);
  for (int y = 0; y < depth_m.rows; ++y) {
    const float* d = depth_m.ptr<float>(y);
    uint16_t* o = out.ptr<uint16_t>(y);
    for (int x = 0; x < depth_m.cols; ++x) {
      const double v = std::floor(static_cast<double>(d[x]) * kDepthFactor + 0.5);
      o[x] = (d[x] > 0 && v <= 65535.0) ? static_cast<uint16_t>(v) : 0;
    }
  }
  return out;
}

std::string settings_yaml(const Sequence& seq) {
  const slam::PinholeCamera& c = seq.camera();
  const SequenceOptions& o = seq.options();
  std::ostringstream s;
  s << "%YAML:1.0\n---\n"
    << "# Written by 'wardmap synth': scenario " << seq.scenario().name << ", variant "
    << (o.variant == Variant::kSlow ? "slow" : "quick") << ", seed " << o.seed << ".\n"
    << "# ORB-SLAM3 keys; ideal pinhole (no distortion).\n"
    << "File.version: \"1.0\"\n\n"
    << "Camera.type: \"PinHole\"\n"
    << "Camera1.fx: " << num(c.fx) << "\nCamera1.fy: " << num(c.fy) << "\nCamera1.cx: " << num(c.cx)
    << "\nCamera1.cy: " << num(c.cy) << "\n"
    << "Camera1.k1: 0.0\nCamera1.k2: 0.0\nCamera1.p1: 0.0\nCamera1.p2: 0.0\nCamera1.k3: 0.0\n"
    << "Camera.width: " << c.width << "\nCamera.height: " << c.height << "\n"
    << "Camera.fps: " << static_cast<int>(std::lround(o.fps)) << "\n"
    << "Camera.RGB: 1\n\n"
    // The rendered depth is exact (to the PNG's 1/5000 m): its weight as a virtual disparity,
    // z^2 / (fx b) m per pixel, need not be a Kinect's (b = 0.07-0.08 in ORB-SLAM's files). With
    // b = 0.2 the threaded synthetic RGB-D ATE fell from 1.10 to 0.79 cm (6 sequences, 2 runs at
    // 0.07, 6 at 0.2) and from 1.39 to 1.12 cm on 6 others not used to choose it; 0.3 gave 0.87,
    // 0.5 0.84.
    // ThDepth keeps close points under 2.8 m, as before.
    << "Stereo.ThDepth: 14.0\nStereo.b: 0.2\nRGBD.DepthMapFactor: " << num(kDepthFactor) << "\n\n"
    << "ORBextractor.nFeatures: 1000\nORBextractor.scaleFactor: 1.2\nORBextractor.nLevels: 8\n"
    << "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\n\n"
    << "Viewer.KeyFrameSize: 0.05\nViewer.KeyFrameLineWidth: 1.0\nViewer.GraphLineWidth: 0.9\n"
    << "Viewer.PointSize: 2.0\nViewer.CameraSize: 0.08\nViewer.CameraLineWidth: 3.0\n"
    << "Viewer.ViewpointX: 0.0\nViewer.ViewpointY: -0.7\nViewer.ViewpointZ: -1.8\nViewer.ViewpointF: 500.0\n\n"
    << "# wardmap: how this sequence was made (world frame z up, metres, floor at z = 0)\n"
    << "Synth.scenario: \"" << seq.scenario().name << "\"\n"
    << "Synth.variant: \"" << (o.variant == Variant::kSlow ? "slow" : "quick") << "\"\n"
    << "Synth.seed: " << o.seed << "\n"
    << "Synth.frames: " << seq.frame_count() << "\n";
  return s.str();
}

std::string objects_json(const Scene& scene) {
  std::ostringstream s;
  s << "{\"objects\": [";
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectInstance& o = scene.objects[i];
    const Eigen::Vector3d& p = o.pose.translation();
    const Eigen::Quaterniond q = canonical(o.pose.rotation());
    s << (i ? ",\n  " : "\n  ") << "{\"id\": " << o.id << ", \"class\": \"" << to_string(o.cls) << "\", \"position\": ["
      << num(p.x()) << ", " << num(p.y()) << ", " << num(p.z()) << "], \"rotation_xyzw\": [" << num(q.x()) << ", "
      << num(q.y()) << ", " << num(q.z()) << ", " << num(q.w()) << "], \"size\": [" << num(o.size.x()) << ", "
      << num(o.size.y()) << ", " << num(o.size.z()) << "]}";
  }
  s << "\n]}\n";
  return s.str();
}

std::string annotation_line(double timestamp, const std::vector<Annotation>& annotations) {
  std::ostringstream s;
  s << "{\"timestamp\": " << format_timestamp(timestamp) << ", \"objects\": [";
  for (size_t i = 0; i < annotations.size(); ++i) {
    const Annotation& a = annotations[i];
    s << (i ? ", " : "") << "{\"id\": " << a.id << ", \"class\": \"" << to_string(a.cls) << "\", \"box\": [" << a.box[0]
      << ", " << a.box[1] << ", " << a.box[2] << ", " << a.box[3] << "], \"visible\": " << fmt("%.4f", a.visible)
      << "}";
  }
  s << "]}\n";
  return s.str();
}

void write_sequence(Sequence& seq, const fs::path& out_arg, const ProgressFn& progress) {
  std::error_code ec;
  const fs::path out = fs::absolute(out_arg).lexically_normal();
  const fs::path target = out.filename().empty() ? out.parent_path() : out;
  const fs::path parent = target.parent_path();
  fs::create_directories(parent, ec);
  if (ec) throw InputError(parent.string(), "cannot create folder: " + ec.message());
  if (fs::exists(target)) {
    const bool earlier =
        fs::is_directory(target) &&
        (fs::is_empty(target) || (fs::exists(target / "rgb.txt") && fs::exists(target / "groundtruth.txt")));
    if (!earlier)
      throw InputError(target.string(),
                       "exists and is not an earlier 'wardmap synth' output; remove it or choose another --out");
  }
  const std::string pid = std::to_string(static_cast<long>(::getpid()));
  const fs::path tmp = parent / ("." + target.filename().string() + ".partial-" + pid);
  fs::remove_all(tmp, ec);
  try {
    fs::create_directories(tmp / "rgb");
    fs::create_directories(tmp / "depth");
    std::ostringstream rgb_txt, depth_txt, gt_txt, ann;
    const std::string label = seq.scenario().name + " " + (seq.options().variant == Variant::kSlow ? "slow" : "quick") +
                              " seed " + std::to_string(seq.options().seed);
    rgb_txt << "# color images\n# file: 'wardmap synth " << label << "'\n# timestamp filename\n";
    depth_txt << "# depth maps\n# file: 'wardmap synth " << label << "'\n# timestamp filename\n";
    gt_txt << "# ground truth trajectory\n# file: 'wardmap synth " << label << "'\n# timestamp tx ty tz qx qy qz qw\n";
    const std::vector<int> png = {cv::IMWRITE_PNG_COMPRESSION, 3};
    Frame frame;
    const int n = seq.frame_count();
    for (int i = 0; i < n; ++i) {
      seq.render(i, frame, true);
      const std::string ts = format_timestamp(frame.timestamp);
      const fs::path rgb_file = tmp / "rgb" / (ts + ".png"), depth_file = tmp / "depth" / (ts + ".png");
      if (!cv::imwrite(rgb_file.string(), frame.buffers.rgb, png))
        throw InputError(rgb_file.string(), "cannot write image");
      if (!cv::imwrite(depth_file.string(), depth_to_png16(frame.buffers.depth), png))
        throw InputError(depth_file.string(), "cannot write image");
      rgb_txt << ts << " rgb/" << ts << ".png\n";
      depth_txt << ts << " depth/" << ts << ".png\n";
      const Eigen::Vector3d& p = frame.T_wc.translation();
      const Eigen::Quaterniond q = canonical(frame.T_wc.rotation());
      gt_txt << ts << " " << num(p.x()) << " " << num(p.y()) << " " << num(p.z()) << " " << num(q.x()) << " "
             << num(q.y()) << " " << num(q.z()) << " " << num(q.w()) << "\n";
      ann << annotation_line(frame.timestamp, frame.annotations);
      if (progress) progress(i + 1, n);
    }
    std::ostringstream ch;
    ch << "# t_begin t_end kind\n";
    for (const ChallengeSegment& c : seq.challenges())
      ch << format_timestamp(c.t_begin) << " " << format_timestamp(c.t_end) << " " << to_string(c.kind) << "\n";
    write_text(tmp / "rgb.txt", rgb_txt.str());
    write_text(tmp / "depth.txt", depth_txt.str());
    write_text(tmp / "groundtruth.txt", gt_txt.str());
    write_text(tmp / "annotations.jsonl", ann.str());
    write_text(tmp / "objects.json", objects_json(seq.scene()));
    write_text(tmp / "challenges.txt", ch.str());
    write_text(tmp / "settings.yaml", settings_yaml(seq));
    if (fs::exists(target)) {
      const fs::path old = parent / ("." + target.filename().string() + ".old-" + pid);
      fs::rename(target, old);
      fs::rename(tmp, target);
      fs::remove_all(old, ec);
    } else {
      fs::rename(tmp, target);
    }
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(tmp, ec);
    throw InputError(e.path1().string(), e.code().message());
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

}  // namespace wardmap::sim
