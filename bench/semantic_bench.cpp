// Per-stage time of the semantic layer per keyframe (issue 5: "under 60 ms in total with
// YOLOX-nano on 2 threads"), on the shared 7-Scenes redkitchen RGB-D recording with ground-truth
// poses, keyframes chosen as `wardmap run --poses gt` chooses them. The stage times are the ones
// SemanticMapper records itself (the figures of report.json): detection, embedding (every crop of
// the keyframe) and measurement per keyframe as medians; MOT, HDP and pose selection run once over
// all keyframe groups, so their run totals are divided by the number of keyframes. Counters in ms;
// goal_ratio = total / 60 ms. Also on 1 OpenCV thread, to show what the second one buys. Skipped
// when ../shared/data or ../shared/models is missing.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bench/bench_support.h"
#include "semantics/detection/detector_factory.h"
#include "semantics/detection/embedder.h"
#include "semantics/detection/model_search.h"
#include "semantics/keyframe_groups.h"
#include "semantics/object_measurement.h"
#include "semantics/semantic_mapper.h"
#include "slam/io/sequence.h"

namespace wardmap::bench {
namespace {

constexpr double kGoalMs = 60.0;

double median_ms(std::vector<double> seconds) {
  if (seconds.empty()) return 0;
  std::nth_element(seconds.begin(), seconds.begin() + seconds.size() / 2, seconds.end());
  return 1e3 * seconds[seconds.size() / 2];
}

// One pass of the semantic layer over the sequence per iteration; arg 0 = OpenCV threads.
void BM_SemanticStagesKitchenYolox(benchmark::State& state) {
  const auto root = data_dir() / "7scenes-redkitchen";
  if (!std::filesystem::exists(root))
    return state.SkipWithError(("shared sequence " + root.string() + " not found (put ../shared beside the checkout or set WARDMAP_DATA)").c_str());
  const int threads = static_cast<int>(state.range(0));
  const int saved_threads = cv::getNumThreads();
  cv::setNumThreads(threads);

  std::unique_ptr<semantics::Detector> detector;
  std::shared_ptr<semantics::Embedder> embedder;
  try {
    semantics::DetectorOptions det;
    det.kind = "yolox";
    det.landmark_set = "indoor";
    detector = semantics::make_detector(det, root);
    embedder = std::make_shared<semantics::Embedder>(semantics::find_embedder_file(), threads);
  } catch (const std::exception& e) {
    cv::setNumThreads(saved_threads);
    return state.SkipWithError((std::string("models not available: ") + e.what()).c_str());
  }
  // As apps/semantic_job.cpp: the crops on the embedder's networks at once, one per thread.
  const semantics::SemanticMapper::EmbedFn embed = [embedder](const cv::Mat& image,
                                                              const std::vector<Eigen::Vector4d>& boxes) {
    return embedder->embed_all(image, boxes);
  };


  // Keyframes from the ground-truth poses, decoded before timing.
  auto reader = slam::io::open_sequence(root);
  if (!reader->info().calibration) {
    cv::setNumThreads(saved_threads);
    return state.SkipWithError("the 7-Scenes reader gave no calibration");
  }
  const slam::PinholeCamera camera = *reader->info().calibration;
  const semantics::SemanticOptions options;
  semantics::KeyframeSelector selector(options.keyframes);
  std::vector<semantics::KeyframeInput> keyframes;
  for (size_t i = 0; i < reader->size(); ++i) {
    const auto& pose = reader->gt_pose(i);
    if (!pose || !selector.accept(*pose)) continue;
    const slam::io::Frame f = reader->read(i);
    keyframes.push_back({f.timestamp, f.image, f.depth, *pose});
  }
  if (keyframes.empty()) {
    cv::setNumThreads(saved_threads);
    return state.SkipWithError("no keyframe with a ground-truth pose");
  }
  const Eigen::Vector3d up = semantics::estimate_up(reader->ground_truth().poses);
  // Warm-up: the first forward pass of each network allocates.
  detector->detect(keyframes.front().image, keyframes.front().timestamp);
  embedder->embed(keyframes.front().image, Eigen::Vector4d(100, 100, 200, 300));

  std::vector<double> detection, embedding, measurement;
  double mot = 0, hdp = 0, pose_selection = 0;
  size_t measurements = 0, landmarks = 0, runs = 0;
  for (auto _ : state) {
    semantics::SemanticMapper mapper(options, *detector, embed, camera);
    mapper.set_up(up);
    for (const auto& kf : keyframes) mapper.add_keyframe(kf);
    const semantics::AssociationResult result = mapper.build_map();
    const semantics::StageTimes& t = mapper.times();
    detection.insert(detection.end(), t.detection.begin(), t.detection.end());
    embedding.insert(embedding.end(), t.embedding.begin(), t.embedding.end());
    measurement.insert(measurement.end(), t.measurement.begin(), t.measurement.end());
    mot += t.mot, hdp += t.hdp, pose_selection += t.pose_selection;
    measurements += mapper.measurements().size();
    landmarks += result.landmarks.size();
    ++runs;
  }
  cv::setNumThreads(saved_threads);

  const double per_keyframe = 1e3 / static_cast<double>(runs * keyframes.size());
  auto& c = state.counters;
  c["detection_ms"] = median_ms(detection);
  c["embedding_ms"] = median_ms(embedding);
  c["measurement_ms"] = median_ms(measurement);
  c["mot_ms"] = mot * per_keyframe;
  c["hdp_ms"] = hdp * per_keyframe;
  c["pose_selection_ms"] = pose_selection * per_keyframe;
  const double total = c["detection_ms"] + c["embedding_ms"] + c["measurement_ms"] + c["mot_ms"] + c["hdp_ms"] +
                       c["pose_selection_ms"];
  c["total_ms"] = total;
  c["goal_ratio"] = total / kGoalMs;
  c["keyframes"] = static_cast<double>(keyframes.size());
  c["measurements_per_kf"] = static_cast<double>(measurements) / static_cast<double>(runs * keyframes.size());
  c["landmarks"] = static_cast<double>(landmarks) / static_cast<double>(runs);
  state.SetLabel("YOLOX-nano + OSNet x0.25, " + std::to_string(threads) + " threads, total " +
                 std::to_string(std::lround(total)) + " ms/keyframe vs goal " +
                 std::to_string(static_cast<int>(kGoalMs)) + " ms");
}
BENCHMARK(BM_SemanticStagesKitchenYolox)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace wardmap::bench
