// Keyframe detection on its own thread while the SLAM runs (apps/detection_cache.h): every image is
// detected and embedded once, the tracker's offer never waits, and a refused image is answered
// after the run all the same.
#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>

#include "apps/detection_cache.h"

namespace wardmap::apps {
namespace {

// One box per frame, its x0 the frame's timestamp; counts its calls; can be held back.
class FakeDetector : public semantics::Detector {
 public:
  std::vector<semantics::Detection> detect(const cv::Mat&, double t) override {
    {
      std::unique_lock<std::mutex> lock(m);
      cv.wait(lock, [&] { return !hold; });
    }
    ++calls;
    semantics::Detection d;
    d.box = Eigen::Vector4d(t, 0, t + 10, 10);
    d.label = "chair";
    return {d};
  }
  std::string name() const override { return "fake"; }
  void release() {
    {
      std::lock_guard<std::mutex> lock(m);
      hold = false;
    }
    cv.notify_all();
  }
  std::atomic<int> calls{0};
  std::mutex m;
  std::condition_variable cv;
  bool hold = false;
};

semantics::SemanticMapper::EmbedFn counting_embed(std::atomic<int>& calls) {
  return [&calls](const cv::Mat&, const std::vector<Eigen::Vector4d>& boxes) {
    std::vector<Eigen::VectorXf> out;
    for (const auto& box : boxes) {
      ++calls;
      out.emplace_back(1);
      out.back()(0) = static_cast<float>(box(0));
    }
    return out;
  };
}

TEST(DetectionCache, DetectsEachOfferedImageOnceOnItsThread) {
  FakeDetector det;
  std::atomic<int> embeds{0};
  DetectionCache cache(det, counting_embed(embeds));
  cache.start(8);
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar(0));
  for (int t = 0; t < 5; ++t) EXPECT_TRUE(cache.offer(t, image));
  cache.finish();
  EXPECT_EQ(det.calls, 5);
  EXPECT_EQ(embeds, 5);
  const auto embed = cache.embed_fn();
  for (int t = 0; t < 5; ++t) {
    const auto d = cache.detect(image, t);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].box(0), t);
    EXPECT_EQ(embed(image, {d[0].box}).at(0)(0), static_cast<float>(t));
  }
  EXPECT_EQ(det.calls, 5);  // all from the cache
  EXPECT_EQ(embeds, 5);
  EXPECT_EQ(cache.detection_seconds().size(), 5u);
  EXPECT_EQ(cache.offered(), 5);
  EXPECT_EQ(cache.refused(), 0);
}

TEST(DetectionCache, WithoutItsThreadAnswersOnDemandOnce) {
  FakeDetector det;
  std::atomic<int> embeds{0};
  DetectionCache cache(det, counting_embed(embeds));
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar(0));
  EXPECT_FALSE(cache.offer(1, image));  // not started: refused, nothing lost
  EXPECT_EQ(cache.refused(), 1);
  const auto embed = cache.embed_fn();
  const auto d = cache.detect(image, 1);
  EXPECT_EQ(embed(image, {d[0].box}).at(0)(0), 1.0f);
  cache.detect(image, 1);
  EXPECT_EQ(det.calls, 1);
  EXPECT_EQ(embeds, 1);
  // A box the detector did not give is embedded now; the cached one is not embedded again.
  const std::vector<Eigen::VectorXf> both = embed(image, {Eigen::Vector4d(7, 0, 9, 2), d[0].box});
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0](0), 7.0f);
  EXPECT_EQ(both[1](0), 1.0f);
  EXPECT_EQ(embeds, 2);
}

// The detector is held back: the queue fills, and offers return at once (false) instead of waiting.
// Once it runs again, every frame is answered, the refused ones on demand.
TEST(DetectionCache, AFullQueueRefusesWithoutWaiting) {
  FakeDetector det;
  det.hold = true;
  std::atomic<int> embeds{0};
  DetectionCache cache(det, counting_embed(embeds));
  cache.start(2);
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar(0));
  int refused = 0;
  for (int t = 0; t < 10; ++t) refused += cache.offer(t, image) ? 0 : 1;
  EXPECT_GE(refused, 7);  // the worker holds one, the queue two
  EXPECT_EQ(cache.refused(), refused);
  det.release();
  cache.finish();
  for (int t = 0; t < 10; ++t) EXPECT_EQ(cache.detect(image, t)[0].box(0), t);
  EXPECT_EQ(det.calls, 10);
}

}  // namespace
}  // namespace wardmap::apps
