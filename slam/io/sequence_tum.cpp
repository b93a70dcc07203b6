// TUM RGB-D: rgb.txt and depth.txt (`timestamp path`), groundtruth.txt, depth factor 5000.
#include <algorithm>
#include <limits>

#include "slam/core/errors.h"
#include "slam/io/sequence.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

namespace {

struct TimedPath {
  double t;
  fs::path path;
  long line;
};

std::vector<TimedPath> read_index(const fs::path& root, const char* name) {
  const fs::path file = root / name;
  std::vector<TimedPath> out;
  double previous = -std::numeric_limits<double>::infinity();
  for_each_data_line(file, false, [&](long line, const std::vector<std::string>& tok) {
    if (tok.size() != 2)
      throw InputError(file.string(),
                       "expected 'timestamp path', got " + std::to_string(tok.size()) +
                           (tok.size() == 1 ? " field" : " fields") +
                           (tok.size() > 2 ? " (a file name with a space in it? The format has none)" : ""),
                       line);
    const double t = parse_double(tok[0], file, line, "timestamp");
    check_increasing(t, previous, file, line);
    previous = t;
    out.push_back({t, root / tok[1], line});
  });
  if (out.empty()) throw InputError(file.string(), "no frames listed");
  return out;
}

class TumReader : public SequenceReader {
 public:
  TumReader(const fs::path& root, const ReaderOptions& o) {
    info_.kind = DatasetKind::TumRgbd;
    info_.root = root;
    info_.depth_factor = 5000.0;  // TUM RGB-D; ReaderOptions::depth_factor overrides it (open_sequence)
    info_.fps = 30.0;
    const auto rgb = read_index(root, "rgb.txt");
    std::vector<TimedPath> depth;
    if (fs::exists(root / "depth.txt")) depth = read_index(root, "depth.txt");
    std::vector<double> depth_times;
    for (const auto& d : depth) depth_times.push_back(d.t);
    size_t dropped = 0;
    for (const auto& r : rgb) {
      Entry e;
      e.timestamp = r.t;
      e.image = r.path;
      e.listed_in = root / "rgb.txt";
      e.line = r.line;
      if (!depth.empty()) {
        const auto k = nearest_within(depth_times, r.t, o.max_dt);
        if (!k) {
          ++dropped;
          continue;
        }
        e.depth = depth[*k].path;
        e.depth_listed_in = root / "depth.txt";
        e.depth_line = depth[*k].line;
      }
      entries_.push_back(std::move(e));
    }
    if (dropped)
      add_note(std::to_string(dropped) + " colour frames without depth within " + std::to_string(o.max_dt) +
               " s dropped");
    if (fs::exists(root / "groundtruth.txt")) {
      ground_truth_ = read_trajectory(root / "groundtruth.txt", PoseFormat::Tum);
      attach_ground_truth_by_time(o.max_dt);
    }
    finish_opening();
  }
};

}  // namespace

std::unique_ptr<SequenceReader> open_tum(const fs::path& root, const ReaderOptions& o) {
  return std::make_unique<TumReader>(root, o);
}

}  // namespace wardmap::slam::io
