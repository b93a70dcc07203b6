// A detector model described in models/<name>.yaml: the weights file, the input geometry and
// preprocessing, the decoder and its outputs, the class list, and the class->landmark mappings.
// Loading validates every key and names it in errors. See models/README.md for the keys.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace wardmap::semantics {

// Input preprocessing of a letterbox detector: scale r = min(W / w, H / h), resize into the top-left
// corner of a W x H canvas, fill the rest with pad_value, then (x - mean) / std per channel.
struct InputSpec {
  int width = 0;
  int height = 0;
  std::string channel_order = "bgr";    // bgr | rgb (order the network expects)
  std::array<double, 3> mean{0, 0, 0};  // in the network's channel order, on 0-255 values
  std::array<double, 3> std{1, 1, 1};
  double pad_value = 0;
  bool pad_after_normalisation = false;  // pad_value is in normalised units (NanoDet: 0 after normalising)
  // 0: the canvas is always width x height. N > 0: a side of the canvas that the resized image does
  // not fill is cut to the smallest multiple of N that holds it and N pixels of padding (640x480
  // into 416x416 with N = 32: a 416x352 canvas; KITTI's 1241x376: 416x160), for a fully
  // convolutional network that takes other input sizes: less padding to compute. N must be a
  // multiple of every output stride.
  int canvas_multiple = 0;
};

struct OutputSpec {
  std::vector<int> strides;            // e.g. 8, 16, 32
  std::vector<std::string> names;      // yolox: the single output; nanodet: class outputs per stride
  std::vector<std::string> box_names;  // nanodet: distance outputs per stride
  int bins = 0;                        // nanodet: distribution bins per side
};

struct ModelDescription {
  std::filesystem::path description_file;  // the YAML it came from
  std::string name;                        // "yolox-nano"
  std::filesystem::path file;              // weights, relative to the models folder
  std::string decoder;                     // yolox | nanodet
  InputSpec input;
  OutputSpec output;
  std::vector<std::string> classes;  // the detector's class names in output order
  // set name -> (detector class -> landmark class); classes absent from a set are dropped.
  std::map<std::string, std::map<std::string, std::string>> landmark_sets;

  // Per class index: the landmark label in `set`, or "" when dropped. "coco" maps every class to itself.
  // Throws InputError naming the description file when the set is unknown.
  std::vector<std::string> class_to_landmark(const std::string& set) const;
};

// Loads and validates a description. The class list (key `classes`, a file with one name a line) is
// read from beside the YAML file, else through the model search path (models_dir first). The
// landmark sets (key `landmark_sets`) are inline, or a YAML file name relative to the description.
// Throws InputError(file, "key 'input.width': ...").
ModelDescription load_model_description(const std::filesystem::path& yaml_file,
                                        const std::filesystem::path& models_dir = {});

}  // namespace wardmap::semantics
