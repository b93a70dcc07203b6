// Appearance embedding of a detected object with OSNet x0.25 (torchreid, MODELS.md): 512-d,
// L2-normalised, compared by cosine (dot product). Same object in two views ~0.9, different ~0.45.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

namespace wardmap::semantics {

class Embedder {
 public:
  static constexpr int kDimension = 512;

  // Throws InputError naming the file when it is missing or not a loadable ONNX model.
  // find_embedder_file() (model_search.h) locates the shipped OSNet x0.25 file.
  explicit Embedder(const std::filesystem::path& onnx_file);

  // The crop box (x0, y0, x1, y1, image pixels) is clamped to the image first. Throws
  // std::invalid_argument when the clamped crop is narrower or lower than kMinCropSide pixels
  // (nothing to describe), or when the image is empty. image: BGR 8-bit (grey/BGRA converted).
  // Runs with batch 1 (OpenCV 4.6 trips an assertion on larger batches in OSNet's channel gate).
  Eigen::VectorXf embed(const cv::Mat& image, const Eigen::Vector4d& box);

  static constexpr double kMinCropSide = 2.0;

 private:
  cv::dnn::Net net_;
};

// Cosine similarity of two L2-normalised embeddings.
inline float cosine(const Eigen::VectorXf& a, const Eigen::VectorXf& b) { return a.dot(b); }

}  // namespace wardmap::semantics
