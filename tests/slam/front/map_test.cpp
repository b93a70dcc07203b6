#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "tests/support/test_camera.h"
#include "slam/front/bounded_queue.h"
#include "slam/front/front_process.h"
#include "slam/front/keyframe_policy.h"
#include "slam/front/local_bundle_adjustment.h"
#include "slam/front/submap.h"
#include "slam/front/triangulation.h"
#include "tests/slam/front/test_images.h"

namespace wardmap::slam {

namespace {

PinholeCamera camera() { return test::vga_camera(); }

std::shared_ptr<const FrameFeatures> features() {
  static OrbExtractor ex{OrbOptions{}};
  static auto f = make_frame_features(test::textured_image(), cv::Mat(), ex, camera(), 0.08, 10, 0.05);
  return f;
}

// Up to 80 points on kf0's keypoint rays, at depth(i), each seen at the same keypoint by every
// keyframe; then the covisibility graph.
void observe_on_first_rays(Submap& map, const std::vector<std::shared_ptr<KeyFrame>>& kfs,
                           const std::function<double(size_t)>& depth) {
  const FrameFeatures& f = *features();
  for (size_t i = 0; i < std::min<size_t>(80, f.points.size()); ++i) {
    auto mp = map.create_map_point(camera().unproject(f.points[i]) * depth(i), *kfs[0]);
    for (const auto& kf : kfs) {
      mp->add_observation(kf, static_cast<int>(i));
      kf->set_map_point(i, mp);
    }
  }
  for (const auto& kf : kfs) kf->update_connections();
}

}  // namespace

TEST(Submap, ObservationsBuildTheCovisibilityGraph) {
  Submap map(0);
  std::vector<std::shared_ptr<KeyFrame>> kfs;
  for (int k = 0; k < 3; ++k) {
    Frame f(static_cast<std::uint64_t>(k), k * 0.1, features());
    f.set_pose_cw(SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.1 * k, 0, 0)));
    kfs.push_back(map.create_keyframe(f));
  }
  // 40 points seen by kf0 and kf1, 20 of them also by kf2; 5 seen by kf0 and kf2 only.
  for (int i = 0; i < 45; ++i) {
    auto mp = map.create_map_point(Eigen::Vector3d(i * 0.01, 0, 2), *kfs[0]);
    std::vector<int> seen = i < 20   ? std::vector<int>{0, 1, 2}
                            : i < 40 ? std::vector<int>{0, 1}
                                     : std::vector<int>{0, 2};
    for (int k : seen) {
      mp->add_observation(kfs[static_cast<size_t>(k)], i);
      kfs[static_cast<size_t>(k)]->set_map_point(static_cast<size_t>(i), mp);
    }
  }
  for (auto& kf : kfs) kf->update_connections();
  EXPECT_EQ(kfs[0]->weight(kfs[1]->id()), 40);
  EXPECT_EQ(kfs[0]->weight(kfs[2]->id()), 25);
  EXPECT_EQ(kfs[1]->weight(kfs[2]->id()), 20);
  auto best = kfs[0]->best_covisibles(1);
  ASSERT_EQ(best.size(), 1u);
  EXPECT_EQ(best[0], kfs[1]);
  EXPECT_EQ(kfs[1]->tracked_points(3), 20);

  // Culling kf1 keeps its pose through the parent (kf0) and removes its observations.
  const SE3 pose1 = kfs[1]->pose_cw();
  kfs[1]->bow = {{3, 0.5}, {7, 0.5}};
  kfs[1]->feature_vector[1] = {0, 1};
  EXPECT_TRUE(map.take_culled().empty());
  map.erase_keyframe(kfs[1]);
  EXPECT_TRUE(kfs[1]->bad());
  EXPECT_EQ(map.num_keyframes(), 2u);
  EXPECT_EQ(kfs[0]->weight(kfs[1]->id()), 0);
  EXPECT_LT((resolved_pose_cw(kfs[1]).matrix() - pose1.matrix()).norm(), 1e-12);
  // Its point slots, features and words are released (frames referring to it keep only its pose
  // alive); the frame it was made from still has its features.
  EXPECT_EQ(kfs[1]->size(), 0u);
  EXPECT_TRUE(kfs[1]->map_points().empty());
  EXPECT_TRUE(kfs[1]->bow.empty());
  EXPECT_TRUE(kfs[1]->feature_vector.empty());
  EXPECT_EQ(kfs[1]->features().pyramid, features()->pyramid);
  EXPECT_GT(features()->size(), 0u);
  EXPECT_EQ(kfs[0]->size(), features()->size());
  // The culled id is handed out once, for the tracker's place database.
  EXPECT_EQ(map.take_culled(), std::vector<KeyFrameId>{kfs[1]->id()});
  EXPECT_TRUE(map.take_culled().empty());
  // Moving the parent moves the culled keyframe's resolved pose with it.
  kfs[0]->set_pose_cw(SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 1)));
  EXPECT_NEAR(resolved_pose_cw(kfs[1]).translation().z(), 1.0, 1e-12);
  // The origin is never culled.
  map.erase_keyframe(kfs[0]);
  EXPECT_FALSE(kfs[0]->bad());
}

// Local BA asks `abort` after every solver iteration; true ends the solve there and skips the
// refinement (ORB-SLAM's local BA stopping for a waiting keyframe).
TEST(LocalBundleAdjustment, StopsAtTheIterationWhereAbortIsAsked) {
  const auto run = [](const std::function<bool()>& abort) {
    Submap map(0);
    std::vector<std::shared_ptr<KeyFrame>> kfs;
    for (int k = 0; k < 4; ++k) {
      Frame f(static_cast<std::uint64_t>(k), k * 0.1, features());
      f.set_pose_cw(SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.05 * k, 0.01 * (k % 2), 0)));
      kfs.push_back(map.create_keyframe(f));
    }
    // Points at 2 m on the rays of kf0's keypoints, seen at the same keypoints by every keyframe:
    // the other keyframes' observations disagree with them, so the solver has work to do.
    observe_on_first_rays(map, kfs, [](size_t) { return 2.0; });
    FrontOptions o;
    return local_bundle_adjustment(kfs.back(), map, camera(), o, nullptr, abort);
  };
  const LocalBAResult full = run({});
  EXPECT_FALSE(full.aborted);
  EXPECT_LT(full.final_cost, full.initial_cost);
  int asked = 0;
  const LocalBAResult cut = run([&asked] { return ++asked >= 1; });
  EXPECT_TRUE(cut.aborted);
  EXPECT_EQ(asked, 1);  // one iteration of the robust pass, no refinement
  int never = 0;
  const LocalBAResult kept = run([&never] { ++never; return false; });
  EXPECT_FALSE(kept.aborted);
  EXPECT_GT(never, 1);  // asked at every iteration of both passes
  EXPECT_DOUBLE_EQ(kept.final_cost, full.final_cost);
}

// Four keyframes that see 80 points at the same pixels agree only when they share kf0's pose (the
// points lie on kf0's rays, kf0 is the fixed origin): local BA brings the other three back there
// from a 1 cm / 0.5 degree perturbation, and keeps every observation.
TEST(LocalBundleAdjustment, RecoversPerturbedKeyframePoses) {
  Submap map(0);
  std::vector<std::shared_ptr<KeyFrame>> kfs;
  for (int k = 0; k < 4; ++k) {
    Frame f(static_cast<std::uint64_t>(k), k * 0.1, features());
    const Eigen::Vector3d axis = Eigen::Vector3d(1, 2 * (k % 2) - 1, 0.5 * k).normalized();
    const Eigen::Quaterniond q(Eigen::AngleAxisd(k == 0 ? 0.0 : 0.5 * M_PI / 180, axis));
    f.set_pose_cw(SE3(q, k == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.01, -0.006 * k, 0.004)));
    kfs.push_back(map.create_keyframe(f));
  }
  observe_on_first_rays(map, kfs, [](size_t i) { return 1.5 + 0.01 * static_cast<double>(i % 50); });
  FrontOptions o;
  const LocalBAResult r = local_bundle_adjustment(kfs.back(), map, camera(), o, nullptr, {});
  EXPECT_EQ(r.outliers, 0);
  EXPECT_LT(r.final_cost, 1e-6 * r.initial_cost);
  for (const auto& kf : kfs) {  // all back at kf0's pose, the identity
    const SE3& d = kf->pose_cw();
    EXPECT_LT(d.translation().norm(), 1e-4) << "keyframe " << kf->id();
    EXPECT_LT(Eigen::AngleAxisd(d.rotation()).angle() * 180 / M_PI, 0.005) << "keyframe " << kf->id();
  }
}

TEST(Submap, ReplacingAPointMovesItsObservations) {
  Submap map(0);
  Frame f0(0, 0, features()), f1(1, 0.1, features());
  auto k0 = map.create_keyframe(f0), k1 = map.create_keyframe(f1);
  auto a = map.create_map_point(Eigen::Vector3d(0, 0, 2), *k0);
  auto b = map.create_map_point(Eigen::Vector3d(0, 0, 2.01), *k1);
  a->add_observation(k0, 3);
  k0->set_map_point(3, a);
  b->add_observation(k1, 5);
  k1->set_map_point(5, b);
  b->replace_with(a);
  EXPECT_TRUE(b->bad());
  EXPECT_EQ(b->replaced_by(), a);
  EXPECT_EQ(a->num_observations(), 2);
  EXPECT_EQ(k1->map_point(5), a);
  map.purge_bad_points();
  EXPECT_EQ(map.num_map_points(), 1u);
  map.erase_map_point(a);
  EXPECT_EQ(k0->map_point(3), nullptr);
  EXPECT_EQ(k1->map_point(5), nullptr);
}

TEST(MapPoint, RepresentativeDescriptorHasTheLeastMedianDistanceToTheOthers) {
  // Five keyframes see the point at keypoints 0..4, whose descriptors are set to X with one bit
  // flipped (three of them), X itself (the third) and X inverted: X's median distance is 1, the
  // others' 2 or more.
  auto f = std::make_shared<FrameFeatures>(*features());
  f->descriptors = f->descriptors.clone();
  std::array<uchar, 32> x{};
  for (size_t b = 0; b < x.size(); ++b) x[b] = static_cast<uchar>(37 * b + 11);
  const std::array<int, 5> flipped_bit{5, 77, -1, 200, -2};  // -1: X, -2: X inverted
  for (int i = 0; i < 5; ++i) {
    uchar* d = f->descriptors.ptr<uchar>(i);
    std::copy(x.begin(), x.end(), d);
    const int bit = flipped_bit[static_cast<size_t>(i)];
    if (bit >= 0) d[bit / 8] ^= static_cast<uchar>(1 << (bit % 8));
    if (bit == -2)
      for (int b = 0; b < 32; ++b) d[b] = static_cast<uchar>(~d[b]);
  }
  Submap map(0);
  std::vector<std::shared_ptr<KeyFrame>> kfs;
  for (int k = 0; k < 5; ++k) {
    Frame frame(static_cast<std::uint64_t>(k), k * 0.1, f);
    kfs.push_back(map.create_keyframe(frame));
  }
  auto mp = map.create_map_point(Eigen::Vector3d(0, 0, 2), *kfs[0]);
  EXPECT_EQ(mp->descriptor(), nullptr);
  for (int k = 0; k < 5; ++k) mp->add_observation(kfs[static_cast<size_t>(k)], k);
  mp->update_descriptor();
  ASSERT_NE(mp->descriptor(), nullptr);
  EXPECT_TRUE(std::equal(x.begin(), x.end(), mp->descriptor()));

  // set_descriptor copies: changing the source afterwards leaves the point's descriptor alone.
  std::array<uchar, 32> y = x;
  mp->set_descriptor(y.data());
  y[0] ^= 1;
  EXPECT_TRUE(std::equal(x.begin(), x.end(), mp->descriptor()));
}

TEST(Triangulation, RecoversAPointFromTwoViews) {
  const Eigen::Vector3d X(0.3, -0.2, 4.0);
  const SE3 T1, T2(Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY())), Eigen::Vector3d(-0.2, 0, 0));
  const Eigen::Vector3d p1 = T1 * X, p2 = T2 * X;
  const auto Y = triangulate_dlt(p1 / p1.z(), p2 / p2.z(), T1, T2);
  ASSERT_TRUE(Y.has_value());
  EXPECT_LT((*Y - X).norm(), 1e-9);
  EXPECT_LT(parallax_cos(X, Eigen::Vector3d::Zero(), T2.inverse().translation()), 1.0);
}

TEST(KeyFramePolicy, InsertsWhenTrackingWeakensOrAfterMaxFrames) {
  TrackingOptions o;
  KeyFrameEvidence e;
  e.keyframes_in_map = 5;
  e.reference_points = 400;
  e.tracked_inliers = 380;
  e.tracked_close = 300;
  e.untracked_close = 10;
  e.frames_since_keyframe = 3;
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.tracked_inliers = 250;  // < 0.75 x 400
  EXPECT_TRUE(need_new_keyframe(e, o));
  e.tracked_inliers = 10;  // too weak to make a keyframe from
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.tracked_inliers = 200;
  e.tracked_close = 50;  // few close points tracked, many untracked
  e.untracked_close = 200;
  e.mapper_idle = false;
  EXPECT_TRUE(need_new_keyframe(e, o));
}

TEST(KeyFramePolicy, BusyMapperTakesAKeyframeOnlyWhenDeferringItLeavesTooLongAGap) {
  TrackingOptions o;  // keyframe_max_gap_seconds 0.15
  KeyFrameEvidence e;
  e.keyframes_in_map = 5;
  e.reference_points = 400;
  e.tracked_inliers = 250;  // < 0.75 x 400, not weak (> 0.25 x 400)
  e.frames_since_keyframe = 1;
  e.mapper_idle = false;
  e.deferred_gap_seconds = 2.0 / 30;  // 30 Hz: the next frame is 0.067 s after the keyframe
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.deferred_gap_seconds = 0.2;  // 10 Hz
  EXPECT_TRUE(need_new_keyframe(e, o));
  e.mapper_keyframes_waiting = true;  // one already queued: it waits for the next frame
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.mapper_keyframes_waiting = false;
  o.keyframe_max_gap_seconds = 0.25;
  EXPECT_FALSE(need_new_keyframe(e, o));
}

// An idle mapper counts as busy while the last keyframe is younger than mapping.min_busy_seconds:
// a mapper thread done at once with a young map's keyframe must not get the very next frame too.
TEST(KeyFramePolicy, IdleMapperCountsAsBusyRightAfterAKeyframe) {
  TrackingOptions o;
  KeyFrameEvidence e;
  e.keyframes_in_map = 2;
  e.reference_points = 400;
  e.tracked_inliers = 250;  // < 0.75 x 400, not weak (> 0.25 x 400)
  e.frames_since_keyframe = 1;
  e.mapper_idle = true;
  e.deferred_gap_seconds = 2.0 / 30;
  EXPECT_TRUE(need_new_keyframe(e, o));
  e.keyframe_too_recent = true;
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.tracked_inliers = 50;  // weak tracking takes a keyframe all the same
  EXPECT_TRUE(need_new_keyframe(e, o));
}

// A camera standing still makes no keyframe, neither by the ratio nor by keyframe_max_frames,
// unless tracking is about to fail; 0 switches the rule off.
TEST(KeyFramePolicy, UnmovedViewMakesNoKeyframeUnlessTrackingIsWeak) {
  TrackingOptions o;  // keyframe_still_px 1
  KeyFrameEvidence e;
  e.keyframes_in_map = 5;
  e.reference_points = 400;
  e.tracked_inliers = 250;  // < 0.75 x 400, not weak
  e.tracked_close = 300;
  e.untracked_close = 10;
  e.frames_since_keyframe = 3;
  e.view_motion_px = 1.5;
  EXPECT_TRUE(need_new_keyframe(e, o));
  e.view_motion_px = 0.4;
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.frames_since_keyframe = 50;  // keyframe_max_frames passed long ago
  e.tracked_inliers = 390;
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.view_motion_px = 1.5;
  EXPECT_TRUE(need_new_keyframe(e, o));
  e.view_motion_px = 0.4;
  e.tracked_inliers = 80;  // < 0.25 x 400: the scene changes in front of the still camera
  EXPECT_TRUE(need_new_keyframe(e, o));
  e.tracked_inliers = 10;  // too weak to make a keyframe from
  EXPECT_FALSE(need_new_keyframe(e, o));
  e.tracked_inliers = 390;
  o.keyframe_still_px = 0;
  EXPECT_TRUE(need_new_keyframe(e, o));
}

TEST(BoundedQueue, RefusesWhenFullAndDrainsInOrder) {
  BoundedQueue<int> q(2);
  EXPECT_TRUE(q.try_push(1));
  EXPECT_TRUE(q.try_push(2));
  EXPECT_FALSE(q.try_push(3));
  EXPECT_EQ(*q.try_pop(), 1);
  EXPECT_EQ(*q.pop(), 2);
  EXPECT_FALSE(q.try_pop().has_value());
  q.close();
  EXPECT_FALSE(q.pop().has_value());
  EXPECT_FALSE(q.push(4));
}

}  // namespace wardmap::slam
