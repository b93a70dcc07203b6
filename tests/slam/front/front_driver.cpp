// Test-only driver for measurements: runs the front-process over a sequence and writes the TUM
// trajectory and per-frame timings. (`wardmap run` will replace it.)
//   [FRONT_MONO=1] [FRONT_THREAD=1] [FRONT_VERBOSE=1] wardmap_front_driver <sequence> <settings.yaml> <trajectory.txt> [max_frames]
#include <algorithm>
#include <cstdio>
#include <vector>

#include "slam/eval/trajectory_eval.h"
#include "slam/front/front_process.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/io/trajectory_io.h"

int main(int argc, char** argv) {
  using namespace wardmap::slam;
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s <sequence> <settings.yaml> <trajectory.txt> [max_frames]\n", argv[0]);
    return 2;
  }
  try {
    const io::Settings settings = io::load_settings(argv[2]);
    FrontOptions options = load_front_options(settings);
    options.monocular = std::getenv("FRONT_MONO") != nullptr;
    options.mapping_thread = std::getenv("FRONT_THREAD") != nullptr;
    io::ReaderOptions ro;
    if (settings.camera.depth_map_factor) ro.depth_factor = *settings.camera.depth_map_factor;
    auto reader = io::open_sequence(argv[1], ro);
    const size_t n = argc > 4 ? std::min<size_t>(reader->size(), std::stoul(argv[4])) : reader->size();
    FrontProcess front(options, settings.camera.camera);
    std::vector<double> times, extract_times, tracking_times;
    int tracked = 0, keyframes = 0;
    for (size_t i = 0; i < n; ++i) {
      const io::Frame f = reader->read(i);
      const FrameResult r = front.process(f);
      times.push_back(r.seconds);
      extract_times.push_back(r.extract_seconds);
      tracking_times.push_back(r.seconds - r.mapping_seconds);
      tracked += r.tracked;
      keyframes += r.keyframe;
      if (std::getenv("FRONT_VERBOSE"))
        std::printf("%zu %s kf=%d feat=%d matches=%d inliers=%d %.1f ms\n", i, to_string(r.state), r.keyframe,
                    r.features, r.matches, r.inliers, 1e3 * r.seconds);
    }
    front.finish();
    const Trajectory best = front.trajectory();
    io::write_tum(argv[3], best);
    std::printf("submaps %zu; the largest holds %zu tracked frames (written)\n", front.submaps().size(), best.size());
    if (reader->info().has_ground_truth && best.size() >= 3) {
      const auto& gt = reader->ground_truth();
      const auto pairs = eval::associate(gt, best, {});
      if (pairs.size() >= 3) {
        const auto sim3 = eval::compute_ate(gt, best, pairs, eval::Alignment::Sim3);
        const auto se3 = eval::compute_ate(gt, best, pairs, eval::Alignment::SE3);
        std::printf("ATE Sim(3) %.4f m, SE(3) %.4f m over %zu poses; tracking rate %.1f %%\n", sim3.stats.rmse,
                    se3.stats.rmse, pairs.size(), eval::tracking_rate(gt, best, {}));
      }
    }
    auto pct = [](std::vector<double> s, double p) {
      std::sort(s.begin(), s.end());
      return s.empty() ? 0.0 : 1e3 * s[std::min(s.size() - 1, static_cast<size_t>(p * s.size()))];
    };
    const auto& st = front.mapper_stats();
    std::printf("frames %zu tracked %d (%.1f %%) keyframes made %d kept %zu points %zu\n", n, tracked,
                100.0 * tracked / std::max<size_t>(n, 1), keyframes, front.submap().num_keyframes(),
                front.submap().num_map_points());
    std::printf("mapper: triangulated %d culled points %d culled keyframes %d fused %d\n", st.triangulated,
                st.culled_points, st.culled_keyframes, st.fused);
    std::printf("mapper seconds: register %.2f cull %.2f triangulate %.2f fuse %.2f ba %.2f kf-cull %.2f\n",
                st.t_register, st.t_cull, st.t_triangulate, st.t_fuse, st.t_ba, st.t_cull_keyframes);
    std::printf("last BA: %d keyframes, %d fixed, %d points, %d observations, %d outliers\n", st.last_ba.keyframes,
                st.last_ba.fixed_keyframes, st.last_ba.points, st.last_ba.observations, st.last_ba.outliers);
    std::printf("time per frame (ms): median %.2f p95 %.2f max %.2f\n", pct(times, 0.5), pct(times, 0.95),
                pct(times, 1.0));
    std::printf("  without inline mapping: median %.2f p95 %.2f max %.2f\n", pct(tracking_times, 0.5),
                pct(tracking_times, 0.95), pct(tracking_times, 1.0));
    std::printf("  ORB extraction: median %.2f p95 %.2f\n", pct(extract_times, 0.5), pct(extract_times, 0.95));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
