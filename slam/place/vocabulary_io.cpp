// The vocabulary file, all integers little-endian:
//   8 bytes  magic "WMVOCAB\0"
//   u32      version (1)
//   u32      branching k, u32 levels L, u32 descriptor bytes (32)
//   u32      node count, u32 word count, u64 training images
//   nodes    node count x (u8 child count, 32-byte centre), breadth-first (see Vocabulary's constructor)
//   idf      word count x f32 (IEEE 754)
//   u64      FNV-1a 64 checksum of all the bytes before it
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "slam/core/errors.h"
#include "slam/place/vocabulary.h"

namespace wardmap::slam::place {

namespace {

constexpr char kMagic[8] = {'W', 'M', 'V', 'O', 'C', 'A', 'B', '\0'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 8 + 4 * 6 + 8;
constexpr std::size_t kNodeBytes = 1 + kDescriptorBytes;

std::uint64_t fnv1a64(const char* data, std::size_t n) {
  std::uint64_t h = 14695981039346656037ULL;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<std::uint8_t>(data[i])) * 1099511628211ULL;
  return h;
}

void put(std::string& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

std::uint64_t get(const std::string& in, std::size_t& pos, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(in[pos + i])) << (8 * i);
  pos += bytes;
  return v;
}

}  // namespace

std::string Vocabulary::to_bytes() const {
  std::string out(kMagic, sizeof kMagic);
  put(out, kVersion, 4);
  put(out, static_cast<std::uint32_t>(branching_), 4);
  put(out, static_cast<std::uint32_t>(levels_), 4);
  put(out, kDescriptorBytes, 4);
  put(out, centres_.size(), 4);
  put(out, idf_.size(), 4);
  put(out, training_images_, 8);
  for (std::size_t i = 0; i < centres_.size(); ++i) {
    out.push_back(static_cast<char>(child_count_[i]));
    out.append(reinterpret_cast<const char*>(centres_[i].data()), kDescriptorBytes);
  }
  for (float w : idf_) {
    std::uint32_t bits;
    std::memcpy(&bits, &w, 4);
    put(out, bits, 4);
  }
  put(out, fnv1a64(out.data(), out.size()), 8);
  return out;
}

Vocabulary Vocabulary::from_bytes(const std::string& in, const std::string& name) {
  if (in.size() < kHeaderBytes)
    throw InputError(name, "truncated vocabulary: " + std::to_string(in.size()) + " bytes, the header alone needs " +
                               std::to_string(kHeaderBytes));
  if (std::memcmp(in.data(), kMagic, sizeof kMagic) != 0)
    throw InputError(name, "not a wardmap vocabulary (the file does not start with \"WMVOCAB\")");
  std::size_t pos = sizeof kMagic;
  const auto version = get(in, pos, 4);
  if (version != kVersion)
    throw InputError(name, "vocabulary format version " + std::to_string(version) + ", this build reads version " +
                               std::to_string(kVersion));
  const auto branching = get(in, pos, 4), levels = get(in, pos, 4), descriptor_bytes = get(in, pos, 4);
  const auto nodes = get(in, pos, 4), words = get(in, pos, 4), images = get(in, pos, 8);
  if (descriptor_bytes != static_cast<std::uint64_t>(kDescriptorBytes))
    throw InputError(name, "descriptors of " + std::to_string(descriptor_bytes) +
                               " bytes; only 32-byte ORB descriptors are supported");
  if (branching < 2 || branching > 255 || levels < 1 || levels > 16)
    throw InputError(name, "branching " + std::to_string(branching) + " / levels " + std::to_string(levels) +
                               " out of range ([2, 255] / [1, 16])");
  const std::uint64_t expected = kHeaderBytes + nodes * kNodeBytes + words * 4 + 8;
  if (in.size() < expected)
    throw InputError(name, "truncated vocabulary: " + std::to_string(nodes) + " nodes and " + std::to_string(words) +
                               " words need " + std::to_string(expected) + " bytes, the file has " +
                               std::to_string(in.size()));
  if (in.size() > expected)
    throw InputError(name, std::to_string(in.size() - expected) + " unexpected bytes after the vocabulary's end");
  std::size_t checksum_pos = expected - 8;
  if (get(in, checksum_pos, 8) != fnv1a64(in.data(), expected - 8))
    throw InputError(name, "checksum mismatch: the vocabulary file is corrupted");

  std::vector<Descriptor> centres(nodes);
  std::vector<std::uint8_t> child_counts(nodes);
  for (std::size_t i = 0; i < nodes; ++i) {
    child_counts[i] = static_cast<std::uint8_t>(in[pos++]);
    std::memcpy(centres[i].data(), in.data() + pos, kDescriptorBytes);
    pos += kDescriptorBytes;
  }
  std::vector<float> idf(words);
  for (auto& w : idf) {
    const auto bits = static_cast<std::uint32_t>(get(in, pos, 4));
    std::memcpy(&w, &bits, 4);
  }
  try {
    return Vocabulary(static_cast<int>(branching), static_cast<int>(levels), std::move(centres),
                      std::move(child_counts), std::move(idf), images);
  } catch (const std::invalid_argument& e) {
    throw InputError(name, std::string("inconsistent vocabulary tree: ") + e.what());
  }
}

void Vocabulary::save(const std::filesystem::path& file) const {
  const std::string bytes = to_bytes();
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  const std::filesystem::path tmp = file.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw InputError(file.string(), "cannot write the vocabulary: " + std::generic_category().message(errno));
    }
  }
  std::filesystem::rename(tmp, file);
}

Vocabulary Vocabulary::load(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file.string(), "cannot open the vocabulary file: " + std::generic_category().message(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(file.string(), "cannot read the vocabulary file");
  return from_bytes(ss.str(), file.string());
}

}  // namespace wardmap::slam::place
