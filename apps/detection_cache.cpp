#include "apps/detection_cache.h"

#include <chrono>

namespace wardmap::apps {

DetectionCache::DetectionCache(semantics::Detector& detector, semantics::SemanticMapper::EmbedFn embed)
    : detector_(detector), embed_(std::move(embed)) {}

DetectionCache::~DetectionCache() { finish(); }

void DetectionCache::start(size_t capacity) {
  if (worker_.joinable()) return;
  queue_ = std::make_unique<slam::BoundedQueue<std::pair<double, cv::Mat>>>(capacity);
  worker_ = std::thread([this] { run(); });
}

bool DetectionCache::offer(double timestamp, const cv::Mat& image) {
  const bool queued = worker_.joinable() && queue_->try_push({timestamp, image});
  std::lock_guard<std::mutex> lock(mutex_);
  ++offered_;
  if (!queued) ++refused_;
  return queued;
}

void DetectionCache::finish() {
  if (!worker_.joinable()) return;
  queue_->close();
  worker_.join();
}

void DetectionCache::run() {
  while (auto item = queue_->pop()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (cache_.count(item->first)) continue;
    }
    Entry e = compute(item->second, item->first);
    std::lock_guard<std::mutex> lock(mutex_);
    cache_.emplace(item->first, std::move(e));
  }
}

DetectionCache::Entry DetectionCache::compute(const cv::Mat& image, double timestamp) {
  std::lock_guard<std::mutex> compute_lock(compute_mutex_);
  Entry e;
  auto t0 = std::chrono::steady_clock::now();
  e.detections = detector_.detect(image, timestamp);
  const auto t1 = std::chrono::steady_clock::now();
  if (embed_ && !e.detections.empty()) {
    std::vector<Eigen::Vector4d> boxes;
    for (const auto& d : e.detections) boxes.push_back(d.box);
    e.embeddings = embed_(image, boxes);
  }
  e.embeddings.resize(e.detections.size());
  const auto t2 = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  detection_seconds_.push_back(std::chrono::duration<double>(t1 - t0).count());
  embedding_seconds_.push_back(std::chrono::duration<double>(t2 - t1).count());
  return e;
}

std::vector<semantics::Detection> DetectionCache::detect(const cv::Mat& image, double timestamp) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_timestamp_ = timestamp;
    const auto it = cache_.find(timestamp);
    if (it != cache_.end()) return it->second.detections;
  }
  Entry e = compute(image, timestamp);
  std::lock_guard<std::mutex> lock(mutex_);
  return cache_.emplace(timestamp, std::move(e)).first->second.detections;
}

semantics::SemanticMapper::EmbedFn DetectionCache::embed_fn() {
  if (!embed_) return {};
  return [this](const cv::Mat& image, const std::vector<Eigen::Vector4d>& boxes) {
    std::vector<Eigen::VectorXf> out(boxes.size());
    std::vector<size_t> missing;  // boxes the detector did not give for that frame
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const auto it = cache_.find(last_timestamp_);
      for (size_t b = 0; b < boxes.size(); ++b) {
        bool found = false;
        if (it != cache_.end())
          for (size_t i = 0; i < it->second.detections.size() && !found; ++i)
            if (it->second.detections[i].box == boxes[b]) out[b] = it->second.embeddings[i], found = true;
        if (!found) missing.push_back(b);
      }
    }
    if (missing.empty()) return out;
    std::vector<Eigen::Vector4d> rest;
    for (size_t b : missing) rest.push_back(boxes[b]);
    std::lock_guard<std::mutex> compute_lock(compute_mutex_);
    std::vector<Eigen::VectorXf> computed = embed_(image, rest);
    computed.resize(rest.size());
    for (size_t k = 0; k < missing.size(); ++k) out[missing[k]] = std::move(computed[k]);
    return out;
  };
}

std::vector<double> DetectionCache::detection_seconds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return detection_seconds_;
}

std::vector<double> DetectionCache::embedding_seconds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return embedding_seconds_;
}

int DetectionCache::offered() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return offered_;
}

int DetectionCache::refused() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return refused_;
}

}  // namespace wardmap::apps
