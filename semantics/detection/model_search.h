// Where model weights and descriptions are found.
//
// Weights (ONNX files, class lists) are looked up, in order, in
//   1. DetectorOptions::models_dir (when set),
//   2. $WARDMAP_MODELS (when set),
//   3. <source tree>/../shared/models (compiled in),
// and the first folder that holds the file wins. When none does, InputError names the file and every
// place looked; a folder given in 1 or 2 that does not exist is an InputError naming it. Weights are
// never part of the repository (models/README.md says how to get them).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace wardmap::semantics {

// The folders searched for weights, in order (only those configured; they need not exist).
std::vector<std::filesystem::path> model_search_path(const std::filesystem::path& models_dir = {});

// The first <folder>/<relative> that exists; throws InputError(relative, "not found; looked in ...").
std::filesystem::path find_model_file(const std::filesystem::path& relative,
                                      const std::filesystem::path& models_dir = {});

// <source tree>/models: the shipped model descriptions (yolox.yaml, nanodet.yaml, ...).
std::filesystem::path model_descriptions_dir();

// The OSNet x0.25 ONNX file for Embedder, found through the search path above.
std::filesystem::path find_embedder_file(const std::filesystem::path& models_dir = {});

}  // namespace wardmap::semantics
