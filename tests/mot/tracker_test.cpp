#include "mot/tracker.h"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "mot/mot_metrics.h"

namespace wardmap::mot {
namespace {

Eigen::VectorXf random_unit(std::mt19937& rng, int dim) {
  std::normal_distribution<float> n(0.f, 1.f);
  Eigen::VectorXf v(dim);
  for (int i = 0; i < dim; ++i) v(i) = n(rng);
  return v.normalized();
}

Eigen::VectorXf jitter(std::mt19937& rng, const Eigen::VectorXf& e, float sigma) {
  std::normal_distribution<float> n(0.f, sigma);
  Eigen::VectorXf v = e;
  for (int i = 0; i < v.size(); ++i) v(i) += n(rng);
  return v.normalized();
}

Detection make_detection(double cx, double cy, double w, double h, int cls, const Eigen::VectorXf& emb, int index) {
  Detection d;
  d.box = Eigen::Vector4d(cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2);
  d.class_id = cls;
  d.score = 0.9f;
  d.embedding = emb;
  d.user_index = index;
  return d;
}

// Feeds frames of (gt id, detection) to the tracker, returns CLEAR-MOT over the assignments (a
// detection left without a track counts as a miss).
ClearMotResult run(Tracker& tracker, const std::vector<std::vector<std::pair<int, Detection>>>& frames) {
  ClearMotAccumulator acc;
  for (const auto& frame : frames) {
    std::vector<Detection> dets;
    for (const auto& gd : frame) dets.push_back(gd.second);
    const std::vector<int> ids = tracker.update(dets);
    EXPECT_EQ(ids.size(), dets.size());
    FrameCorrespondences fc;
    for (size_t i = 0; i < ids.size(); ++i) {
      if (ids[i] < 0)
        ++fc.misses;
      else
        fc.matches.emplace_back(frame[i].first, ids[i]);
    }
    acc.add_frame(fc);
  }
  return acc.result();
}

TEST(Tracker, KeepsIdsOfTwoSameClassBoxesCrossing) {
  std::mt19937 rng(5);
  const Eigen::VectorXf ea = random_unit(rng, 128), eb = random_unit(rng, 128);
  std::vector<std::vector<std::pair<int, Detection>>> frames;
  for (int f = 0; f < 21; ++f) {
    // A goes right, B goes left, same row: fully overlapping at f = 10. Detection order alternates so
    // that order cannot carry the identity.
    const Detection a = make_detection(100 + 20 * f, 200, 60, 120, 3, jitter(rng, ea, 0.02f), 0);
    const Detection b = make_detection(500 - 20 * f, 203, 60, 120, 3, jitter(rng, eb, 0.02f), 1);
    if (f % 2)
      frames.push_back({{1, b}, {0, a}});
    else
      frames.push_back({{0, a}, {1, b}});
  }
  Tracker tracker;
  const ClearMotResult r = run(tracker, frames);
  EXPECT_EQ(r.id_switches, 0);
  EXPECT_EQ(r.misses, 0);
  EXPECT_EQ(tracker.tracks().size(), 2u);
  for (const Track& t : tracker.tracks()) EXPECT_TRUE(t.confirmed);
}

TEST(Tracker, KeepsIdsThroughNoisyMotionAndMissedDetections) {
  std::mt19937 rng(17);
  std::normal_distribution<double> pos_noise(0.0, 3.0), size_noise(0.0, 2.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  struct Object {
    double cx, cy, vx, vy, w, h;
    int cls;
    Eigen::VectorXf emb;
  };
  std::vector<Object> objects;
  for (int k = 0; k < 6; ++k)
    objects.push_back({150.0 + 120 * k, 150.0 + 40 * (k % 3), -12 + 5.0 * k, 8 - 3.0 * k, 50 + 5.0 * k, 110, k % 2,
                       random_unit(rng, 64)});
  std::vector<std::vector<std::pair<int, Detection>>> frames;
  int total = 0;
  for (int f = 0; f < 30; ++f) {
    std::vector<std::pair<int, Detection>> frame;
    for (int k = 0; k < static_cast<int>(objects.size()); ++k) {
      if (f > 0 && u(rng) < 0.1) continue;  // missed detection
      const Object& o = objects[k];
      frame.emplace_back(
          k, make_detection(o.cx + o.vx * f + pos_noise(rng), o.cy + o.vy * f + pos_noise(rng), o.w + size_noise(rng),
                            o.h + size_noise(rng), o.cls, jitter(rng, o.emb, 0.05f), total++));
    }
    frames.push_back(frame);
  }
  Tracker tracker;
  const ClearMotResult r = run(tracker, frames);
  EXPECT_EQ(r.id_switches, 0);
  EXPECT_EQ(r.misses, 0);
  EXPECT_DOUBLE_EQ(r.mota, 1.0);
}

TEST(Tracker, FairMotExactOptionsAlsoKeepCrossingIds) {
  std::mt19937 rng(6);
  const Eigen::VectorXf ea = random_unit(rng, 128), eb = random_unit(rng, 128);
  std::vector<std::vector<std::pair<int, Detection>>> frames;
  for (int f = 0; f < 21; ++f)
    frames.push_back({{0, make_detection(100 + 10 * f, 200, 60, 120, 3, jitter(rng, ea, 0.02f), 0)},
                      {1, make_detection(300 - 10 * f, 200, 60, 120, 3, jitter(rng, eb, 0.02f), 1)}});
  TrackerOptions o;
  o.motion_gate_position_only = false;
  o.motion_gate_chi2 = kChi2Inv95Dof4;
  o.match_unconfirmed_by_appearance = false;
  Tracker tracker(o);
  const ClearMotResult r = run(tracker, frames);
  EXPECT_EQ(r.id_switches, 0);
  EXPECT_EQ(r.misses, 0);
}

TEST(Tracker, MotionGateRejectsAFarJumpDespiteIdenticalAppearance) {
  std::mt19937 rng(8);
  const Eigen::VectorXf e = random_unit(rng, 32);
  Tracker tracker;
  int id = -1;
  for (int f = 0; f < 5; ++f) id = tracker.update({make_detection(100 + 5 * f, 100, 40, 80, 0, e, 0)})[0];
  EXPECT_NE(tracker.update({make_detection(900, 600, 40, 80, 0, e, 0)})[0], id);
  // With the gate disabled appearance alone decides.
  TrackerOptions o;
  o.motion_gate_chi2 = 0;
  Tracker ungated(o);
  for (int f = 0; f < 5; ++f) id = ungated.update({make_detection(100 + 5 * f, 100, 40, 80, 0, e, 0)})[0];
  EXPECT_EQ(ungated.update({make_detection(900, 600, 40, 80, 0, e, 0)})[0], id);
}

TEST(Tracker, KeyframeSizedJumpsStayInsideTheDefaultGate) {
  // 45 px per update on a 60 px wide box: typical of keyframes, far beyond video-frame motion.
  std::mt19937 rng(2);
  const Eigen::VectorXf e = random_unit(rng, 32);
  std::vector<std::vector<std::pair<int, Detection>>> frames;
  for (int f = 0; f < 10; ++f) frames.push_back({{0, make_detection(100 + 45 * f, 300 - 10 * f, 60, 120, 0, e, f)}});
  Tracker tracker;
  const ClearMotResult r = run(tracker, frames);
  EXPECT_EQ(r.id_switches, 0);
  EXPECT_EQ(tracker.tracks().size(), 1u);
}

TEST(Tracker, CameraMotionPredictionKeepsIdsOfIdenticalNeighboursInAQuickPan) {
  // Three identical boxes 40 px apart, still for two updates, then the camera pans: every box moves
  // left by 40, then 100 px. The Kalman filter (no image velocity yet) predicts the old places,
  // where the right-hand neighbours now are; the caller's prediction knows the shift.
  const Eigen::VectorXf e = Eigen::VectorXf::Unit(16, 0);
  const std::vector<double> shift = {0, 0, -40, -140};
  auto frame = [&](size_t f) {
    std::vector<std::pair<int, Detection>> dets;
    for (int i = 0; i < 3; ++i) dets.push_back({i, make_detection(300 + 40 * i + shift[f], 200, 36, 80, 0, e, i)});
    return dets;
  };
  auto run_with = [&](bool compensate) {
    Tracker tracker;
    ClearMotAccumulator acc;
    for (size_t f = 0; f < shift.size(); ++f) {
      const double dx = f == 0 ? 0.0 : shift[f] - shift[f - 1];
      const Tracker::BoxPredictor predict = [&](const Track& t) -> std::optional<Eigen::Vector4d> {
        return t.box() + Eigen::Vector4d(dx, 0, dx, 0);
      };
      std::vector<Detection> dets;
      for (const auto& gd : frame(f)) dets.push_back(gd.second);
      const std::vector<int> ids = compensate ? tracker.update(dets, 1.0, predict) : tracker.update(dets);
      FrameCorrespondences fc;
      for (size_t i = 0; i < ids.size(); ++i) fc.matches.emplace_back(static_cast<int>(i), ids[i]);
      acc.add_frame(fc);
    }
    return acc.result();
  };
  EXPECT_GT(run_with(false).id_switches, 0);  // the scene is one that image-space motion gets wrong
  EXPECT_EQ(run_with(true).id_switches, 0);
}

TEST(Tracker, LostTrackIsRecoveredByAppearance) {
  std::mt19937 rng(9);
  const Eigen::VectorXf e = random_unit(rng, 64);
  Tracker tracker;
  int id = -1;
  for (int f = 0; f < 12; ++f) {
    std::vector<Detection> dets;
    if (f < 4 || f >= 8) dets.push_back(make_detection(200 + 10 * f, 200, 50, 100, 1, jitter(rng, e, 0.03f), f));
    const std::vector<int> ids = tracker.update(dets);
    if (dets.empty()) {
      ASSERT_NE(tracker.find(id), nullptr);
      EXPECT_EQ(tracker.find(id)->state, TrackState::kLost);
      continue;
    }
    if (id < 0) id = ids[0];
    EXPECT_EQ(ids[0], id) << "frame " << f;
  }
}

TEST(Tracker, NeverMatchesAcrossClasses) {
  std::mt19937 rng(4);
  const Eigen::VectorXf e = random_unit(rng, 16);
  TrackerOptions o;
  o.confirm_hits = 1;  // else the tentative track of the second class dies on its first miss
  Tracker tracker(o);
  std::map<int, int> id_of_class;
  for (int f = 0; f < 8; ++f) {
    const int cls = f % 2;  // the same box and appearance alternates between two classes
    const std::vector<int> ids = tracker.update({make_detection(300, 300, 80, 80, cls, e, 0)});
    ASSERT_GE(ids[0], 0);
    const Track* t = tracker.find(ids[0]);
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->class_id, cls);
    if (!id_of_class.count(cls)) id_of_class[cls] = ids[0];
    EXPECT_EQ(ids[0], id_of_class[cls]);
  }
  EXPECT_NE(id_of_class[0], id_of_class[1]);
}

TEST(Tracker, WeakDetectionsAreIgnoredAndLostTracksAge) {
  TrackerOptions o;
  o.max_lost_frames = 2;
  Tracker tracker(o);
  Detection d = make_detection(100, 100, 40, 80, 0, Eigen::VectorXf(), 0);
  d.score = 0.2f;
  EXPECT_EQ(tracker.update({d})[0], -1);
  d.score = 0.9f;
  const int id = tracker.update({d})[0];
  EXPECT_GE(id, 0);
  for (int f = 0; f < 3; ++f) tracker.update({});
  EXPECT_EQ(tracker.find(id), nullptr);
}

TEST(Tracker, TentativeTrackNeedsConfirmation) {
  Tracker tracker;
  tracker.update({});  // frame 1 empty: later births are tentative
  const Detection d = make_detection(100, 100, 40, 80, 0, Eigen::VectorXf(), 0);
  const int id = tracker.update({d})[0];
  EXPECT_FALSE(tracker.is_confirmed(id));
  EXPECT_EQ(tracker.update({d})[0], id);
  EXPECT_TRUE(tracker.is_confirmed(id));
}

TEST(Tracker, OptionsNameTheBadField) {
  TrackerOptions o;
  o.motion_lambda = 1.5;
  ASSERT_TRUE(o.validate().has_value());
  EXPECT_NE(o.validate()->find("motion_lambda"), std::string::npos);
  o = TrackerOptions{};
  o.kalman.std_aspect = 0;
  EXPECT_NE(o.validate()->find("kalman.std_aspect"), std::string::npos);
  EXPECT_THROW(Tracker{o}, std::invalid_argument);
}

}  // namespace
}  // namespace wardmap::mot
