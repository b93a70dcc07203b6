// Detections and appearance embeddings of keyframe images, computed once per image: on a thread of
// their own while the SLAM tracks (ARCHITECTURE.md: the tracker never waits on semantics), or on
// demand. The stages that need the final keyframe poses (measurement, groups, MOT, HDP, pose
// selection) run once the map is done, on the same answers: a run gives the same objects with or
// without the thread.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "semantics/detection/detection.h"
#include "semantics/semantic_mapper.h"
#include "slam/front/bounded_queue.h"

namespace wardmap::apps {

class DetectionCache : public semantics::Detector {
 public:
  // `embed` may be empty (no appearance). Both are used by one thread at a time.
  DetectionCache(semantics::Detector& detector, semantics::SemanticMapper::EmbedFn embed);
  ~DetectionCache() override;
  DetectionCache(const DetectionCache&) = delete;
  DetectionCache& operator=(const DetectionCache&) = delete;

  // Starts the worker thread, with room for `capacity` waiting images.
  void start(size_t capacity);
  // Never waits: false when the queue is full or the worker not running (the image is then
  // detected on demand, after the run).
  bool offer(double timestamp, const cv::Mat& image);
  // Waits for the queued images; stops the worker.
  void finish();

  // The frame's detections: from the cache, else computed now (with their embeddings) and cached.
  std::vector<semantics::Detection> detect(const cv::Mat& image, double timestamp) override;
  std::string name() const override { return detector_.name(); }
  // The embedding of a box returned by the last detect(): from the cache, else computed now.
  semantics::SemanticMapper::EmbedFn embed_fn();

  // Seconds of each image's detection and embedding (cached answers cost nothing again).
  std::vector<double> detection_seconds() const;
  std::vector<double> embedding_seconds() const;
  // Images offered during the run, and those the full queue refused.
  int offered() const;
  int refused() const;

 private:
  struct Entry {
    std::vector<semantics::Detection> detections;
    std::vector<Eigen::VectorXf> embeddings;
  };
  Entry compute(const cv::Mat& image, double timestamp);
  void run();

  semantics::Detector& detector_;
  semantics::SemanticMapper::EmbedFn embed_;
  std::mutex compute_mutex_;     // the detector and the embedder: one caller at a time
  mutable std::mutex mutex_;     // everything below
  std::map<double, Entry> cache_;
  std::vector<double> detection_seconds_, embedding_seconds_;
  int offered_ = 0, refused_ = 0;
  double last_timestamp_ = 0;
  std::unique_ptr<slam::BoundedQueue<std::pair<double, cv::Mat>>> queue_;
  std::thread worker_;
};

}  // namespace wardmap::apps
