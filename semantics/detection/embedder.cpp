#include "semantics/detection/embedder.h"

#include "semantics/detection/onnx_net.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <system_error>
#include <thread>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "semantics/detection/letterbox.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace {
// OSNet input (MODELS.md): RGB, 128 wide x 256 high, /255, ImageNet mean and std.
constexpr int kInputWidth = 128;
constexpr int kInputHeight = 256;
const cv::Scalar kMean(0.485, 0.456, 0.406);
const cv::Scalar kStd(0.229, 0.224, 0.225);
}  // namespace

namespace {

// The embedding of `box` in a BGR 8-bit image, by `net` (Embedder::embed's contract).
Eigen::VectorXf embed_crop(cv::dnn::Net& net, const OnnxRewrites& rewrites, const cv::Mat& bgr,
                           const Eigen::Vector4d& box) {
  const double x0 = std::clamp(box[0], 0.0, static_cast<double>(bgr.cols));
  const double y0 = std::clamp(box[1], 0.0, static_cast<double>(bgr.rows));
  const double x1 = std::clamp(box[2], 0.0, static_cast<double>(bgr.cols));
  const double y1 = std::clamp(box[3], 0.0, static_cast<double>(bgr.rows));
  if (x1 - x0 < Embedder::kMinCropSide || y1 - y0 < Embedder::kMinCropSide)
    throw std::invalid_argument("Embedder::embed: crop smaller than 2 px after clamping to the image");
  // Whole pixels covering the box.
  const int ix0 = static_cast<int>(std::floor(x0)), iy0 = static_cast<int>(std::floor(y0));
  const int ix1 = static_cast<int>(std::ceil(x1)), iy1 = static_cast<int>(std::ceil(y1));
  cv::Mat crop;
  cv::resize(bgr(cv::Rect(ix0, iy0, ix1 - ix0, iy1 - iy0)), crop, cv::Size(kInputWidth, kInputHeight), 0, 0,
             cv::INTER_LINEAR);
  cv::cvtColor(crop, crop, cv::COLOR_BGR2RGB);
  cv::Mat input;
  crop.convertTo(input, CV_32FC3, 1.0 / 255.0);
  cv::subtract(input, kMean, input);
  cv::divide(input, kStd, input);
  net.setInput(rewrites.prepare_input(cv::dnn::blobFromImage(input)));  // 1 x 3 x 256 x 128
  // A single-output model: its output, put back as the original model gives it when a rewrite
  // left its final Transpose out (transposed_outputs names graph outputs).
  const cv::Mat out = rewrites.transposed_outputs.empty()
                          ? net.forward()
                          : rewrites.restore_output(rewrites.transposed_outputs.front(),
                                                    net.forward(rewrites.transposed_outputs.front()));
  if (out.total() != static_cast<size_t>(Embedder::kDimension))
    throw std::runtime_error("expected a " + std::to_string(Embedder::kDimension) + "-d output, got " +
                             std::to_string(out.total()) + " values");
  Eigen::VectorXf v = Eigen::Map<const Eigen::VectorXf>(out.ptr<float>(), Embedder::kDimension);
  const float norm = v.norm();
  if (norm > 0) v /= norm;
  return v;
}

}  // namespace

Embedder::Embedder(const std::filesystem::path& onnx_file, int threads) {
  if (threads < 1 || threads > 8)
    throw std::invalid_argument("Embedder: threads must be in [1, 8], got " + std::to_string(threads));
  // Rewritten for speed (onnx_net.h; OSNet: its 7 x 7 stem, 60 depthwise and 92 of its 1 x 1
  // convolutions), the same for every copy.
  for (int k = 0; k < threads; ++k)
    nets_.push_back(load_onnx_net(
        onnx_file, "embedding model not found (models/README.md says where to get OSNet x0.25)", rewrites_,
        /*few_channel_convs=*/true));
  // One crop of a blank image: a file that is not an embedding model (another network, which
  // cv::dnn may run on OSNet's input all the same) is refused here, naming it.
  try {
    embed_crop(nets_.front(), rewrites_, cv::Mat(kInputHeight, kInputWidth, CV_8UC3, cv::Scalar::all(0)),
               Eigen::Vector4d(0, 0, kInputWidth, kInputHeight));
  } catch (const cv::Exception& ex) {
    throw InputError(onnx_file.string(), "the network does not run on OSNet's 128 x 256 input: " + ex.msg);
  } catch (const std::exception& ex) {
    throw InputError(onnx_file.string(), std::string(ex.what()) + ": not OSNet x0.25 (models/README.md)?");
  }
}

Eigen::VectorXf Embedder::embed(const cv::Mat& image, const Eigen::Vector4d& box) {
  return embed_crop(nets_.front(), rewrites_, to_bgr8(image), box);
}

std::vector<Eigen::VectorXf> Embedder::embed_all(const cv::Mat& image, const std::vector<Eigen::Vector4d>& boxes) {
  std::vector<Eigen::VectorXf> out(boxes.size());
  if (boxes.empty()) return out;
  const cv::Mat bgr = to_bgr8(image);
  std::atomic<size_t> next{0};
  // Worker k embeds, with network k, the next crop not yet taken until none is left; worker 0 is
  // this thread. The first error stops the others after their crop in hand.
  const size_t workers = std::min(nets_.size(), boxes.size());
  std::vector<std::exception_ptr> errors(workers);
  auto work = [&](size_t k) {
    try {
      for (size_t i = next++; i < boxes.size(); i = next++) {
        try {
          out[i] = embed_crop(nets_[k], rewrites_, bgr, boxes[i]);
        } catch (const std::invalid_argument&) {
          out[i].resize(0);  // a sliver: no appearance
        }
      }
    } catch (...) {
      errors[k] = std::current_exception();
      next = boxes.size();
    }
  };
  std::vector<std::thread> threads;
  for (size_t k = 1; k < workers; ++k) {
    try {
      threads.emplace_back(work, k);
    } catch (const std::system_error&) {
      break;  // no thread to be had: the threads started (and this one) share the crops
    }
  }
  work(0);
  for (auto& t : threads) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

}  // namespace wardmap::semantics
