#include "slam/eval/challenge_recovery.h"

#include <algorithm>
#include <utility>

#include "slam/core/errors.h"
#include "slam/io/text_file.h"

namespace wardmap::slam::eval {
namespace {

bool localised(const std::string& status) {
  return status == "tracked" || status == "relocalised" || status == "backfilled";
}

}  // namespace

std::vector<ChallengeSegment> read_challenges(const std::filesystem::path& file) {
  std::vector<ChallengeSegment> out;
  io::for_each_data_line(file, false, [&](long line, const std::vector<std::string>& t) {
    if (t.size() != 3)
      throw InputError(file.string(), "expected 't_begin t_end kind', got " + std::to_string(t.size()) + " fields",
                       line);
    ChallengeSegment s;
    s.begin = io::parse_double(t[0], file, line, "t_begin");
    s.end = io::parse_double(t[1], file, line, "t_end");
    s.kind = t[2];
    if (!(s.end >= s.begin)) throw InputError(file.string(), "t_end " + t[1] + " is before t_begin " + t[0], line);
    out.push_back(std::move(s));
  });
  return out;
}

std::vector<ChallengeRecovery> challenge_recovery(const std::vector<FrameState>& frames,
                                                  const std::vector<ChallengeSegment>& segments, int hold_frames) {
  std::vector<ChallengeRecovery> out;
  if (frames.empty()) return out;
  // run[i]: how many frames from i on are localised in a row.
  std::vector<int> run(frames.size() + 1, 0);
  for (size_t i = frames.size(); i-- > 0;) run[i] = localised(frames[i].status) ? run[i + 1] + 1 : 0;
  for (const ChallengeSegment& s : segments) {
    if (s.end < frames.front().timestamp || s.begin > frames.back().timestamp) continue;
    ChallengeRecovery r;
    r.segment = s;
    r.covered = frames.back().timestamp >= s.end;
    for (size_t i = 0; i < frames.size(); ++i) {
      if (frames[i].timestamp < s.end) continue;
      const int left = static_cast<int>(frames.size() - i);
      if (run[i] >= std::min(hold_frames, left)) {
        r.held_after = frames[i].timestamp - s.end;
        break;
      }
    }
    for (const FrameState& f : frames) {
      if (f.timestamp < s.begin) {
        if (localised(f.status)) r.submap_before = f.submap;
      } else if (f.timestamp <= s.end) {
        ++r.frames_inside;
        if (!localised(f.status)) ++r.lost_inside;
      }
      if (f.timestamp >= s.end && localised(f.status)) {
        r.resumed_after = f.timestamp - s.end;
        r.submap_after = f.submap;
        break;
      }
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace wardmap::slam::eval
