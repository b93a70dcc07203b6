// The protobuf wire reader/writer and the folding of a strided-slice input stage (onnx_fold.h): on a
// small Focus model built here, and on the shipped YOLOX-nano when ../shared/models has it. The
// folded network must give exactly the output of the original on the same image. Also the SiLU
// fusion (fuse_silu) and its layer's kernel (silu_layer.h): the same output up to float rounding.
#include "semantics/detection/onnx_fold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <opencv2/dnn.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "semantics/detection/depthwise_layer.h"
#include "semantics/detection/embedder.h"
#include "semantics/detection/letterbox.h"
#include "semantics/detection/model_description.h"
#include "semantics/detection/model_search.h"
#include "semantics/detection/onnx_net.h"
#include "semantics/detection/pointwise_layer.h"
#include "semantics/detection/protobuf_wire.h"
#include "semantics/detection/silu_layer.h"
#include "semantics/detection/small_conv_layer.h"
#include "tests/semantics/detection/detection_test_support.h"

namespace wardmap::semantics {
namespace {

using wire::bytes_field;
using wire::serialize;
using wire::varint_field;

// --- a tiny ONNX builder (onnx.proto field numbers) ---
std::string int64_tensor(const std::string& name, const std::vector<std::int64_t>& values) {
  std::string packed;
  for (std::int64_t v : values) packed += serialize({varint_field(1, static_cast<std::uint64_t>(v))}).substr(1);
  return serialize({varint_field(1, values.size()), varint_field(2, 7), bytes_field(7, packed), bytes_field(8, name)});
}
std::string node(const std::string& op, const std::vector<std::string>& in, const std::vector<std::string>& out,
                 const std::vector<std::string>& attributes = {}) {
  std::vector<wire::Field> f;
  for (const auto& s : in) f.push_back(bytes_field(1, s));
  for (const auto& s : out) f.push_back(bytes_field(2, s));
  f.push_back(bytes_field(4, op));
  for (const auto& a : attributes) f.push_back(bytes_field(5, a));
  return serialize(f);
}
std::string int_attribute(const std::string& name, std::int64_t v) {
  return serialize({bytes_field(1, name), varint_field(3, static_cast<std::uint64_t>(v)), varint_field(20, 2)});
}
std::string float_value(const std::string& name, const std::vector<int>& dims) {
  std::vector<wire::Field> shape;
  for (int d : dims) shape.push_back(bytes_field(1, serialize({varint_field(1, d)})));
  const std::string tensor = serialize({varint_field(1, 1), bytes_field(2, serialize(shape))});
  return serialize({bytes_field(1, name), bytes_field(2, serialize({bytes_field(1, tensor)}))});
}

struct FocusSpec {
  int step = 2;
  bool slice_output_is_graph_output = false;
  int chains = 4;
};

// x (1x3x4x6) -> YOLOX's Focus (H then W slices; concat top-left, bottom-left, top-right,
// bottom-right) -> Relu -> y.
std::string focus_model(const FocusSpec& spec = {}) {
  std::vector<wire::Field> g;
  const std::int64_t big = 9223372036854775807LL;
  for (const auto& [name, v] : std::vector<std::pair<std::string, std::int64_t>>{
           {"zero", 0}, {"one", 1}, {"end", big}, {"h", 2}, {"w", 3}, {"step", spec.step}})
    g.push_back(bytes_field(5, int64_tensor(name, {v})));
  const std::vector<std::pair<std::string, std::string>> phases = {
      {"zero", "zero"}, {"one", "zero"}, {"zero", "one"}, {"one", "one"}};
  std::vector<std::string> ends;
  for (int k = 0; k < spec.chains; ++k) {
    const std::string a = "rows" + std::to_string(k), b = "phase" + std::to_string(k);
    g.push_back(bytes_field(1, node("Slice", {"x", phases[k].first, "end", "h", "step"}, {a})));
    g.push_back(bytes_field(1, node("Slice", {a, phases[k].second, "end", "w", "step"}, {b})));
    ends.push_back(b);
  }
  g.push_back(bytes_field(1, node("Concat", ends, {"focus"}, {int_attribute("axis", 1)})));
  g.push_back(bytes_field(1, node("Relu", {"focus"}, {"y"})));
  g.push_back(bytes_field(2, "focus_test"));
  g.push_back(bytes_field(11, float_value("x", {1, 3, 4, 6})));
  g.push_back(bytes_field(12, float_value("y", {1, 3 * spec.chains, 2, 3})));
  if (spec.slice_output_is_graph_output) g.push_back(bytes_field(12, float_value("rows0", {1, 3, 2, 6})));
  const std::string opset = serialize({bytes_field(1, ""), varint_field(2, 11)});
  return serialize(
      {varint_field(1, 7), bytes_field(2, "wardmap-test"), bytes_field(7, serialize(g)), bytes_field(8, opset)});
}

enum class SiluShape { kXTimesSigmoid, kSigmoidTimesX, kGate, kSigmoidAlsoOutput, kSigmoidUsedTwice };

// x (1x2x3x4) -> Sigmoid -> s; Mul(x, s) -> m; m -> Relu -> y, with the variations of SiluShape:
// the Mul's inputs swapped, a gate (Sigmoid of another tensor times x: OSNet's channel gate, not
// a SiLU), the Sigmoid's output also a graph output, or also read by a second node.
std::string silu_model(SiluShape shape) {
  std::vector<wire::Field> g;
  const std::string gated = shape == SiluShape::kGate ? "g" : "x";
  if (shape == SiluShape::kGate) g.push_back(bytes_field(1, node("Relu", {"x"}, {"g"})));
  g.push_back(bytes_field(1, node("Sigmoid", {gated}, {"s"})));
  g.push_back(bytes_field(1, node("Mul", shape == SiluShape::kSigmoidTimesX ? std::vector<std::string>{"s", "x"}
                                                                                : std::vector<std::string>{"x", "s"},
                                  {"m"})));
  if (shape == SiluShape::kSigmoidUsedTwice) {
    g.push_back(bytes_field(1, node("Add", {"m", "s"}, {"a"})));
    g.push_back(bytes_field(1, node("Relu", {"a"}, {"y"})));
  } else {
    g.push_back(bytes_field(1, node("Relu", {"m"}, {"y"})));
  }
  g.push_back(bytes_field(2, "silu_test"));
  g.push_back(bytes_field(11, float_value("x", {1, 2, 3, 4})));
  g.push_back(bytes_field(12, float_value("y", {1, 2, 3, 4})));
  if (shape == SiluShape::kSigmoidAlsoOutput) g.push_back(bytes_field(12, float_value("s", {1, 2, 3, 4})));
  const std::string opset = serialize({bytes_field(1, ""), varint_field(2, 11)});
  return serialize(
      {varint_field(1, 7), bytes_field(2, "wardmap-test"), bytes_field(7, serialize(g)), bytes_field(8, opset)});
}

std::string ints_attribute(const std::string& name, const std::vector<std::int64_t>& values) {
  std::vector<wire::Field> f = {bytes_field(1, name)};
  for (std::int64_t v : values) f.push_back(varint_field(8, static_cast<std::uint64_t>(v)));
  f.push_back(varint_field(20, 7));
  return serialize(f);
}

struct PoolSpec {
  std::vector<int> kernels = {5, 9, 13};
  int stride = 1;
  bool same_padding = true;
  int ceil_mode = 0;
};

// x (1x2x9x11) -> a MaxPool of x per kernel (YOLOX's SPP) -> Concat(x, the pools) -> y.
std::string pool_model(const PoolSpec& spec = {}) {
  std::vector<wire::Field> g;
  std::vector<std::string> cat = {"x"};
  for (int k : spec.kernels) {
    const std::int64_t p = spec.same_padding ? k / 2 : 0;
    const std::string out = "pool" + std::to_string(k);
    g.push_back(bytes_field(1, node("MaxPool", {"x"}, {out},
                                    {int_attribute("ceil_mode", spec.ceil_mode), ints_attribute("kernel_shape", {k, k}),
                                     ints_attribute("pads", {p, p, p, p}), ints_attribute("strides", {spec.stride, spec.stride})})));
    cat.push_back(out);
  }
  g.push_back(bytes_field(1, node("Concat", cat, {"y"}, {int_attribute("axis", 1)})));
  g.push_back(bytes_field(2, "pool_test"));
  g.push_back(bytes_field(11, float_value("x", {1, 2, 9, 11})));
  g.push_back(bytes_field(12, float_value("y", {1, 2 * static_cast<int>(cat.size()), 9, 11})));
  const std::string opset = serialize({bytes_field(1, ""), varint_field(2, 11)});
  return serialize(
      {varint_field(1, 7), bytes_field(2, "wardmap-test"), bytes_field(7, serialize(g)), bytes_field(8, opset)});
}

// Each node's inputs and, for a MaxPool, its kernel_shape, in order.
std::vector<std::pair<std::vector<std::string>, std::vector<std::int64_t>>> pool_wiring(const std::string& onnx) {
  std::vector<std::pair<std::vector<std::string>, std::vector<std::int64_t>>> out;
  for (const wire::Field& f : wire::parse(onnx))
    if (f.number == 7)
      for (const std::string& n : wire::strings(wire::parse(f.bytes), 1)) {
        const std::vector<wire::Field> fields = wire::parse(n);
        std::vector<std::int64_t> kernel;
        for (const std::string& a : wire::strings(fields, 5)) {
          const std::vector<wire::Field> af = wire::parse(a);
          if (wire::strings(fields, 4).front() == "MaxPool" && wire::strings(af, 1).front() == "kernel_shape")
            kernel = wire::varints(af, 8);
        }
        out.emplace_back(wire::strings(fields, 1), kernel);
      }
  return out;
}

// The op types of a model's nodes, in order.
std::vector<std::string> op_types(const std::string& onnx) {
  std::vector<std::string> ops;
  for (const wire::Field& f : wire::parse(onnx))
    if (f.number == 7)
      for (const std::string& n : wire::strings(wire::parse(f.bytes), 1))
        ops.push_back(wire::strings(wire::parse(n), 4).front());
  return ops;
}

cv::Mat forward(const std::string& onnx, const cv::Mat& blob) {
  cv::dnn::Net net = cv::dnn::readNetFromONNX(onnx.data(), onnx.size());
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setInput(blob);
  return net.forward().clone();
}

TEST(ProtobufWire, ParsesWhatItWritesAndRejectsTruncatedMessages) {
  const std::vector<wire::Field> fields = {varint_field(1, 300), bytes_field(2, "abc"), varint_field(3, ~0ULL),
                                           bytes_field(15, std::string(200, 'x'))};
  const std::string bytes = serialize(fields);
  const std::vector<wire::Field> back = wire::parse(bytes);
  ASSERT_EQ(back.size(), 4u);
  EXPECT_EQ(back[0].varint, 300u);
  EXPECT_EQ(back[1].bytes, "abc");
  EXPECT_EQ(static_cast<std::int64_t>(back[2].varint), -1);
  EXPECT_EQ(back[3].number, 15u);
  EXPECT_EQ(serialize(back), bytes);
  EXPECT_THROW(wire::parse(bytes.substr(0, bytes.size() - 1)), std::runtime_error);
  EXPECT_THROW(wire::parse(std::string("\x0b", 1)), std::runtime_error);  // group start
  // Packed and unpacked repeated varints read the same.
  const std::string packed = serialize({varint_field(1, 5)}).substr(1) + serialize({varint_field(1, 7)}).substr(1);
  EXPECT_EQ(wire::varints({bytes_field(4, packed)}, 4), (std::vector<std::int64_t>{5, 7}));
  EXPECT_EQ(wire::varints({varint_field(4, 5), varint_field(4, 7)}, 4), (std::vector<std::int64_t>{5, 7}));
}

TEST(OnnxFold, FocusStageIsFoldedAndTheOutputIsUnchanged) {
  const std::string onnx = focus_model();
  const auto folded = fold_space_to_depth_input(onnx);
  ASSERT_TRUE(folded.has_value());
  EXPECT_EQ(folded->input.channels, 3);
  EXPECT_EQ(folded->input.height, 4);
  EXPECT_EQ(folded->input.width, 6);
  const std::vector<std::array<int, 2>> expected = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  EXPECT_EQ(folded->input.offsets, expected);

  const int dims[4] = {1, 3, 4, 6};
  cv::Mat blob(4, dims, CV_32F);
  cv::randu(blob, 0.0, 255.0);
  const cv::Mat reference = forward(onnx, blob);
  const cv::Mat rearranged = folded->input.apply(blob);
  ASSERT_EQ(rearranged.size[1], 12);
  const cv::Mat out = forward(folded->onnx, rearranged);
  ASSERT_EQ(out.total(), reference.total());
  EXPECT_EQ(cv::norm(out.reshape(1, 1), reference.reshape(1, 1), cv::NORM_INF), 0.0);
  // A hand check: channel 3 (bottom-left block, channel 0) at (0, 1) is x[0][1][2].
  EXPECT_EQ(rearranged.ptr<float>()[3 * 2 * 3 + 1], blob.ptr<float>()[1 * 6 + 2]);

  // Another even size (a smaller letterbox canvas) is rearranged the same way; odd sides and other
  // channel counts are refused.
  const int other[4] = {1, 3, 2, 8};
  cv::Mat small(4, other, CV_32F);
  cv::randu(small, 0.0, 255.0);
  const cv::Mat small_out = folded->input.apply(small);
  ASSERT_EQ(small_out.size[2], 1);
  ASSERT_EQ(small_out.size[3], 4);
  EXPECT_EQ(small_out.ptr<float>()[3 * 1 * 4 + 2], small.ptr<float>()[1 * 8 + 4]);  // block 1 (row phase 1), x = 2
  const int odd[4] = {1, 3, 4, 7}, channels[4] = {1, 4, 4, 6};
  EXPECT_THROW(folded->input.apply(cv::Mat(4, odd, CV_32F)), std::invalid_argument);
  EXPECT_THROW(folded->input.apply(cv::Mat(4, channels, CV_32F)), std::invalid_argument);
}

TEST(OnnxFold, OtherGraphsAreLeftAlone) {
  FocusSpec step1;
  step1.step = 1;
  EXPECT_FALSE(fold_space_to_depth_input(focus_model(step1)).has_value());
  FocusSpec exposed;
  exposed.slice_output_is_graph_output = true;
  EXPECT_FALSE(fold_space_to_depth_input(focus_model(exposed)).has_value());
  FocusSpec three;
  three.chains = 3;
  EXPECT_FALSE(fold_space_to_depth_input(focus_model(three)).has_value());
  EXPECT_THROW(fold_space_to_depth_input("\x0a\x05"
                                         "ab"),
               std::runtime_error);  // truncated
}

TEST(Silu, KernelMatchesTheFormulaWithStdExp) {
  // Every length up to 19 (the 8- and 4-lane loops' tails), in place and not, values from -100 to
  // 100 and the clamp's edges.
  std::vector<float> values = {0.0f, -0.0f, 1e-30f, -1e-30f, 87.0f, -87.0f, 88.0f, -88.0f, 90.0f, -90.0f, 100.0f, -100.0f};
  for (int i = -2000; i <= 2000; ++i) values.push_back(static_cast<float>(i) * 0.037f);
  for (void (*kernel)(const float*, float*, std::size_t) : {&silu, &silu_4lanes}) {
    std::vector<float> out(values.size());
    kernel(values.data(), out.data(), values.size());
    for (size_t i = 0; i < values.size(); ++i) {
      const double x = values[i], expected = x / (1.0 + std::exp(-x));
      EXPECT_NEAR(out[i], expected, 1e-6 * std::abs(expected) + 1e-30) << "x = " << x;
    }
    for (std::size_t n = 0; n <= 19; ++n) {
      std::vector<float> in(values.begin() + 100, values.begin() + 100 + static_cast<long>(n)), copy = in;
      std::vector<float> separate(n + 1, -7.0f);
      kernel(in.data(), separate.data(), n);
      kernel(copy.data(), copy.data(), n);  // in place
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(copy[i], separate[i]);
        EXPECT_NEAR(separate[i], in[i] / (1.0 + std::exp(-double{in[i]})), 1e-6);
      }
      EXPECT_EQ(separate[n], -7.0f) << "wrote past the end at n = " << n;
    }
  }
}

TEST(OnnxFold, SiluPairsAreFusedAndTheOutputMatches) {
  register_silu_layer();
  const int dims[4] = {1, 2, 3, 4};
  cv::Mat blob(4, dims, CV_32F);
  cv::randu(blob, -6.0, 6.0);
  for (SiluShape shape : {SiluShape::kXTimesSigmoid, SiluShape::kSigmoidTimesX}) {
    const std::string onnx = silu_model(shape);
    const std::optional<std::string> fused = fuse_silu(onnx);
    ASSERT_TRUE(fused.has_value());
    EXPECT_EQ(op_types(*fused), (std::vector<std::string>{kSiluOpType, "Relu"}));
    const cv::Mat reference = forward(onnx, blob), out = forward(*fused, blob);
    ASSERT_EQ(out.total(), reference.total());
    EXPECT_LE(cv::norm(out.reshape(1, 1), reference.reshape(1, 1), cv::NORM_INF), 1e-5);
    EXPECT_GT(cv::norm(out.reshape(1, 1), cv::NORM_INF), 0.5);  // not all zero
  }
}

TEST(OnnxFold, SigmoidsThatAreNotSiluAreLeftAlone) {
  for (SiluShape shape : {SiluShape::kGate, SiluShape::kSigmoidAlsoOutput, SiluShape::kSigmoidUsedTwice})
    EXPECT_FALSE(fuse_silu(silu_model(shape)).has_value()) << static_cast<int>(shape);
  EXPECT_FALSE(fuse_silu(focus_model()).has_value());
  EXPECT_THROW(fuse_silu("\x0a\x05"
                         "ab"),
               std::runtime_error);  // truncated
}

TEST(OnnxFold, SideBySideMaxPoolsAreChainedAndTheOutputIsUnchanged) {
  const std::string onnx = pool_model();
  const std::optional<std::string> chained = cascade_max_pools(onnx);
  ASSERT_TRUE(chained.has_value());
  EXPECT_EQ(op_types(*chained), op_types(onnx));
  const auto wiring = pool_wiring(*chained);
  ASSERT_EQ(wiring.size(), 4u);
  EXPECT_EQ(wiring[0].first, std::vector<std::string>{"x"});
  EXPECT_EQ(wiring[1].first, std::vector<std::string>{"pool5"});  // 9 = 5 then 5
  EXPECT_EQ(wiring[2].first, std::vector<std::string>{"pool9"});  // 13 = 9 then 5
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(wiring[i].second, (std::vector<std::int64_t>{5, 5})) << i;

  // Negative values too: a pool that counted the padding as 0 would differ at the borders.
  const int dims[4] = {1, 2, 9, 11};
  cv::Mat blob(4, dims, CV_32F);
  cv::randu(blob, -5.0, 5.0);
  const cv::Mat reference = forward(onnx, blob), out = forward(*chained, blob);
  ASSERT_EQ(out.total(), reference.total());
  EXPECT_EQ(cv::norm(out.reshape(1, 1), reference.reshape(1, 1), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(out.reshape(1, 1), cv::NORM_INF), 4.0);

  // Kernels 3 and 7: the second reads the first with 5.
  PoolSpec two;
  two.kernels = {3, 7};
  const std::optional<std::string> chained2 = cascade_max_pools(pool_model(two));
  ASSERT_TRUE(chained2.has_value());
  EXPECT_EQ(pool_wiring(*chained2)[1].second, (std::vector<std::int64_t>{5, 5}));
  EXPECT_EQ(cv::norm(forward(*chained2, blob).reshape(1, 1), forward(pool_model(two), blob).reshape(1, 1), cv::NORM_INF),
            0.0);
}

TEST(OnnxFold, OtherMaxPoolsAreLeftAlone) {
  PoolSpec one, strided, unpadded, ceil, shrinking, equal;
  one.kernels = {5};
  strided.stride = 2;
  unpadded.same_padding = false;
  ceil.ceil_mode = 1;
  shrinking.kernels = {13, 9, 5};  // the chain's inputs would come after their users
  equal.kernels = {5, 5};
  for (const PoolSpec& spec : {one, strided, unpadded, ceil, shrinking, equal})
    EXPECT_FALSE(cascade_max_pools(pool_model(spec)).has_value()) << spec.kernels.size() << " " << spec.stride;
  EXPECT_FALSE(cascade_max_pools(focus_model()).has_value());
  EXPECT_THROW(cascade_max_pools("\x0a\x05"
                                 "ab"),
               std::runtime_error);  // truncated
}

enum class TransposeShape { kOutput, kOtherPerm, kAlsoReadElsewhere, kNotAnOutput, kOutputReadOn };

// x (1x3x5) -> Relu -> r -> Transpose (0, 2, 1) -> y, with the variations of TransposeShape: another
// perm, r also read by a second node (a graph output z), the Transpose's output read on (by a Relu
// making y), y both an output and read on (by a Relu making z).
std::string transpose_model(TransposeShape shape) {
  std::vector<wire::Field> g;
  g.push_back(bytes_field(1, node("Relu", {"x"}, {"r"})));
  const std::vector<std::int64_t> perm =
      shape == TransposeShape::kOtherPerm ? std::vector<std::int64_t>{0, 1, 2} : std::vector<std::int64_t>{0, 2, 1};
  const std::string t = shape == TransposeShape::kNotAnOutput ? "t" : "y";
  g.push_back(bytes_field(1, node("Transpose", {"r"}, {t}, {ints_attribute("perm", perm)})));
  if (shape == TransposeShape::kNotAnOutput) g.push_back(bytes_field(1, node("Relu", {"t"}, {"y"})));
  if (shape == TransposeShape::kAlsoReadElsewhere) g.push_back(bytes_field(1, node("Relu", {"r"}, {"z"})));
  if (shape == TransposeShape::kOutputReadOn) g.push_back(bytes_field(1, node("Relu", {"y"}, {"z"})));
  g.push_back(bytes_field(2, "transpose_test"));
  g.push_back(bytes_field(11, float_value("x", {1, 3, 5})));
  g.push_back(bytes_field(12, float_value("y", {1, 5, 3})));
  if (shape == TransposeShape::kAlsoReadElsewhere) g.push_back(bytes_field(12, float_value("z", {1, 3, 5})));
  if (shape == TransposeShape::kOutputReadOn) g.push_back(bytes_field(12, float_value("z", {1, 5, 3})));
  const std::string opset = serialize({bytes_field(1, ""), varint_field(2, 11)});
  return serialize(
      {varint_field(1, 7), bytes_field(2, "wardmap-test"), bytes_field(7, serialize(g)), bytes_field(8, opset)});
}

TEST(OnnxFold, OutputTransposeIsLeftToTheCallerAndTheOutputIsUnchanged) {
  const std::string onnx = transpose_model(TransposeShape::kOutput);
  const std::optional<FoldedOutputs> folded = fold_output_transposes(onnx);
  ASSERT_TRUE(folded.has_value());
  EXPECT_EQ(folded->outputs, std::vector<std::string>{"y"});
  EXPECT_EQ(op_types(folded->onnx), std::vector<std::string>{"Relu"});
  const int dims[3] = {1, 3, 5};
  cv::Mat blob(3, dims, CV_32F);
  cv::randu(blob, -5.0, 5.0);
  const cv::Mat reference = forward(onnx, blob);
  const cv::Mat raw = forward(folded->onnx, blob);
  ASSERT_EQ(raw.dims, 3);
  EXPECT_EQ(raw.size[1], 3);
  const cv::Mat out = transpose_output(raw);
  ASSERT_EQ(out.dims, 3);
  EXPECT_EQ(out.size[1], 5);
  EXPECT_EQ(out.size[2], 3);
  EXPECT_EQ(cv::norm(out.reshape(1, 1), reference.reshape(1, 1), cv::NORM_INF), 0.0);
  EXPECT_EQ(out.ptr<float>()[1 * 3 + 2], std::max(0.0f, blob.ptr<float>()[2 * 5 + 1]));  // y[0][1][2] = relu(x[0][2][1])
  EXPECT_THROW(transpose_output(cv::Mat(3, 5, CV_32F)), std::invalid_argument);

  for (TransposeShape shape : {TransposeShape::kOtherPerm, TransposeShape::kAlsoReadElsewhere, TransposeShape::kNotAnOutput,
                               TransposeShape::kOutputReadOn})
    EXPECT_FALSE(fold_output_transposes(transpose_model(shape)).has_value()) << static_cast<int>(shape);
  EXPECT_FALSE(fold_output_transposes(focus_model()).has_value());
  EXPECT_THROW(fold_output_transposes("\x0a\x05"
                                      "ab"),
               std::runtime_error);  // truncated
}

TEST(OnnxFold, YoloxNanoRewrittenGivesTheSameOutput) {
  WARDMAP_REQUIRE_MODEL("yolox-nano/yolox_nano_416x416.onnx");
  WARDMAP_REQUIRE_DATA("images");
  const auto file = wardmap::test::shared_models_dir() / "yolox-nano/yolox_nano_416x416.onnx";
  OnnxRewrites rewrites;
  cv::dnn::Net folded = load_onnx_net(file, "missing", rewrites);
  ASSERT_TRUE(rewrites.input.has_value()) << "YOLOX-nano's Focus stage was not recognised";
  const std::vector<std::array<int, 2>> yolox_order = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  EXPECT_EQ(rewrites.input->offsets, yolox_order);
  EXPECT_EQ(rewrites.transposed_outputs, std::vector<std::string>{"output"});
  cv::dnn::Net original = load_onnx_net(file, "missing");
  {  // its SPP block is chained: three 5 x 5 pools
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::optional<std::string> chained = cascade_max_pools(bytes);
    ASSERT_TRUE(chained.has_value()) << "YOLOX-nano's SPP pools were not recognised";
    int pools = 0;
    for (const auto& [inputs, kernel] : pool_wiring(*chained))
      if (!kernel.empty()) {
        EXPECT_EQ(kernel, (std::vector<std::int64_t>{5, 5}));
        ++pools;
      }
    EXPECT_EQ(pools, 3);
  }
  // Each SiLU took the place of a Sigmoid (and a Mul); the heads' own Sigmoids stay.
  const int silus = folded.getLayersCount(kSiluOpType);
  EXPECT_GT(silus, 50);
  EXPECT_EQ(silus, original.getLayersCount("Sigmoid") - folded.getLayersCount("Sigmoid"));
  // Its stem (12 -> 16 channels after the Focus fold) runs on small_conv_layer.h; no other conv.
  EXPECT_EQ(folded.getLayersCount(kSmallConvOpType), 1);
  EXPECT_EQ(original.getLayersCount("Convolution") - folded.getLayersCount("Convolution"), 1);

  ModelDescription model = load_model_description(model_descriptions_dir() / "yolox-nano.yaml");
  const cv::Mat image = cv::imread((wardmap::test::shared_data_dir() / "images" / "bus.jpg").string());
  ASSERT_FALSE(image.empty());
  // The full 416x416 canvas and the one cut to the image (810x1080: 352x416), as shipped.
  ASSERT_EQ(model.input.canvas_multiple, 32);
  for (int multiple : {0, 32}) {
    model.input.canvas_multiple = multiple;
    const Letterbox lb = make_letterbox(image, model.input);
    EXPECT_EQ(lb.canvas, multiple ? cv::Size(352, 416) : cv::Size(416, 416));
    original.setInput(lb.blob);
    folded.setInput(rewrites.prepare_input(lb.blob));
    const cv::Mat a = original.forward().clone(), b = rewrites.restore_output("output", folded.forward("output"));
    ASSERT_EQ(a.total(), b.total());
    EXPECT_EQ(a.size[1], (lb.canvas.width / 8) * (lb.canvas.height / 8) + (lb.canvas.width / 16) * (lb.canvas.height / 16) +
                             (lb.canvas.width / 32) * (lb.canvas.height / 32));
    EXPECT_LE(cv::norm(a.reshape(1, 1), b.reshape(1, 1), cv::NORM_INF), 1e-4);
  }
}

std::string float_tensor(const std::string& name, const std::vector<std::int64_t>& dims, const std::vector<float>& values) {
  std::vector<wire::Field> f;
  for (std::int64_t d : dims) f.push_back(varint_field(1, static_cast<std::uint64_t>(d)));
  f.push_back(varint_field(2, 1));  // FLOAT
  f.push_back(bytes_field(8, name));
  f.push_back(bytes_field(9, std::string(reinterpret_cast<const char*>(values.data()), 4 * values.size())));
  return serialize(f);
}

struct DepthwiseSpec {
  int channels = 3, kernel = 3, stride = 1, pad = 1;
  int out_channels = 0;   // 0: = channels
  int height = 5, width = 7;  // the input's
  int group = 3;          // = channels: depthwise
  bool bias = true;
  bool relu = true;       // a Relu after it (fused into the layer)
  bool weight_is_input = false;  // the weights a graph input, not a constant
};

// x (1 x C x H x W, 5 x 7 unless the spec says) -> Conv (C -> C' channels in the spec's groups, kernel, stride and padding) -> [Relu] -> y.
std::string depthwise_model(const DepthwiseSpec& spec, unsigned seed = 1) {
  std::vector<wire::Field> g;
  cv::RNG rng(seed);
  const int in_per_group = spec.channels / spec.group;
  const int outs = spec.out_channels > 0 ? spec.out_channels : spec.channels;
  std::vector<float> w(static_cast<size_t>(outs * in_per_group * spec.kernel * spec.kernel)), b(outs);
  for (float& v : w) v = static_cast<float>(rng.uniform(-1.0, 1.0));
  for (float& v : b) v = static_cast<float>(rng.uniform(-1.0, 1.0));
  if (!spec.weight_is_input)
    g.push_back(bytes_field(5, float_tensor("w", {outs, in_per_group, spec.kernel, spec.kernel}, w)));
  if (spec.bias) g.push_back(bytes_field(5, float_tensor("b", {outs}, b)));
  std::vector<std::string> in = {"x", "w"};
  if (spec.bias) in.push_back("b");
  const std::string conv_out = spec.relu ? "c" : "y";
  g.push_back(bytes_field(1, node("Conv", in, {conv_out},
                                  {int_attribute("group", spec.group), ints_attribute("kernel_shape", {spec.kernel, spec.kernel}),
                                   ints_attribute("pads", {spec.pad, spec.pad, spec.pad, spec.pad}),
                                   ints_attribute("strides", {spec.stride, spec.stride})})));
  if (spec.relu) g.push_back(bytes_field(1, node("Relu", {"c"}, {"y"})));
  g.push_back(bytes_field(2, "depthwise_test"));
  g.push_back(bytes_field(11, float_value("x", {1, spec.channels, spec.height, spec.width})));
  if (spec.weight_is_input)
    g.push_back(bytes_field(11, float_value("w", {outs, in_per_group, spec.kernel, spec.kernel})));
  const int oh = (spec.height + 2 * spec.pad - spec.kernel) / spec.stride + 1;
  const int ow = (spec.width + 2 * spec.pad - spec.kernel) / spec.stride + 1;
  g.push_back(bytes_field(12, float_value("y", {1, outs, oh, ow})));
  const std::string opset = serialize({bytes_field(1, ""), varint_field(2, 11)});
  return serialize(
      {varint_field(1, 7), bytes_field(2, "wardmap-test"), bytes_field(7, serialize(g)), bytes_field(8, opset)});
}

// Runs the model and its rewrite on one random input of the spec's shape. The outputs must agree
// within `tolerance` and not be all zero, and the rewrite must apply the Relu exactly where the
// spec has one (no negative value with it, some without). Returns the rewrite's output, empty when
// the two sizes differ.
cv::Mat expect_same_output(const std::string& onnx, const std::string& replaced, const DepthwiseSpec& spec,
                           double tolerance, const std::string& what) {
  const int dims[4] = {1, spec.channels, spec.height, spec.width};
  cv::Mat blob(4, dims, CV_32F);
  cv::randu(blob, -3.0, 3.0);
  const cv::Mat reference = forward(onnx, blob), out = forward(replaced, blob);
  EXPECT_EQ(out.total(), reference.total()) << what;
  if (out.total() != reference.total()) return {};
  EXPECT_LE(cv::norm(out.reshape(1, 1), reference.reshape(1, 1), cv::NORM_INF), tolerance) << what;
  EXPECT_GT(cv::norm(out.reshape(1, 1), cv::NORM_INF), 0.5) << what;  // not all zero
  double least = 0;
  cv::minMaxIdx(out.reshape(1, 1), &least);
  if (spec.relu) EXPECT_GE(least, 0.0) << what;  // the Relu was applied ...
  else EXPECT_LT(least, 0.0) << what;            // ... and only where there is one
  return out;
}

TEST(Depthwise, KernelMatchesTheDefinition) {
  cv::RNG rng(7);
  for (const auto& [h, w] : std::vector<std::pair<int, int>>{{1, 1}, {1, 5}, {4, 1}, {2, 2}, {7, 9}, {16, 33}}) {
    std::vector<float> src(static_cast<size_t>(h * w)), k(9), padded(static_cast<size_t>((h + 2) * (w + 2)), 123.0f);
    for (float& v : src) v = static_cast<float>(rng.uniform(-3.0, 3.0));
    for (float& v : k) v = static_cast<float>(rng.uniform(-1.0, 1.0));
    std::vector<float> dst(static_cast<size_t>(h * w) + 1, -7.0f);
    depthwise_conv3x3(src.data(), dst.data(), h, w, k.data(), 0.25f, padded.data());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double expected = 0.25;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int sy = y + i - 1, sx = x + j - 1;
            if (sy >= 0 && sy < h && sx >= 0 && sx < w) expected += double{k[3 * i + j]} * src[sy * w + sx];
          }
        EXPECT_NEAR(dst[y * w + x], expected, 1e-5) << h << "x" << w << " at " << y << "," << x;
      }
    EXPECT_EQ(dst[static_cast<size_t>(h * w)], -7.0f) << "wrote past the end at " << h << "x" << w;
  }
}

TEST(OnnxFold, DepthwiseConvsAreReplacedAndTheOutputMatches) {
  register_depthwise_layer();
  for (bool bias : {true, false})
    for (bool relu : {true, false}) {
      DepthwiseSpec spec;
      spec.bias = bias;
      spec.relu = relu;
      const std::string onnx = depthwise_model(spec);
      const std::optional<std::string> replaced = replace_depthwise_convs(onnx);
      ASSERT_TRUE(replaced.has_value()) << bias << relu;
      EXPECT_EQ(op_types(*replaced).front(), kDepthwiseOpType);
      expect_same_output(onnx, *replaced, spec, 1e-5, std::to_string(bias) + std::to_string(relu));
    }
}

TEST(OnnxFold, OtherConvsAreLeftAlone) {
  DepthwiseSpec strided, dense, five, unpadded, input_weights;
  strided.stride = 2;
  dense.group = 1;  // an ordinary convolution
  five.kernel = 5;
  five.pad = 2;
  unpadded.pad = 0;
  input_weights.weight_is_input = true;
  for (const DepthwiseSpec& spec : {strided, dense, five, unpadded, input_weights})
    EXPECT_FALSE(replace_depthwise_convs(depthwise_model(spec)).has_value())
        << spec.stride << spec.group << spec.kernel << spec.pad << spec.weight_is_input;
  EXPECT_FALSE(replace_depthwise_convs(focus_model()).has_value());
  EXPECT_THROW(replace_depthwise_convs("\x0a\x05"
                                       "ab"),
               std::runtime_error);  // truncated
}

TEST(OnnxFold, OsnetRewrittenGivesTheSameEmbedding) {
  WARDMAP_REQUIRE_MODEL("osnet-x0_25/osnet_x0_25_msmt17.onnx");
  WARDMAP_REQUIRE_DATA("images");
  const auto file = wardmap::test::shared_models_dir() / "osnet-x0_25/osnet_x0_25_msmt17.onnx";
  OnnxRewrites rewrites;
  cv::dnn::Net rewritten = load_onnx_net(file, "missing", rewrites, /*few_channel_convs=*/true);
  EXPECT_FALSE(rewrites.input.has_value());
  EXPECT_TRUE(rewrites.transposed_outputs.empty());
  cv::dnn::Net original = load_onnx_net(file, "missing");
  EXPECT_EQ(rewritten.getLayersCount(kDepthwiseOpType), 60);  // OSNet x0.25's LightConv3x3 blocks
  EXPECT_EQ(rewritten.getLayersCount(kSmallConvOpType), 1);   // its 7 x 7 stem, stride 2
  EXPECT_EQ(rewritten.getLayersCount(kPointwiseOpType), 92);  // 1 x 1 from at most 32 channels
  EXPECT_EQ(original.getLayersCount("Convolution") - rewritten.getLayersCount("Convolution"), 153);

  // A person's crop of bus.jpg through both, and the Embedder (which rewrites) against the original.
  const cv::Mat image = cv::imread((wardmap::test::shared_data_dir() / "images" / "bus.jpg").string());
  ASSERT_FALSE(image.empty());
  cv::Mat crop;
  cv::resize(image(cv::Rect(50, 400, 200, 500)), crop, cv::Size(128, 256));
  const cv::Mat blob = cv::dnn::blobFromImage(crop, 1.0 / 255.0, cv::Size(), cv::Scalar(), true);
  original.setInput(blob);
  rewritten.setInput(blob);
  const cv::Mat a = original.forward().clone(), b = rewritten.forward().clone();
  ASSERT_EQ(a.total(), 512u);
  ASSERT_EQ(b.total(), 512u);
  const double largest = cv::norm(a.reshape(1, 1), cv::NORM_INF);
  EXPECT_GT(largest, 0.1);
  EXPECT_LE(cv::norm(a.reshape(1, 1), b.reshape(1, 1), cv::NORM_INF), 1e-5 * std::max(1.0, largest));
}

TEST(SmallConv, KernelMatchesTheDefinition) {
  // Both shapes the layer runs, with and without padding; output widths below, at and above a
  // vector (4 or 8 lanes) and its multiples; odd and even input sides (stride 2); two output blocks.
  struct Case {
    int kernel, stride, pad, h, w, cin;
  };
  const std::vector<Case> cases = {{3, 1, 1, 1, 1, 1},  {3, 1, 1, 3, 5, 2},  {3, 1, 1, 4, 8, 12}, {3, 1, 1, 5, 17, 3},
                                   {3, 1, 1, 6, 9, 16}, {3, 1, 0, 4, 11, 3}, {7, 2, 3, 1, 1, 1},  {7, 2, 3, 8, 16, 3},
                                   {7, 2, 3, 9, 35, 2}, {7, 2, 3, 16, 33, 3}, {7, 2, 0, 9, 23, 4}, {7, 2, 1, 12, 20, 16}};
  cv::RNG rng(11);
  for (const Case& k : cases) {
    SmallConvGeometry g;
    g.in_channels = k.cin;
    g.out_channels = 16;
    g.kernel = k.kernel;
    g.stride = k.stride;
    g.pad = k.pad;
    g.height = k.h;
    g.width = k.w;
    const int cin = k.cin, cout = g.out_channels, h = k.h, w = k.w, oh = g.out_height(), ow = g.out_width();
    ASSERT_GE(oh, 1);
    ASSERT_GE(ow, 1);
    const int taps = k.kernel * k.kernel;
    std::vector<float> src(static_cast<size_t>(cin * h * w)), weights(static_cast<size_t>(cout * cin * taps)), bias(cout);
    for (float& v : src) v = static_cast<float>(rng.uniform(-3.0, 3.0));
    for (float& v : weights) v = static_cast<float>(rng.uniform(-1.0, 1.0));
    for (float& v : bias) v = static_cast<float>(rng.uniform(-1.0, 1.0));
    std::vector<float> layout(g.layout_floats(), 0.0f);
    small_conv_layout(src.data(), g, layout.data());
    const std::vector<float> packed = small_conv_pack_weights(weights.data(), g);
    std::vector<float> dst(static_cast<size_t>(cout * oh * ow) + 1, -7.0f);
    // In two row ranges, as cv::dnn's threads would.
    small_input_conv(layout.data(), g, packed.data(), bias.data(), dst.data(), 0, oh / 2);
    small_input_conv(layout.data(), g, packed.data(), bias.data(), dst.data(), oh / 2, oh);
    const std::string where = std::to_string(k.kernel) + "/" + std::to_string(k.stride) + "/" + std::to_string(k.pad) +
                              " " + std::to_string(h) + "x" + std::to_string(w) + " cin " + std::to_string(cin);
    for (int o = 0; o < cout; ++o)
      for (int y = 0; y < oh; ++y)
        for (int x = 0; x < ow; ++x) {
          double expected = bias[o];
          for (int c = 0; c < cin; ++c)
            for (int i = 0; i < k.kernel; ++i)
              for (int j = 0; j < k.kernel; ++j) {
                const int sy = k.stride * y + i - k.pad, sx = k.stride * x + j - k.pad;
                if (sy >= 0 && sy < h && sx >= 0 && sx < w)
                  expected += double{weights[((o * cin + c) * k.kernel + i) * k.kernel + j]} * src[(c * h + sy) * w + sx];
              }
          EXPECT_NEAR(dst[(o * oh + y) * ow + x], expected, 1e-4) << where << " at " << o << "," << y << "," << x;
        }
    EXPECT_EQ(dst[static_cast<size_t>(cout * oh * ow)], -7.0f) << "wrote past the end at " << where;
  }
}

TEST(OnnxFold, SmallInputConvsAreReplacedAndTheOutputMatches) {
  register_small_conv_layer();
  // A dense 8 -> 8 channel 3 x 3 convolution, padded and not; a 7 x 7 one with stride 2 and 3 pixels
  // of padding, 3 -> 16 channels (OSNet's stem) on 20 x 27 and 8 -> 8 unpadded on 16 x 19.
  DepthwiseSpec three, unpadded, seven, seven_unpadded;
  for (DepthwiseSpec* spec : {&three, &unpadded, &seven_unpadded}) spec->channels = 8, spec->group = 1;
  unpadded.pad = 0;
  seven.channels = 3, seven.out_channels = 16, seven.group = 1, seven.kernel = 7, seven.stride = 2, seven.pad = 3;
  seven.height = 20, seven.width = 27;
  seven_unpadded.kernel = 7, seven_unpadded.stride = 2, seven_unpadded.pad = 0;
  seven_unpadded.height = 16, seven_unpadded.width = 19;
  for (DepthwiseSpec spec : {three, unpadded, seven, seven_unpadded})
    for (bool bias : {true, false})
      for (bool relu : {true, false}) {
        spec.bias = bias;
        spec.relu = relu;
        const std::string what = std::to_string(spec.kernel) + "/" + std::to_string(spec.stride) + "/" +
                                 std::to_string(spec.pad) + (bias ? " bias" : "") + (relu ? " relu" : "");
        const std::string onnx = depthwise_model(spec);
        EXPECT_FALSE(replace_depthwise_convs(onnx).has_value());
        const std::optional<std::string> replaced = replace_small_input_convs(onnx);
        ASSERT_TRUE(replaced.has_value()) << what;
        EXPECT_EQ(op_types(*replaced).front(), kSmallConvOpType);
        const cv::Mat out = expect_same_output(onnx, *replaced, spec, 1e-4, what);
        ASSERT_FALSE(out.empty()) << what;
        EXPECT_EQ(out.size[2], (spec.height + 2 * spec.pad - spec.kernel) / spec.stride + 1) << what;
      }
  // Left alone: depthwise, 3 x 3 with stride 2, 5 x 5, 7 x 7 with stride 1, weights as an input,
  // more than 16 inputs, an output count that is not a multiple of 8 (3).
  DepthwiseSpec depthwise, strided, five, seven_unit, input_weights, wide, odd;
  for (DepthwiseSpec* spec : {&strided, &five, &seven_unit, &input_weights})
    spec->channels = 8, spec->group = 1;
  depthwise.channels = 8, depthwise.group = 8;
  strided.stride = 2;
  five.kernel = 5, five.pad = 2;
  seven_unit.kernel = 7, seven_unit.pad = 3;
  input_weights.weight_is_input = true;
  wide.channels = 24, wide.group = 1;
  odd.group = 1;
  for (const DepthwiseSpec& spec : {depthwise, strided, five, seven_unit, input_weights, wide, odd})
    EXPECT_FALSE(replace_small_input_convs(depthwise_model(spec)).has_value())
        << spec.channels << " " << spec.group << " " << spec.stride << spec.kernel << spec.pad << spec.weight_is_input;
}

TEST(Pointwise, KernelMatchesTheDefinition) {
  // Planes below, at and above a vector (4 or 8 lanes) and a block of three; one to 32 inputs; one to
  // three output blocks.
  cv::RNG rng(13);
  for (const size_t plane : {1, 3, 7, 8, 9, 23, 24, 25, 47, 100, 2048})
    for (const int cin : {1, 5, 16, 32})
      for (const int cout : {4, 12}) {
        std::vector<float> src(cin * plane), weights(static_cast<size_t>(cout * cin)), bias(cout);
        for (float& v : src) v = static_cast<float>(rng.uniform(-3.0, 3.0));
        for (float& v : weights) v = static_cast<float>(rng.uniform(-1.0, 1.0));
        for (float& v : bias) v = static_cast<float>(rng.uniform(-1.0, 1.0));
        std::vector<float> dst(cout * plane + 1, -7.0f);
        pointwise_conv(src.data(), cin, cout, plane, weights.data(), bias.data(), dst.data());
        for (int o = 0; o < cout; ++o)
          for (size_t p = 0; p < plane; ++p) {
            double expected = bias[o];
            for (int c = 0; c < cin; ++c) expected += double{weights[o * cin + c]} * src[c * plane + p];
            ASSERT_NEAR(dst[o * plane + p], expected, 1e-4) << plane << " px, " << cin << " -> " << cout << " at " << o
                                                            << "," << p;
          }
        EXPECT_EQ(dst[cout * plane], -7.0f) << "wrote past the end at " << plane << " px, " << cin << " -> " << cout;
      }
}

TEST(OnnxFold, PointwiseConvsAreReplacedAndTheOutputMatches) {
  register_pointwise_layer();
  // 8 -> 12 and 32 -> 4 channels, with and without bias and Relu.
  DepthwiseSpec narrow, widest;
  for (DepthwiseSpec* spec : {&narrow, &widest}) spec->group = 1, spec->kernel = 1, spec->pad = 0;
  narrow.channels = 8, narrow.out_channels = 12;
  widest.channels = kPointwiseMaxInputs, widest.out_channels = 4;
  for (DepthwiseSpec spec : {narrow, widest})
    for (bool bias : {true, false})
      for (bool relu : {true, false}) {
        spec.bias = bias;
        spec.relu = relu;
        const std::string what = std::to_string(spec.channels) + " -> " + std::to_string(spec.out_channels) +
                                 (bias ? " bias" : "") + (relu ? " relu" : "");
        const std::string onnx = depthwise_model(spec);
        EXPECT_FALSE(replace_depthwise_convs(onnx).has_value()) << what;
        EXPECT_FALSE(replace_small_input_convs(onnx).has_value()) << what;
        const std::optional<std::string> replaced = replace_pointwise_convs(onnx);
        ASSERT_TRUE(replaced.has_value()) << what;
        EXPECT_EQ(op_types(*replaced).front(), kPointwiseOpType);
        expect_same_output(onnx, *replaced, spec, 1e-5, what);
      }
  // Left alone: more than kPointwiseMaxInputs inputs, an output count that is not a multiple of 4,
  // depthwise 1 x 1 (C groups), strided, padded, 3 x 3, weights as an input.
  DepthwiseSpec wide, odd, grouped, strided, padded, three, input_weights;
  for (DepthwiseSpec* spec : {&wide, &odd, &strided, &padded, &three, &input_weights})
    spec->channels = 8, spec->group = 1, spec->kernel = 1, spec->pad = 0;
  wide.channels = kPointwiseMaxInputs + 8;
  odd.out_channels = 6;
  grouped.channels = 8, grouped.group = 8, grouped.kernel = 1, grouped.pad = 0;
  strided.stride = 2;
  padded.pad = 1;
  three.kernel = 3, three.pad = 1, three.channels = 24;  // too many inputs for the small-input layer too
  input_weights.weight_is_input = true;
  for (const DepthwiseSpec& spec : {wide, odd, grouped, strided, padded, three, input_weights})
    EXPECT_FALSE(replace_pointwise_convs(depthwise_model(spec)).has_value())
        << spec.channels << " " << spec.out_channels << " " << spec.group << " " << spec.stride << spec.kernel << spec.pad
        << spec.weight_is_input;
}

}  // namespace
}  // namespace wardmap::semantics
