#include "semantics/detection/dnn_detector.h"

#include <algorithm>
#include <exception>
#include <map>

#include "semantics/detection/class_nms.h"
#include "semantics/detection/decoders.h"
#include "semantics/detection/letterbox.h"
#include "semantics/detection/onnx_net.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace fs = std::filesystem;

DnnDetector::DnnDetector(ModelDescription model, const fs::path& onnx_file, const DnnDetectorOptions& options)
    : model_(std::move(model)), options_(options) {
  landmark_of_class_ = model_.class_to_landmark(options_.landmark_set);
  std::map<std::string, int> group_ids;
  for (const std::string& label : landmark_of_class_) {
    const int next = static_cast<int>(group_ids.size());
    group_of_class_.push_back(label.empty() ? -1 : group_ids.emplace(label, next).first->second);
  }

  net_ = load_onnx_net(onnx_file, "model file not found", rewrites_);

  output_names_ = model_.output.names;
  output_names_.insert(output_names_.end(), model_.output.box_names.begin(), model_.output.box_names.end());
  const std::vector<std::string> layers = net_.getLayerNames();
  const std::vector<std::string> unconnected = net_.getUnconnectedOutLayersNames();
  for (const std::string& name : output_names_) {
    if (std::find(layers.begin(), layers.end(), name) == layers.end() &&
        std::find(unconnected.begin(), unconnected.end(), name) == unconnected.end())
      throw InputError(onnx_file.string(),
                       "the network has no output '" + name + "' (named in " + model_.description_file.string() + ")");
  }
  // One forward of a blank image: weights that do not fit the description (another model's) are
  // refused here, naming both files, not at the first frame.
  try {
    DnnDetector::detect(cv::Mat(model_.input.height, model_.input.width, CV_8UC3, cv::Scalar::all(0)), 0.0);
  } catch (const cv::Exception& ex) {
    throw InputError(onnx_file.string(),
                     "the network does not run on the input of " + model_.description_file.string() + ": " + ex.msg);
  } catch (const std::exception& ex) {
    throw InputError(onnx_file.string(),
                     std::string(ex.what()) + ": not the model " + model_.description_file.string() + " describes?");
  }
}

std::vector<Detection> DnnDetector::detect(const cv::Mat& image, double /*timestamp*/) {
  const cv::Mat bgr = to_bgr8(image);
  const Letterbox lb = make_letterbox(bgr, model_.input);
  net_.setInput(rewrites_.prepare_input(lb.blob));
  std::vector<cv::Mat> outputs;
  net_.forward(outputs, output_names_);
  for (size_t i = 0; i < outputs.size(); ++i) outputs[i] = rewrites_.restore_output(output_names_[i], outputs[i]);

  const float min_score = options_.score_threshold;
  std::vector<Candidate> candidates;
  if (model_.decoder == "yolox") {
    candidates = decode_yolox(outputs.front(), model_, lb.canvas, min_score);
  } else {
    const size_t levels = model_.output.strides.size();
    const std::vector<cv::Mat> cls(outputs.begin(), outputs.begin() + levels);
    const std::vector<cv::Mat> dis(outputs.begin() + levels, outputs.end());
    candidates = decode_nanodet(cls, dis, model_, lb.canvas, min_score);
  }

  // Map to landmark classes first and suppress per landmark class: one vehicle often scores as both
  // car and truck (MODELS.md), which in the road set are the same landmark.
  const cv::Rect2d frame(0, 0, bgr.cols, bgr.rows);
  std::vector<cv::Rect2d> boxes;
  std::vector<float> scores;
  std::vector<int> groups, class_ids;
  for (const Candidate& c : candidates) {
    if (group_of_class_[c.class_id] < 0) continue;
    const cv::Rect2d in_image(c.box.x / lb.scale, c.box.y / lb.scale, c.box.width / lb.scale, c.box.height / lb.scale);
    const cv::Rect2d clipped = in_image & frame;
    if (clipped.width < 1.0 || clipped.height < 1.0) continue;
    boxes.push_back(clipped);
    scores.push_back(c.score);
    groups.push_back(group_of_class_[c.class_id]);
    class_ids.push_back(c.class_id);
  }
  std::vector<Detection> out;
  for (int k : class_wise_nms(boxes, scores, groups, options_.nms_iou)) {
    Detection d;
    d.box = Eigen::Vector4d(boxes[k].x, boxes[k].y, boxes[k].br().x, boxes[k].br().y);
    d.source_label = model_.classes[class_ids[k]];
    d.label = landmark_of_class_[class_ids[k]];
    d.score = scores[k];
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace wardmap::semantics
