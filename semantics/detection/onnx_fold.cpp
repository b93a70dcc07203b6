#include "semantics/detection/onnx_fold.h"

#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>

#include "semantics/detection/depthwise_layer.h"
#include "semantics/detection/pointwise_layer.h"
#include "semantics/detection/protobuf_wire.h"
#include "semantics/detection/silu_layer.h"
#include "semantics/detection/small_conv_layer.h"

namespace wardmap::semantics {

namespace {

// Field numbers of onnx.proto (ONNX IR).
constexpr std::uint32_t kModelGraph = 7;
constexpr std::uint32_t kGraphNode = 1, kGraphInitializer = 5, kGraphInput = 11, kGraphOutput = 12,
                        kGraphValueInfo = 13;
constexpr std::uint32_t kNodeInput = 1, kNodeOutput = 2, kNodeName = 3, kNodeOpType = 4, kNodeAttribute = 5;
constexpr std::uint32_t kValueInfoName = 1, kValueInfoType = 2;
constexpr std::uint32_t kTypeTensorType = 1, kTensorTypeElemType = 1, kTensorTypeShape = 2, kShapeDim = 1,
                        kDimValue = 1;
constexpr std::uint32_t kTensorDims = 1, kTensorDataType = 2, kTensorInt32Data = 5, kTensorInt64Data = 7,
                        kTensorName = 8, kTensorRawData = 9;
constexpr std::uint32_t kAttributeName = 1, kAttributeInt = 3, kAttributeString = 4, kAttributeTensor = 5,
                        kAttributeInts = 8, kAttributeType = 20;
constexpr std::uint64_t kAttributeTypeInts = 7;
constexpr std::int64_t kOnnxInt32 = 6, kOnnxInt64 = 7;

std::string first_string(const std::vector<wire::Field>& fields, std::uint32_t number) {
  const std::vector<std::string> all = wire::strings(fields, number);
  return all.empty() ? std::string() : all.front();
}

// The integers of a constant INT64 / INT32 tensor (TensorProto bytes), nullopt for other types.
std::optional<std::vector<std::int64_t>> tensor_integers(const std::string& tensor) {
  const std::vector<wire::Field> fields = wire::parse(tensor);
  const std::vector<std::int64_t> type = wire::varints(fields, kTensorDataType);
  if (type.size() != 1 || (type[0] != kOnnxInt64 && type[0] != kOnnxInt32)) return std::nullopt;
  const size_t width = type[0] == kOnnxInt64 ? 8 : 4;
  const std::vector<std::string> raw = wire::strings(fields, kTensorRawData);
  if (raw.empty()) return wire::varints(fields, type[0] == kOnnxInt64 ? kTensorInt64Data : kTensorInt32Data);
  if (raw[0].size() % width != 0) return std::nullopt;
  std::vector<std::int64_t> out;
  for (size_t at = 0; at < raw[0].size(); at += width) {  // little-endian
    if (width == 8) {
      std::int64_t v;
      std::memcpy(&v, raw[0].data() + at, 8);
      out.push_back(v);
    } else {
      std::int32_t v;
      std::memcpy(&v, raw[0].data() + at, 4);
      out.push_back(v);
    }
  }
  return out;
}

struct Node {
  size_t field = 0;  // index in the graph's fields
  std::string op;
  std::vector<std::string> inputs, outputs;
  std::vector<std::vector<wire::Field>> attributes;

  const std::vector<wire::Field>* attribute(const std::string& name) const {
    for (const auto& a : attributes)
      if (first_string(a, kAttributeName) == name) return &a;
    return nullptr;
  }
};

using Constants = std::map<std::string, std::vector<std::int64_t>>;

const std::vector<std::int64_t>* constant(const Constants& constants, const std::vector<std::string>& inputs,
                                          size_t k) {
  if (k >= inputs.size() || inputs[k].empty()) return nullptr;
  const auto it = constants.find(inputs[k]);
  return it == constants.end() ? nullptr : &it->second;
}

// Adds a Slice's row / column phase to `phase` (index 0: axis 2, 1: axis 3). False unless every
// sliced axis is H or W, with step 2, a start of 0 or 1, to the end, and not sliced before.
bool add_slice_phase(const Node& slice, const Constants& constants, const std::array<std::int64_t, 2>& extent,
                     std::array<int, 2>& phase) {
  const auto* starts = constant(constants, slice.inputs, 1);
  const auto* ends = constant(constants, slice.inputs, 2);
  const auto* axes = constant(constants, slice.inputs, 3);
  const auto* steps = constant(constants, slice.inputs, 4);
  // Opset < 10 (attributes, no steps) and missing or non-constant parameters do not fold.
  if (!starts || !ends || !steps || starts->size() != ends->size() || steps->size() != starts->size()) return false;
  if (slice.inputs.size() > 3 && !slice.inputs[3].empty() && (!axes || axes->size() != starts->size())) return false;
  for (size_t j = 0; j < starts->size(); ++j) {
    std::int64_t axis = axes ? (*axes)[j] : static_cast<std::int64_t>(j);
    if (axis < 0) axis += 4;
    if (axis != 2 && axis != 3) return false;
    const size_t a = static_cast<size_t>(axis - 2);
    if ((*steps)[j] != 2 || ((*starts)[j] != 0 && (*starts)[j] != 1) || (*ends)[j] < extent[a] || phase[a] != -1)
      return false;
    phase[a] = static_cast<int>((*starts)[j]);
  }
  return true;
}

// A ValueInfoProto's tensor element type (-1 when absent) and dims (0 for one not known).
struct TensorShape {
  std::int64_t elem_type = -1;
  std::vector<std::int64_t> dims;

  bool known(size_t rank) const {
    if (elem_type < 0 || dims.size() != rank) return false;
    for (std::int64_t d : dims)
      if (d <= 0) return false;
    return true;
  }
};

TensorShape tensor_shape(const std::string& value_info) {
  const std::vector<wire::Field> tensor_type =
      wire::parse(first_string(wire::parse(first_string(wire::parse(value_info), kValueInfoType)), kTypeTensorType));
  TensorShape shape;
  const std::vector<std::int64_t> elem_type = wire::varints(tensor_type, kTensorTypeElemType);
  if (elem_type.size() == 1) shape.elem_type = elem_type[0];
  for (const std::string& d : wire::strings(wire::parse(first_string(tensor_type, kTensorTypeShape)), kShapeDim)) {
    const std::vector<std::int64_t> value = wire::varints(wire::parse(d), kDimValue);
    shape.dims.push_back(value.size() == 1 ? value[0] : 0);
  }
  return shape;
}

std::string tensor_value_info(const std::string& name, std::int64_t elem_type, const std::vector<std::int64_t>& dims) {
  std::vector<wire::Field> shape;
  for (std::int64_t d : dims)
    shape.push_back(wire::bytes_field(kShapeDim, wire::serialize({wire::varint_field(kDimValue, d)})));
  const std::string tensor_type = wire::serialize({wire::varint_field(kTensorTypeElemType, elem_type),
                                                   wire::bytes_field(kTensorTypeShape, wire::serialize(shape))});
  const std::string type = wire::serialize({wire::bytes_field(kTypeTensorType, tensor_type)});
  return wire::serialize({wire::bytes_field(kValueInfoName, name), wire::bytes_field(kValueInfoType, type)});
}

// A model's graph, parsed: its fields, the nodes, the constant integers, the weights' names and dims
// and the graph outputs.
struct ParsedGraph {
  std::vector<wire::Field> model;
  size_t graph_field = 0;  // the graph's index in `model`
  std::vector<wire::Field> graph;
  Constants constants;
  std::map<std::string, std::vector<std::int64_t>> initializers;  // name -> dims
  std::vector<Node> nodes;
  std::set<std::string> graph_outputs;

  // The model with `graph` written back.
  std::string serialize_with(const std::vector<wire::Field>& rewritten) {
    model[graph_field].bytes = wire::serialize(rewritten);
    return wire::serialize(model);
  }
};

// Nullopt when the model has no graph or more than one. Throws std::runtime_error for bytes that are
// not a protobuf message.
std::optional<ParsedGraph> parse_graph(const std::string& onnx) {
  ParsedGraph p;
  p.model = wire::parse(onnx);
  int graphs = 0;
  for (size_t i = 0; i < p.model.size(); ++i)
    if (p.model[i].number == kModelGraph && p.model[i].type == wire::kLengthDelimited) p.graph_field = i, ++graphs;
  if (graphs != 1) return std::nullopt;
  p.graph = wire::parse(p.model[p.graph_field].bytes);
  for (size_t i = 0; i < p.graph.size(); ++i) {
    const wire::Field& f = p.graph[i];
    if (f.type != wire::kLengthDelimited) continue;
    if (f.number == kGraphInitializer) {
      const std::vector<wire::Field> tensor = wire::parse(f.bytes);
      const std::string name = first_string(tensor, kTensorName);
      p.initializers[name] = wire::varints(tensor, kTensorDims);
      if (auto values = tensor_integers(f.bytes)) p.constants[name] = std::move(*values);
    } else if (f.number == kGraphOutput) {
      p.graph_outputs.insert(first_string(wire::parse(f.bytes), kValueInfoName));
    } else if (f.number == kGraphNode) {
      const std::vector<wire::Field> n = wire::parse(f.bytes);
      Node node;
      node.field = i;
      node.op = first_string(n, kNodeOpType);
      node.inputs = wire::strings(n, kNodeInput);
      node.outputs = wire::strings(n, kNodeOutput);
      for (const std::string& a : wire::strings(n, kNodeAttribute)) node.attributes.push_back(wire::parse(a));
      if (node.op == "Constant" && node.outputs.size() == 1) {
        if (const auto* value = node.attribute("value")) {
          const std::string tensor = first_string(*value, kAttributeTensor);
          if (auto values = tensor_integers(tensor)) p.constants[node.outputs[0]] = std::move(*values);
        }
      }
      p.nodes.push_back(std::move(node));
    }
  }
  return p;
}

// True for a graph field `number` (a ValueInfoProto: value_info, input, output) that names one of
// `tensors`.
bool value_info_naming(const wire::Field& field, std::uint32_t number, const std::set<std::string>& tensors) {
  return field.number == number && field.type == wire::kLengthDelimited &&
         tensors.count(first_string(wire::parse(field.bytes), kValueInfoName));
}

// True for a graph's value_info field that names one of `tensors` (a tensor a rewrite removed).
bool is_value_info_of(const wire::Field& field, const std::set<std::string>& tensors) {
  return value_info_naming(field, kGraphValueInfo, tensors);
}

// The model with its graph rewritten: the graph fields in `dropped` and the value_info naming one
// of `dropped_tensors` left out, each field of `replaced` written in its place.
std::string rewrite_graph(ParsedGraph& p, const std::set<size_t>& dropped, const std::set<std::string>& dropped_tensors,
                          std::map<size_t, wire::Field> replaced) {
  std::vector<wire::Field> rewritten;
  for (size_t i = 0; i < p.graph.size(); ++i) {
    if (dropped.count(i) || is_value_info_of(p.graph[i], dropped_tensors)) continue;
    const auto it = replaced.find(i);
    rewritten.push_back(it == replaced.end() ? std::move(p.graph[i]) : std::move(it->second));
  }
  return p.serialize_with(rewritten);
}

std::map<std::string, std::vector<size_t>> consumers_of(const std::vector<Node>& nodes) {
  std::map<std::string, std::vector<size_t>> consumers;
  for (size_t k = 0; k < nodes.size(); ++k)
    for (const std::string& in : nodes[k].inputs) consumers[in].push_back(k);
  return consumers;
}

}  // namespace

cv::Mat SpaceToDepth::apply(const cv::Mat& blob) const {
  if (blob.dims != 4 || blob.type() != CV_32F || blob.size[0] != batch || blob.size[1] != channels ||
      blob.size[2] % 2 != 0 || blob.size[3] % 2 != 0)
    throw std::invalid_argument("SpaceToDepth: expected a float blob of " + std::to_string(batch) + " x " +
                                std::to_string(channels) + " x H x W, H and W even (the model's: " +
                                std::to_string(height) + " x " + std::to_string(width) + ")");
  const int h = blob.size[2], w = blob.size[3];  // the blob's own: any even size
  const cv::Mat in = blob.isContinuous() ? blob : blob.clone();
  const int blocks = static_cast<int>(offsets.size());
  const int oh = h / 2, ow = w / 2;
  const int dims[4] = {batch, channels * blocks, oh, ow};
  cv::Mat out(4, dims, CV_32F);
  const float* src = in.ptr<float>();
  float* dst = out.ptr<float>();
  for (int n = 0; n < batch; ++n)
    for (int k = 0; k < blocks; ++k)
      for (int c = 0; c < channels; ++c) {
        const float* plane = src + (static_cast<size_t>(n) * channels + c) * h * w;
        float* o = dst + ((static_cast<size_t>(n) * blocks + k) * channels + c) * oh * ow;
        for (int y = 0; y < oh; ++y) {
          const float* row = plane + static_cast<size_t>(2 * y + offsets[k][0]) * w + offsets[k][1];
          for (int x = 0; x < ow; ++x) *o++ = row[2 * x];
        }
      }
  return out;
}

std::optional<FoldedModel> fold_space_to_depth_input(const std::string& onnx) {
  std::optional<ParsedGraph> parsed = parse_graph(onnx);
  if (!parsed) return std::nullopt;
  std::vector<wire::Field>& graph = parsed->graph;
  const auto& initializers = parsed->initializers;
  const Constants& constants = parsed->constants;
  const std::vector<Node>& nodes = parsed->nodes;
  const std::set<std::string>& graph_outputs = parsed->graph_outputs;

  // The one input that is not a weight, with a fully known N x C x H x W shape, H and W even.
  size_t input_field = 0;
  std::string input;
  int inputs = 0;
  for (size_t i = 0; i < graph.size(); ++i) {
    if (graph[i].number != kGraphInput || graph[i].type != wire::kLengthDelimited) continue;
    const std::string name = first_string(wire::parse(graph[i].bytes), kValueInfoName);
    if (initializers.count(name)) continue;
    input_field = i, input = name, ++inputs;
  }
  if (inputs != 1) return std::nullopt;
  const TensorShape shape = tensor_shape(graph[input_field].bytes);
  if (!shape.known(4) || shape.dims[2] % 2 != 0 || shape.dims[3] % 2 != 0) return std::nullopt;
  const std::vector<std::int64_t>& dims = shape.dims;

  std::map<std::string, std::vector<size_t>> consumers = consumers_of(nodes);

  // Follow each chain of Slices from the input to the Concat, collecting its phases.
  std::set<size_t> removed;
  std::optional<size_t> concat;
  std::map<std::string, std::array<int, 2>> chain_ends;
  for (const size_t first : consumers[input]) {
    std::array<int, 2> phase{-1, -1};
    std::string tensor = input;
    size_t k = first;
    while (nodes[k].op != "Concat") {
      const Node& n = nodes[k];
      if (n.op != "Slice" || n.inputs.empty() || n.inputs[0] != tensor || n.outputs.size() != 1) return std::nullopt;
      if (!add_slice_phase(n, constants, {dims[2], dims[3]}, phase) || !removed.insert(k).second) return std::nullopt;
      tensor = n.outputs[0];
      const std::vector<size_t>& next = consumers[tensor];
      if (graph_outputs.count(tensor) || next.size() != 1) return std::nullopt;
      k = next.front();
    }
    if (phase[0] < 0 || phase[1] < 0 || (concat && *concat != k) || tensor == input ||
        !chain_ends.emplace(tensor, phase).second)
      return std::nullopt;
    concat = k;
  }
  if (!concat) return std::nullopt;
  const Node& cat = nodes[*concat];
  const auto* axis = cat.attribute("axis");
  const std::vector<std::int64_t> axis_value = axis ? wire::varints(*axis, kAttributeInt) : std::vector<std::int64_t>{};
  if (axis_value.size() != 1 || (axis_value[0] != 1 && axis_value[0] != -3) || cat.outputs.size() != 1 ||
      cat.inputs.size() != 4 || chain_ends.size() != 4 || graph_outputs.count(cat.outputs[0]))
    return std::nullopt;
  SpaceToDepth s2d;
  s2d.batch = static_cast<int>(dims[0]);
  s2d.channels = static_cast<int>(dims[1]);
  s2d.height = static_cast<int>(dims[2]);
  s2d.width = static_cast<int>(dims[3]);
  std::set<std::array<int, 2>> phases;
  for (const std::string& in : cat.inputs) {
    const auto it = chain_ends.find(in);
    if (it == chain_ends.end() || !phases.insert(it->second).second) return std::nullopt;
    s2d.offsets.push_back(it->second);
  }
  removed.insert(*concat);

  // Rewrite: drop the Slices and the Concat (and value_info naming their outputs); the Concat's
  // output becomes the graph input (its value_info is that input now).
  std::set<size_t> dropped_fields;
  std::set<std::string> dropped_tensors;
  for (size_t k : removed) {
    dropped_fields.insert(nodes[k].field);
    dropped_tensors.insert(nodes[k].outputs.begin(), nodes[k].outputs.end());
  }
  const wire::Field new_input = wire::bytes_field(
      kGraphInput, tensor_value_info(cat.outputs[0], shape.elem_type, {dims[0], 4 * dims[1], dims[2] / 2, dims[3] / 2}));
  return FoldedModel{rewrite_graph(*parsed, dropped_fields, dropped_tensors, {{input_field, new_input}}), std::move(s2d)};
}

std::optional<std::string> fuse_silu(const std::string& onnx) {
  std::optional<ParsedGraph> parsed = parse_graph(onnx);
  if (!parsed) return std::nullopt;
  const std::vector<Node>& nodes = parsed->nodes;
  const std::map<std::string, std::vector<size_t>> consumers = consumers_of(nodes);
  std::map<size_t, wire::Field> replaced;  // Mul's graph field -> the fused node
  std::set<size_t> dropped;                // Sigmoids' graph fields
  std::set<std::string> dropped_tensors;   // their outputs
  for (const Node& sigmoid : nodes) {
    if (sigmoid.op != "Sigmoid" || sigmoid.inputs.size() != 1 || sigmoid.outputs.size() != 1) continue;
    const std::string& x = sigmoid.inputs[0];
    const std::string& s = sigmoid.outputs[0];
    const auto users = consumers.find(s);
    if (parsed->graph_outputs.count(s) || users == consumers.end() || users->second.size() != 1) continue;
    const Node& mul = nodes[users->second.front()];
    if (mul.op != "Mul" || mul.inputs.size() != 2 || mul.outputs.size() != 1) continue;
    if (!((mul.inputs[0] == x && mul.inputs[1] == s) || (mul.inputs[0] == s && mul.inputs[1] == x))) continue;
    dropped.insert(sigmoid.field);
    dropped_tensors.insert(s);
    const std::string name = "wardmap_silu_" + std::to_string(replaced.size());
    replaced[mul.field] = wire::bytes_field(
        kGraphNode, wire::serialize({wire::bytes_field(kNodeInput, x), wire::bytes_field(kNodeOutput, mul.outputs[0]),
                                     wire::bytes_field(kNodeName, name), wire::bytes_field(kNodeOpType, kSiluOpType)}));
  }
  if (replaced.empty()) return std::nullopt;
  return rewrite_graph(*parsed, dropped, dropped_tensors, std::move(replaced));
}

namespace {

// A MaxPool of one input and one output with a square odd kernel, stride 1 and "same" padding (the
// defaults of the attributes it leaves out: no dilation, floor rounding, explicit padding): its
// kernel side, else 0.
std::int64_t same_size_max_pool_kernel(const Node& n) {
  if (n.op != "MaxPool" || n.inputs.size() != 1 || n.outputs.size() != 1) return 0;
  std::int64_t k = 0;
  bool padded = false;
  for (const auto& a : n.attributes) {
    const std::string name = first_string(a, kAttributeName);
    const std::vector<std::int64_t> ints = wire::varints(a, kAttributeInts);
    const std::vector<std::int64_t> value = wire::varints(a, kAttributeInt);
    const auto all_equal = [&ints](std::int64_t v) {
      for (std::int64_t x : ints)
        if (x != v) return false;
      return true;
    };
    if (name == "kernel_shape") {
      if (ints.size() != 2 || ints[0] != ints[1] || ints[0] < 3 || ints[0] % 2 == 0) return 0;
      k = ints[0];
    } else if (name == "strides" || name == "dilations") {
      if (!all_equal(1)) return 0;
    } else if (name == "pads") {
      if (ints.size() != 4) return 0;
      padded = true;
    } else if (name == "ceil_mode" || name == "storage_order") {
      if (value.size() != 1 || value[0] != 0) return 0;
    } else if (name == "auto_pad") {
      if (first_string(a, kAttributeString) != "NOTSET") return 0;
    } else {
      return 0;
    }
  }
  if (k == 0 || !padded) return 0;
  const auto* pads = n.attribute("pads");
  for (std::int64_t p : wire::varints(*pads, kAttributeInts))
    if (p != k / 2) return 0;
  return k;
}

std::string ints_attribute(const std::string& name, const std::vector<std::int64_t>& values) {
  std::vector<wire::Field> f = {wire::bytes_field(kAttributeName, name)};
  for (std::int64_t v : values) f.push_back(wire::varint_field(kAttributeInts, static_cast<std::uint64_t>(v)));
  f.push_back(wire::varint_field(kAttributeType, kAttributeTypeInts));
  return wire::serialize(f);
}

}  // namespace

std::optional<std::string> cascade_max_pools(const std::string& onnx) {
  std::optional<ParsedGraph> parsed = parse_graph(onnx);
  if (!parsed) return std::nullopt;
  const std::vector<Node>& nodes = parsed->nodes;
  // The qualifying pools of each tensor, in graph order.
  std::map<std::string, std::vector<size_t>> pools;
  for (size_t k = 0; k < nodes.size(); ++k)
    if (same_size_max_pool_kernel(nodes[k]) > 0) pools[nodes[k].inputs[0]].push_back(k);
  std::map<size_t, wire::Field> replaced;  // graph field -> the rewritten node
  for (const auto& [tensor, set] : pools) {
    if (set.size() < 2) continue;
    // Kernels growing in graph order, so that each pool's new input is made before it.
    bool growing = true;
    for (size_t j = 1; j < set.size(); ++j)
      growing = growing && same_size_max_pool_kernel(nodes[set[j]]) > same_size_max_pool_kernel(nodes[set[j - 1]]);
    if (!growing) continue;
    for (size_t j = 1; j < set.size(); ++j) {
      const Node& n = nodes[set[j]];
      const std::int64_t k = same_size_max_pool_kernel(n) - same_size_max_pool_kernel(nodes[set[j - 1]]) + 1;
      std::vector<wire::Field> f = {wire::bytes_field(kNodeInput, nodes[set[j - 1]].outputs[0]),
                                    wire::bytes_field(kNodeOutput, n.outputs[0])};
      const std::vector<wire::Field> original = wire::parse(parsed->graph[n.field].bytes);
      const std::string name = first_string(original, kNodeName);
      if (!name.empty()) f.push_back(wire::bytes_field(kNodeName, name));
      f.push_back(wire::bytes_field(kNodeOpType, "MaxPool"));
      f.push_back(wire::bytes_field(kNodeAttribute, ints_attribute("kernel_shape", {k, k})));
      f.push_back(wire::bytes_field(kNodeAttribute, ints_attribute("pads", {k / 2, k / 2, k / 2, k / 2})));
      f.push_back(wire::bytes_field(kNodeAttribute, ints_attribute("strides", {1, 1})));
      replaced[n.field] = wire::bytes_field(kGraphNode, wire::serialize(f));
    }
  }
  if (replaced.empty()) return std::nullopt;
  return rewrite_graph(*parsed, {}, {}, std::move(replaced));
}

std::optional<FoldedOutputs> fold_output_transposes(const std::string& onnx) {
  std::optional<ParsedGraph> parsed = parse_graph(onnx);
  if (!parsed) return std::nullopt;
  const std::vector<Node>& nodes = parsed->nodes;
  const std::map<std::string, std::vector<size_t>> consumers = consumers_of(nodes);
  std::map<std::string, size_t> producer;
  for (size_t k = 0; k < nodes.size(); ++k)
    for (const std::string& out : nodes[k].outputs) producer[out] = k;
  FoldedOutputs folded;
  std::set<size_t> dropped;                   // the Transposes' graph fields
  std::map<size_t, wire::Field> replaced;     // producer's graph field -> its rewritten node; the outputs
  std::set<std::string> dropped_tensors;      // the tensors before them (value_info naming them goes)
  for (const Node& t : nodes) {
    if (t.op != "Transpose" || t.inputs.size() != 1 || t.outputs.size() != 1) continue;
    const std::string& x = t.inputs[0];
    const std::string& y = t.outputs[0];
    const auto* perm = t.attribute("perm");
    if (!perm || wire::varints(*perm, kAttributeInts) != std::vector<std::int64_t>{0, 2, 1}) continue;
    // y only an output (a node reading it would get the untransposed tensor), x read by t alone.
    if (!parsed->graph_outputs.count(y) || consumers.count(y) || parsed->graph_outputs.count(x) ||
        consumers.at(x).size() != 1)
      continue;
    const auto p = producer.find(x);
    if (p == producer.end() || replaced.count(nodes[p->second].field)) continue;  // a graph input, or done
    std::vector<wire::Field> fields = wire::parse(parsed->graph[nodes[p->second].field].bytes);
    for (wire::Field& f : fields)
      if (f.number == kNodeOutput && f.type == wire::kLengthDelimited && f.bytes == x) f.bytes = y;
    replaced[nodes[p->second].field] = wire::bytes_field(kGraphNode, wire::serialize(fields));
    dropped.insert(t.field);
    dropped_tensors.insert(x);
    folded.outputs.push_back(y);
  }
  if (folded.outputs.empty()) return std::nullopt;
  // Each output's declared shape B x N x C becomes B x C x N (kept as it is when not fully known).
  const std::set<std::string> outputs(folded.outputs.begin(), folded.outputs.end());
  for (size_t i = 0; i < parsed->graph.size(); ++i) {
    if (!value_info_naming(parsed->graph[i], kGraphOutput, outputs)) continue;
    const TensorShape shape = tensor_shape(parsed->graph[i].bytes);
    if (!shape.known(3)) continue;
    const std::string name = first_string(wire::parse(parsed->graph[i].bytes), kValueInfoName);
    replaced[i] = wire::bytes_field(
        kGraphOutput, tensor_value_info(name, shape.elem_type, {shape.dims[0], shape.dims[2], shape.dims[1]}));
  }
  folded.onnx = rewrite_graph(*parsed, dropped, dropped_tensors, std::move(replaced));
  return folded;
}

cv::Mat transpose_output(const cv::Mat& output) {
  if (output.dims != 3 || output.type() != CV_32F || !output.isContinuous())
    throw std::invalid_argument("transpose_output: expected a continuous B x C x N float blob");
  const int b = output.size[0], c = output.size[1], n = output.size[2];
  const int dims[3] = {b, n, c};
  cv::Mat out(3, dims, CV_32F);
  for (int k = 0; k < b; ++k) {
    const cv::Mat from(c, n, CV_32F, const_cast<float*>(output.ptr<float>()) + static_cast<size_t>(k) * c * n);
    cv::Mat to(n, c, CV_32F, out.ptr<float>() + static_cast<size_t>(k) * c * n);
    cv::transpose(from, to);
  }
  return out;
}

namespace {

// A Conv's attributes when its dilation is 1 (or absent), its stride the same on both axes and its
// padding the same on every side: the group count (1 when absent), the kernel side (0 when absent),
// the stride (1 when absent) and the padding (0 when absent). Nullopt for any other attribute or
// value.
struct ConvAttributes {
  std::int64_t group = 1, kernel = 0, stride = 1, pad = 0;
};
std::optional<ConvAttributes> conv_attributes(const Node& n) {
  ConvAttributes c;
  for (const auto& a : n.attributes) {
    const std::string name = first_string(a, kAttributeName);
    const std::vector<std::int64_t> ints = wire::varints(a, kAttributeInts);
    const std::vector<std::int64_t> value = wire::varints(a, kAttributeInt);
    if (name == "group") {
      if (value.size() != 1) return std::nullopt;
      c.group = value[0];
    } else if (name == "kernel_shape") {
      if (ints.size() != 2 || ints[0] != ints[1]) return std::nullopt;
      c.kernel = ints[0];
    } else if (name == "strides") {
      if (ints.size() != 2 || ints[0] != ints[1] || ints[0] < 1) return std::nullopt;
      c.stride = ints[0];
    } else if (name == "dilations") {
      if (ints != std::vector<std::int64_t>{1, 1}) return std::nullopt;
    } else if (name == "pads") {
      if (ints.size() != 4 || ints[1] != ints[0] || ints[2] != ints[0] || ints[3] != ints[0] || ints[0] < 0)
        return std::nullopt;
      c.pad = ints[0];
    } else if (name == "auto_pad") {
      if (first_string(a, kAttributeString) != "NOTSET") return std::nullopt;
    } else {
      return std::nullopt;
    }
  }
  return c;
}

// A square 2-D Conv that reads one tensor with constant weights (Cout x Cin/group x k x k) and an
// optional constant bias of Cout values, with conv_attributes: the weights' dims and the attributes
// (the kernel side filled in from the weights); else nullopt.
struct SquareConv {
  std::vector<std::int64_t> weight;
  ConvAttributes attributes;
};
std::optional<SquareConv> square_conv(const Node& n, const ParsedGraph& p) {
  if (n.op != "Conv" || n.inputs.size() < 2 || n.inputs.size() > 3 || n.outputs.size() != 1) return std::nullopt;
  const auto weight = p.initializers.find(n.inputs[1]);
  if (weight == p.initializers.end()) return std::nullopt;
  const std::vector<std::int64_t>& w = weight->second;
  if (w.size() != 4 || w[0] < 1 || w[1] < 1 || w[2] < 1 || w[3] != w[2]) return std::nullopt;
  if (n.inputs.size() == 3) {
    const auto bias = p.initializers.find(n.inputs[2]);
    if (bias == p.initializers.end() || bias->second != std::vector<std::int64_t>{w[0]}) return std::nullopt;
  }
  std::optional<ConvAttributes> c = conv_attributes(n);
  if (!c || (c->kernel != 0 && c->kernel != w[2])) return std::nullopt;
  c->kernel = w[2];
  return SquareConv{w, *c};
}

// The model with every square Conv that `takes` gets op type `op_type`, its inputs, attributes and
// name unchanged (cv::dnn hands the attributes to the layer as parameters); nullopt when there is
// none.
template <typename Takes>
std::optional<std::string> retype_convs(const std::string& onnx, const char* op_type, Takes takes) {
  std::optional<ParsedGraph> parsed = parse_graph(onnx);
  if (!parsed) return std::nullopt;
  std::map<size_t, wire::Field> replaced;  // graph field -> the node with the new op type
  for (const Node& n : parsed->nodes) {
    const std::optional<SquareConv> conv = square_conv(n, *parsed);
    if (!conv || !takes(conv->weight, conv->attributes)) continue;
    std::vector<wire::Field> f;
    for (const std::string& in : n.inputs) f.push_back(wire::bytes_field(kNodeInput, in));
    f.push_back(wire::bytes_field(kNodeOutput, n.outputs[0]));
    const std::vector<wire::Field> original = wire::parse(parsed->graph[n.field].bytes);
    const std::string name = first_string(original, kNodeName);
    if (!name.empty()) f.push_back(wire::bytes_field(kNodeName, name));
    f.push_back(wire::bytes_field(kNodeOpType, op_type));
    for (const wire::Field& a : original)
      if (a.number == kNodeAttribute) f.push_back(a);
    replaced[n.field] = wire::bytes_field(kGraphNode, wire::serialize(f));
  }
  if (replaced.empty()) return std::nullopt;
  return rewrite_graph(*parsed, {}, {}, std::move(replaced));
}

}  // namespace

std::optional<std::string> replace_depthwise_convs(const std::string& onnx) {
  // C x 1 x 3 x 3 weights in C groups, stride 1, one pixel of padding.
  return retype_convs(onnx, kDepthwiseOpType, [](const std::vector<std::int64_t>& w, const ConvAttributes& c) {
    return w[1] == 1 && c.group == w[0] && c.kernel == 3 && c.stride == 1 && c.pad == 1;
  });
}

std::optional<std::string> replace_pointwise_convs(const std::string& onnx) {
  // Cout x Cin x 1 x 1 weights in one group, stride 1, no padding.
  return retype_convs(onnx, kPointwiseOpType, [](const std::vector<std::int64_t>& w, const ConvAttributes& c) {
    return c.group == 1 && c.kernel == 1 && c.stride == 1 && c.pad == 0 && w[0] % kPointwiseBlock == 0 &&
           w[1] <= kPointwiseMaxInputs;
  });
}

std::optional<std::string> replace_small_input_convs(const std::string& onnx) {
  return retype_convs(onnx, kSmallConvOpType, [](const std::vector<std::int64_t>& w, const ConvAttributes& c) {
    return c.group == 1 && w[1] <= kSmallConvMaxInputs && w[0] % kSmallConvBlock == 0 &&
           small_conv_supported(static_cast<int>(c.kernel), static_cast<int>(c.stride));
  });
}

}  // namespace wardmap::semantics
