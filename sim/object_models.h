// The six object classes built from boxes and cylinders, and a cache of the textures they share
// (instances of one class and variant share textures, so rows of them look identical).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sim/mesh.h"
#include "sim/scenario.h"
#include "sim/textures.h"

namespace wardmap::sim {

class TextureCache {
 public:
  TextureCache(std::vector<Texture>& textures, uint32_t seed) : textures_(textures), seed_(seed) {}
  // The texture stored under `key`, made (with an Rng derived from the seed and the key) on first use.
  int get(const std::string& key, bool wrap, const std::function<cv::Mat(Rng&)>& make);

 private:
  std::vector<Texture>& textures_;
  uint32_t seed_;
  std::map<std::string, int> ids_;
};

// FNV-1a hash of a string (seed salts).
uint32_t hash_string(const std::string& s);

// Triangles of one object in its own frame: x across, y front (+y) to back, z up, origin on the
// floor. The object's box is the tight axis-aligned box of these triangles in this frame.
std::vector<Triangle> build_object_local(ObjectClass cls, int variant, TextureCache& textures, int instance);

}  // namespace wardmap::sim
