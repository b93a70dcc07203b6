// Builds the detector DetectorOptions asks for:
//   yolox       -> DnnDetector with models/yolox-nano.yaml
//   nanodet     -> DnnDetector with models/nanodet-m.yaml
//   annotations -> AnnotationsDetector on <sequence_dir>/annotations.jsonl
// The description is DetectorOptions::model_description when set; weights and class lists are found
// through the model search path (model_search.h).
#pragma once

#include <filesystem>
#include <memory>

#include "semantics/detection/detection.h"
#include "semantics/detection/detector_options.h"

namespace wardmap::semantics {

// Throws InputError when the options are invalid (naming the option), or when a description,
// model or annotations file is missing or malformed (naming the file and the places searched).
std::unique_ptr<Detector> make_detector(const DetectorOptions& options, const std::filesystem::path& sequence_dir = {});

// The description file used for a network kind ("yolox" | "nanodet").
std::filesystem::path default_model_description(const std::string& kind);

}  // namespace wardmap::semantics
