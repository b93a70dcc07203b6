#include "semantics/detection/silu_layer.h"

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/dnn/layer.details.hpp>

#include "semantics/detection/float_lanes.h"

namespace wardmap::semantics {

namespace {

// Pure arithmetic on buffers its caller owns, run millions of times a forward: left out of
// ThreadSanitizer's instrumentation, which made one YOLOX forward take seconds.
#define WARDMAP_SILU_KERNEL __attribute__((always_inline, no_sanitize("thread"))) inline

// dst[0..W) = x / (1 + exp(-x)) for x = src[0..W). exp: range reduction by ln 2 in two parts, then
// Cephes' expf polynomial, then 2^n from the exponent bits. -x is clamped to [-87, 88] (exp stays a
// normal float), which changes no result: sigmoid is then 0 or 1 to float precision. Vectors are
// loaded and stored here, never passed: their ABI differs with and without AVX.
template <int W>
WARDMAP_SILU_KERNEL void silu_lanes(const float* src, float* dst) {
  using F = typename Lanes<W>::F;
  using I = typename Lanes<W>::I;
  using Load = typename Lanes<W>::Load;
  const F x = *reinterpret_cast<const Load*>(src);
  F t = -x;
  t = t > 88.0f ? F{} + 88.0f : t;
  t = t < -87.0f ? F{} - 87.0f : t;
  const F round = F{} + 12582912.0f;  // 1.5 * 2^23: adding and taking it away rounds to an integer
  const F n = (t * 1.44269504088896341f + round) - round;
  F r = t - n * 0.693359375f;
  r = r + n * 2.12194440e-4f;
  F p = F{} + 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  p = p * (r * r) + r + 1.0f;
  const I exponent = (__builtin_convertvector(n, I) + 127) << 23;
  const F scale = (F)exponent;  // a vector cast keeps the bits
  *reinterpret_cast<Load*>(dst) = x / (1.0f + p * scale);
}

template <int W>
WARDMAP_SILU_KERNEL void silu_loop(const float* src, float* dst, std::size_t n) {
  std::size_t i = 0;
  for (; i + W <= n; i += W) silu_lanes<W>(src + i, dst + i);
  if (i == n) return;
  float in[W] = {}, out[W];
  for (std::size_t k = 0; k < n - i; ++k) in[k] = src[i + k];
  silu_lanes<W>(in, out);
  for (std::size_t k = 0; k < n - i; ++k) dst[i + k] = out[k];
}

#ifdef WARDMAP_X86_SIMD
__attribute__((target("avx2,fma"), no_sanitize("thread"))) void silu_8lanes(const float* src, float* dst, std::size_t n) {
  silu_loop<8>(src, dst, n);
}
#endif

// The layer. As an ActivationLayer it is fused into a convolution before it (forwardSlice on each
// output stripe); forward covers the other cases.
class SiluLayer : public cv::dnn::ActivationLayer {
 public:
  explicit SiluLayer(const cv::dnn::LayerParams& params) { setParamsFrom(params); }

  static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams& params) {
    return cv::Ptr<cv::dnn::Layer>(new SiluLayer(params));
  }

  bool getMemoryShapes(const std::vector<cv::dnn::MatShape>& inputs, int /*required_outputs*/,
                       std::vector<cv::dnn::MatShape>& outputs,
                       std::vector<cv::dnn::MatShape>& /*internals*/) const override {
    outputs = inputs;
    return true;  // in place
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
               cv::OutputArrayOfArrays /*internals*/) override {
    std::vector<cv::Mat> inputs, outputs;
    inputs_arr.getMatVector(inputs);
    outputs_arr.getMatVector(outputs);
    for (size_t k = 0; k < inputs.size(); ++k) {
      CV_Assert(inputs[k].type() == CV_32F && inputs[k].isContinuous() && outputs[k].isContinuous() &&
                inputs[k].total() == outputs[k].total());
      const float* src = inputs[k].ptr<float>();
      float* dst = outputs[k].ptr<float>();
      const std::size_t total = inputs[k].total();
      constexpr std::size_t kStripe = 1 << 14;
      cv::parallel_for_(cv::Range(0, static_cast<int>((total + kStripe - 1) / kStripe)), [&](const cv::Range& r) {
        const std::size_t begin = static_cast<std::size_t>(r.start) * kStripe;
        const std::size_t end = std::min(total, static_cast<std::size_t>(r.end) * kStripe);
        silu(src + begin, dst + begin, end - begin);
      });
    }
  }

  // Channels [cn0, cn1) of a convolution's output, `len` values each, planes `plane_size` apart.
  void forwardSlice(const float* src, float* dst, int len, size_t plane_size, int cn0, int cn1) const override {
    for (int c = cn0; c < cn1; ++c, src += plane_size, dst += plane_size) silu(src, dst, static_cast<std::size_t>(len));
  }
};

}  // namespace

__attribute__((no_sanitize("thread"))) void silu_4lanes(const float* src, float* dst, std::size_t n) {
  silu_loop<4>(src, dst, n);
}

void silu(const float* src, float* dst, std::size_t n) {
#ifdef WARDMAP_X86_SIMD
  if (cpu_has_avx2_fma()) return silu_8lanes(src, dst, n);
#endif
  silu_4lanes(src, dst, n);
}

void register_silu_layer() {
  static std::once_flag once;
  std::call_once(once, [] { cv::dnn::LayerFactory::registerLayer(kSiluOpType, SiluLayer::create); });
}

}  // namespace wardmap::semantics
