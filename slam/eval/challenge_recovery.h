// How tracking fares through the challenge segments of a synthetic sequence (challenges.txt,
// ../shared/docs/FORMATS.md): whether it was lost inside each segment, whether it came back in a new
// submap, and how long after the segment's end it was localised again (issue 4's corridor_loss
// figure, read from the frames' statuses as frames.csv records them).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wardmap::slam::eval {

struct ChallengeSegment {
  double begin = 0, end = 0;  // seconds, the sequence's timestamps
  std::string kind;           // blur, textureless, dark, fast-turn
};

// "t_begin t_end kind" a line, '#' comments. Throws InputError naming the file and line on a
// malformed line or a segment that ends before it begins. The kind is only reported, so any word is
// taken (wardmap synth writes the four above).
std::vector<ChallengeSegment> read_challenges(const std::filesystem::path& file);

// One frame as `wardmap run` records it: status tracked, relocalised, backfilled (localised later by
// a monocular initialisation), initialising or lost; the submap it belongs to.
struct FrameState {
  double timestamp = 0;
  std::string status;
  int submap = -1;
};

// Frames tracking must hold for a segment to count as recovered from (held_after): 1/3 s at 30 Hz.
inline constexpr int kHoldFrames = 10;

struct ChallengeRecovery {
  ChallengeSegment segment;
  bool covered = false;    // the run's frames reach the segment's end
  int frames_inside = 0;   // frames with begin <= t <= end
  int lost_inside = 0;     // of them, not localised
  int submap_before = -1;  // of the last localised frame before the segment (-1: none)
  // The first localised frame at or after the segment's end: its time after the end and its submap.
  std::optional<double> resumed_after;
  int submap_after = -1;
  // The first frame at or after the end from which tracking holds: it and the next hold_frames - 1
  // frames (or all the frames left, when fewer) are localised. A new submap that localises a frame or
  // two and is lost again counts for resumed_after, not for this.
  std::optional<double> held_after;
  bool new_submap() const { return resumed_after && submap_after != submap_before; }
};

// One entry per segment that overlaps the frames' time span, in the segments' order. `frames` in
// time order.
std::vector<ChallengeRecovery> challenge_recovery(const std::vector<FrameState>& frames,
                                                  const std::vector<ChallengeSegment>& segments,
                                                  int hold_frames = kHoldFrames);

}  // namespace wardmap::slam::eval
