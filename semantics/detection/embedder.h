// Appearance embedding of a detected object with OSNet x0.25 (torchreid, MODELS.md): 512-d,
// L2-normalised, compared by cosine (dot product). Same object in two views ~0.9, different ~0.45.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <vector>

#include "semantics/detection/onnx_net.h"

namespace wardmap::semantics {

class Embedder {
 public:
  static constexpr int kDimension = 512;

  // Throws InputError naming the file when it is missing or not a loadable ONNX model.
  // find_embedder_file() (model_search.h) locates the shipped OSNet x0.25 file. `threads` (1-8):
  // how many copies of the network embed_all runs at once, each on a thread of its own.
  explicit Embedder(const std::filesystem::path& onnx_file, int threads = kDefaultThreads);

  // The crop box (x0, y0, x1, y1, image pixels) is clamped to the image first. Throws
  // std::invalid_argument when the clamped crop is narrower or lower than kMinCropSide pixels
  // (nothing to describe), or when the image is empty. image: BGR 8-bit (grey/BGRA converted).
  // Runs with batch 1 (OpenCV 4.6 trips an assertion on larger batches in OSNet's channel gate).
  Eigen::VectorXf embed(const cv::Mat& image, const Eigen::Vector4d& box);

  // One embedding per box of one image, the same as embed() gives, but an empty vector where embed()
  // would throw for the crop (nothing to describe). The crops are shared out over the network
  // copies, one thread each: OSNet's many small layers keep cv::dnn's own threads waiting, so two
  // crops at once take about 1.4x less time than one after the other on two threads (2026-11-29).
  // Throws std::invalid_argument for an empty image when there are boxes.
  std::vector<Eigen::VectorXf> embed_all(const cv::Mat& image, const std::vector<Eigen::Vector4d>& boxes);

  int threads() const { return static_cast<int>(nets_.size()); }

  static constexpr double kMinCropSide = 2.0;
  static constexpr int kDefaultThreads = 2;

 private:
  std::vector<cv::dnn::Net> nets_;  // copies of one network: nets_[k] is used by one thread at a time
  OnnxRewrites rewrites_;           // what load_onnx_net's rewrites ask of the input and output
};

// Cosine similarity of two L2-normalised embeddings.
inline float cosine(const Eigen::VectorXf& a, const Eigen::VectorXf& b) { return a.dot(b); }

}  // namespace wardmap::semantics
