// Hierarchical association and the HDP-only baseline on measurements of identical neighbours with
// known identities (no images: boxes, poses and embeddings made up).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "semantics/association_model.h"
#include "semantics/object_association.h"
#include "semantics/object_measurement.h"
#include "tests/semantics/core/options_error.h"
#include "tests/support/test_camera.h"

namespace wardmap::semantics {
namespace {

// Three identical doors `spacing` apart seen in 40 keyframes while the camera passes: boxes slide
// left, positions carry `noise`, embeddings are identical (appearance cannot tell them apart).
std::vector<ObjectMeasurement> passing_doors(unsigned seed, double spacing = 1.2, double noise = 0.04) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  std::vector<ObjectMeasurement> ms;
  Eigen::VectorXf emb = Eigen::VectorXf::Ones(8).normalized();
  for (int kf = 0; kf < 40; ++kf)
    for (int d = 0; d < 3; ++d) {
      const double u = 600 - 12.0 * kf + 150 * d;  // box centre slides with the camera
      if (u < 40 || u > 600) continue;
      ObjectMeasurement m;
      m.id = static_cast<int>(ms.size());
      m.keyframe = kf;
      m.timestamp = kf * 0.3;
      m.box = Eigen::Vector4d(u - 40, 100, u + 40, 380);
      m.label = "door";
      m.score = 0.9f;
      m.embedding = emb;
      m.gt_instance = d;
      m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(spacing * d + n(rng), 2 + n(rng), 1 + n(rng))),
                          Eigen::Vector3d(0.9, 0.05, 2.0)};
      ms.push_back(m);
    }
  return ms;
}

std::vector<std::vector<int>> groups_of(int keyframes, int M, int j) {
  std::vector<std::vector<int>> g;
  for (int s = 0; s + j < keyframes; s += M - j) {
    std::vector<int> k;
    for (int i = s; i < std::min(keyframes, s + M); ++i) k.push_back(i);
    g.push_back(k);
  }
  return g;
}

// Share of measurements whose landmark's majority identity is their own.
double accuracy(const std::vector<ObjectMeasurement>& ms, const AssociationResult& r) {
  std::map<int, std::map<int, int>> votes;
  for (const auto& m : ms)
    if (r.landmark_of[m.id] >= 0) ++votes[r.landmark_of[m.id]][m.gt_instance];
  int ok = 0, n = 0;
  for (const auto& m : ms) {
    if (r.landmark_of[m.id] < 0) continue;
    const auto& v = votes[r.landmark_of[m.id]];
    const int major = std::max_element(v.begin(), v.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
    ok += major == m.gt_instance;
    ++n;
  }
  return n ? static_cast<double>(ok) / n : 0.0;
}

TEST(Association, MotFollowsIdenticalNeighboursThroughAQuickPanWithTheKeyframePoses) {
  // Three identical chairs 0.55 m apart, 3 m ahead; the camera stands still for two keyframes,
  // then turns 0.15 and 0.30 rad: the boxes jump by about 80 and 160 px, more than the 96 px that
  // separate them. Measured positions carry 5 cm noise.
  slam::PinholeCamera cam;
  cam.fx = cam.fy = 525, cam.cx = 319.5, cam.cy = 239.5, cam.width = 640, cam.height = 480;
  const std::vector<double> yaw = {0, 0, 0.15, 0.30};
  KeyframeViews views{cam, {}};
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 0.05);
  std::vector<ObjectMeasurement> ms;
  std::vector<std::vector<int>> by_keyframe(yaw.size());
  for (size_t kf = 0; kf < yaw.size(); ++kf) {
    views.T_wc.push_back(slam::SE3(Eigen::AngleAxisd(yaw[kf], Eigen::Vector3d::UnitY()).toRotationMatrix(),
                                   Eigen::Vector3d::Zero()));
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p_w(0.55 * (c - 1), 0.3, 3.0);
      const Eigen::Vector3d p_c = views.T_wc[kf].inverse() * p_w;
      const Eigen::Vector2d uv = cam.project(p_c);
      const double hw = 0.5 * 525 * 0.45 / p_c.z(), hh = 0.5 * 525 * 0.85 / p_c.z();
      ObjectMeasurement m;
      m.id = static_cast<int>(ms.size());
      m.keyframe = static_cast<int>(kf);
      m.box = Eigen::Vector4d(uv.x() - hw, uv.y() - hh, uv.x() + hw, uv.y() + hh);
      m.label = "chair";
      m.score = 0.9f;
      m.embedding = Eigen::VectorXf::Ones(8).normalized();
      m.gt_instance = c;
      m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), p_w + Eigen::Vector3d(n(rng), 0, n(rng))),
                          Eigen::Vector3d(0.45, 0.45, 0.85)};
      by_keyframe[kf].push_back(m.id);
      ms.push_back(m);
    }
  }
  const std::vector<int> group = {0, 1, 2, 3};
  const mot::TrackerOptions o;
  // Tracks that hold more than one chair.
  auto mixed_tracks = [&](const KeyframeViews* v) {
    std::map<int, std::set<int>> chairs;
    for (const auto& [id, track] : track_in_group(group, by_keyframe, ms, o, v)) chairs[track].insert(ms[id].gt_instance);
    int mixed = 0;
    for (const auto& [track, c] : chairs) mixed += c.size() > 1;
    return mixed;
  };
  EXPECT_GT(mixed_tracks(nullptr), 0);  // the image-space Kalman prediction swaps them
  EXPECT_EQ(mixed_tracks(&views), 0);
}

// Two far doors of one wall, a few pixels wide and 6 px apart, whose embeddings (OSNet on a crop of
// a few pixels) swap from one keyframe to the next: matched by appearance their tracks swap; with
// groups.min_appearance_width above their width the IoU stages keep each on its own door.
TEST(Association, TinyBoxesAreTrackedWithoutTheirEmbedding) {
  std::vector<ObjectMeasurement> ms;
  std::vector<std::vector<int>> by_keyframe(4);
  for (int kf = 0; kf < 4; ++kf)
    for (int d = 0; d < 2; ++d) {
      ObjectMeasurement m;
      m.id = static_cast<int>(ms.size());
      m.keyframe = kf;
      const double x0 = 250 + 12 * d + kf;
      m.box = Eigen::Vector4d(x0, 190, x0 + 6, 300);
      m.label = "door";
      m.score = 0.9f;
      m.embedding = Eigen::VectorXf::Unit(8, (d + kf) % 2);
      m.gt_instance = d;
      by_keyframe[kf].push_back(m.id);
      ms.push_back(m);
    }
  const auto mixed_tracks = [&](double min_width) {
    std::map<int, std::set<int>> doors;
    for (const auto& [id, track] : track_in_group({0, 1, 2, 3}, by_keyframe, ms, mot::TrackerOptions{}, nullptr, min_width))
      if (track >= 0) doors[track].insert(ms[id].gt_instance);
    int mixed = 0;
    for (const auto& [track, d] : doors) mixed += d.size() > 1;
    return mixed;
  };
  EXPECT_GT(mixed_tracks(0), 0);
  EXPECT_EQ(mixed_tracks(16), 0);
  EXPECT_DOUBLE_EQ(load_semantic_options(YAML::Load("groups: {min_appearance_width: 12}"), "s.yaml").groups.min_appearance_width, 12);
  test::expect_load_error_names("groups: {min_appearance_width: -1}", "groups.min_appearance_width");
}

// A chair cut by the right border in the first keyframe (no pose, only its side-cut pose) leaves the
// view as the camera slides left; the chair behind it, tracked meanwhile, reaches the same border
// and is cut there too. Identical embeddings: only motion can tell which track the last box
// continues. The side-cut pose anchors the first chair's track, so the keyframe poses carry its
// predicted box out of the view, and the last box stays with the chair it belongs to.
TEST(Association, MotCarriesASideCutChairOutOfViewWithTheKeyframePoses) {
  const slam::PinholeCamera cam = test::vga_camera(525);
  const double right = cam.width - 1;  // a box reaching past it is cut there
  KeyframeViews views{cam, {}};
  const std::vector<Eigen::Vector3d> chairs = {{1.2, 0.3, 2.2}, {0.3, 0.3, 3.0}};
  std::vector<ObjectMeasurement> ms;
  std::vector<std::vector<int>> by_keyframe(5);
  for (int kf = 0; kf < 5; ++kf) {
    views.T_wc.push_back(slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.4 * kf, 0, 0)));
    for (int c = 0; c < 2; ++c) {
      if (c == 0 && kf > 0) continue;  // out of view
      const Eigen::Vector3d p_c = views.T_wc[kf].inverse() * chairs[c];
      const Eigen::Vector2d uv = cam.project(p_c);
      const double hw = 0.5 * cam.fx * 0.45 / p_c.z(), hh = 0.5 * cam.fy * 0.85 / p_c.z();
      ObjectMeasurement m;
      m.id = static_cast<int>(ms.size());
      m.keyframe = kf;
      m.box = Eigen::Vector4d(uv.x() - hw, uv.y() - hh, std::min(uv.x() + hw, right), uv.y() + hh);
      m.label = "chair";
      m.score = 0.9f;
      m.embedding = Eigen::VectorXf::Ones(8).normalized();
      m.gt_instance = c;
      const ObjectPose pose{slam::SE3(Eigen::Quaterniond::Identity(), chairs[c]), Eigen::Vector3d(0.45, 0.45, 0.85)};
      if (uv.x() + hw > right)
        m.side_cut_pose = pose;  // cut: measured as if uncut only
      else
        m.pose = pose;
      by_keyframe[kf].push_back(m.id);
      ms.push_back(m);
    }
  }
  ASSERT_TRUE(ms.front().side_cut_pose && !ms.back().pose);  // the first chair's box and the last are cut
  std::map<int, std::set<int>> tracks;
  for (const auto& [id, track] : track_in_group({0, 1, 2, 3, 4}, by_keyframe, ms, mot::TrackerOptions{}, &views))
    tracks[track].insert(ms[id].gt_instance);
  for (const auto& [track, c] : tracks) EXPECT_EQ(c.size(), 1u) << "track " << track << " holds both chairs";
}

TEST(Association, HierarchicalSeparatesIdenticalNeighbours) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const auto ms = passing_doors(seed);
    SemanticOptions o;
    o.association.crf.seed = seed;
    // The suffix swaps (on by default; here with the landmark compactness too) keep a right state right.
    if (seed == 4) o.association.suffix_swaps = true, o.association.compactness_weight = 1.0;
    const AssociationResult r = associate_objects(ms, groups_of(40, o.groups.size, o.groups.overlap), o);
    EXPECT_EQ(r.landmarks.size(), 3u) << "seed " << seed;
    EXPECT_DOUBLE_EQ(accuracy(ms, r), 1.0) << "seed " << seed;
    for (const auto& l : r.landmarks) {
      EXPECT_EQ(l.label, "door");
      // Eq. 4-6 picks a measurement near the consensus: within 3 noise sigmas of the true door.
      const int d = ms[l.pose_measurement].gt_instance;
      EXPECT_LT((l.pose.pose.translation() - Eigen::Vector3d(1.2 * d, 2, 1)).norm(), 0.12);
    }
  }
}

TEST(Association, DeterministicForASeed) {
  const auto ms = passing_doors(7);
  SemanticOptions o;
  const auto g = groups_of(40, o.groups.size, o.groups.overlap);
  const AssociationResult a = associate_objects(ms, g, o), b = associate_objects(ms, g, o);
  EXPECT_EQ(a.landmark_of, b.landmark_of);
}

// Several Gibbs chains keep the MAP state of the most probable one, whatever the threads they run on.
// Doors 0.5 m apart with 20 cm noise: the four chains end in different states (the third of them
// is the most probable for this data).
TEST(Association, KeepsTheBestOfSeveralChainsOnAnyThreads) {
  const auto ms = passing_doors(2, 0.5, 0.2);
  SemanticOptions o;
  const auto g = groups_of(40, o.groups.size, o.groups.overlap);
  o.association.chains = 1;
  double best = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < 4; ++c) {
    SemanticOptions one = o;
    one.association.crf.seed = o.association.crf.seed + static_cast<std::uint64_t>(c);
    best = std::max(best, associate_objects(ms, g, one).hdp_log_joint);
  }
  o.association.chains = 4;
  o.association.threads = 1;
  const AssociationResult serial = associate_objects(ms, g, o);
  o.association.threads = 2;
  const AssociationResult parallel = associate_objects(ms, g, o);
  EXPECT_DOUBLE_EQ(serial.hdp_log_joint, best);
  EXPECT_DOUBLE_EQ(parallel.hdp_log_joint, best);
  EXPECT_EQ(serial.landmark_of, parallel.landmark_of);
}

TEST(Association, HdpOnlyBaselineKeepsFirstMeasurementPose) {
  const auto ms = passing_doors(1);
  SemanticOptions o;
  o.association.mode = "hdp-only";
  const AssociationResult r = associate_objects(ms, {}, o);
  ASSERT_FALSE(r.landmarks.empty());
  EXPECT_EQ(r.num_groups, 40);  // one group per keyframe
  for (const auto& l : r.landmarks) {
    EXPECT_EQ(l.pose_measurement, l.measurements.front());
    EXPECT_EQ(r.track_of[l.measurements.front()], -1);  // no MOT
  }
}

TEST(Association, ClassesNeverShareALandmark) {
  auto ms = passing_doors(1);
  for (auto& m : ms)
    if (m.gt_instance == 1) m.label = "cabinet";  // same place scale, other class
  SemanticOptions o;
  const AssociationResult r = associate_objects(ms, groups_of(40, o.groups.size, o.groups.overlap), o);
  for (const auto& l : r.landmarks)
    for (int id : l.measurements) EXPECT_EQ(ms[id].label, l.label);
}

// A chair group object of group `id` with one measurement at x.
GroupObject chair_object(int id, double x) {
  GroupObject g;
  g.group = id;
  g.label = "chair";
  g.measurements = {id};
  g.keyframe_measurements = {{id, id}};
  g.features = {pose_feature(ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(x, 0, 0.4)),
                                        Eigen::Vector3d(0.5, 0.5, 0.85)})};
  return g;
}

// A landmark's GMM is the mixture of its group objects' GMMs: one stray group object (measured on its
// neighbour, 0.6 m away) weighs 1/N in it, so it cannot pull the neighbour's group objects in. With
// the best single member's GMM (landmark_mixture: false) it would attract them fully.
TEST(Association, StrayMemberWeighsOneNthOfTheLandmarkPrior) {
  // Objects 0-4 at x = 0 and a stray 5 at x = 0.6 form landmark A; 6-10 at x = 0.6 form B; 11 is
  // the item, at x = 0.6.
  std::vector<GroupObject> objects;
  std::vector<std::vector<int>> groups;
  for (int i = 0; i < 12; ++i) {
    objects.push_back(chair_object(i, i < 5 ? 0.0 : 0.6));
    groups.push_back({i});
  }
  std::vector<hdp::ItemRef> a, b;
  for (int i = 0; i < 6; ++i) a.push_back({i, 0});
  for (int i = 6; i < 11; ++i) b.push_back({i, 0});
  const hdp::ItemRef item{11, 0};
  AssociationOptions o;
  const AssociationModel mixture(objects, groups, o);
  // A: (1 + 5 g(0.6 m)) / 6 of B's density, g the Gaussian falloff of one component.
  const double g = std::exp(-0.5 * std::pow(0.6 / o.sigma_position, 2));
  EXPECT_NEAR(mixture.log_predictive(item, b) - mixture.log_predictive(item, a), std::log(6.0 / (1 + 5 * g)), 1e-6);
  o.landmark_mixture = false;
  const AssociationModel best_member(objects, groups, o);
  EXPECT_NEAR(best_member.log_predictive(item, b), best_member.log_predictive(item, a), 1e-9);
}

// The score of a whole landmark (the suffix swaps' criterion) loses the spread of its group objects'
// positions, as Gaussians of sigma_position, times compactness_weight: three chairs at x = 0 and
// two at x = 0.6 (two half-landmarks) lose 0.5 * sum |x - mean|^2 / sigma^2; five at one place lose nothing.
TEST(Association, CompactnessWeighsTheSpreadOfALandmark) {
  std::vector<GroupObject> objects;
  std::vector<std::vector<int>> groups;
  for (int i = 0; i < 10; ++i) {
    objects.push_back(chair_object(i, i < 3 || i >= 5 ? 0.0 : 0.6));
    groups.push_back({i});
  }
  std::vector<hdp::ItemRef> split, together;
  for (int i = 0; i < 5; ++i) split.push_back({i, 0});
  for (int i = 5; i < 10; ++i) together.push_back({i, 0});
  AssociationOptions o;
  const AssociationModel plain(objects, groups, o);
  o.compactness_weight = 1.0;
  const AssociationModel compact(objects, groups, o);
  const double mean = 2 * 0.6 / 5, ss = 3 * mean * mean + 2 * (0.6 - mean) * (0.6 - mean);
  EXPECT_NEAR(compact.log_marginal(split) - plain.log_marginal(split), -0.5 * ss / std::pow(o.sigma_position, 2), 1e-9);
  EXPECT_NEAR(compact.log_marginal(together), plain.log_marginal(together), 1e-9);
}

// The suffix-swap keys load over the defaults; a bad value is named in the error.
TEST(Association, SuffixSwapKeysLoadAndABadOneIsNamed) {
  const auto o = load_semantic_options(
      YAML::Load("association: {suffix_swaps: false, suffix_swap_min_gain: 2.5, compactness_weight: 0.5}"), "s.yaml");
  EXPECT_TRUE(SemanticOptions().association.suffix_swaps);
  EXPECT_FALSE(o.association.suffix_swaps);
  EXPECT_DOUBLE_EQ(o.association.suffix_swap_min_gain, 2.5);
  EXPECT_DOUBLE_EQ(o.association.compactness_weight, 0.5);
  test::expect_load_error_names("association: {compactness_weight: -1}", "association.compactness_weight");
}

// A chair-sized landmark turned by `yaw`, holding measurement ids first_id .. first_id + count - 1.
ObjectLandmark landmark_at(const std::string& label, double x, double y, int first_id, int count, double yaw = 0.3) {
  ObjectLandmark l;
  l.label = label;
  l.pose = ObjectPose{slam::SE3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(x, y, 0.4)),
                      Eigen::Vector3d(0.5, 0.5, 0.85)};
  for (int i = 0; i < count; ++i) l.measurements.push_back(first_id + i);
  return l;
}

// A landmark inside the footprint of a same-class landmark with more measurements, or holding its
// centre in its own footprint when the two were never seen together, joins it, and the merged
// landmark's pose is chosen again; one just outside it, or of another class, stays.
TEST(Association, LandmarkInsideAStrongerOneOfItsClassJoinsIt) {
  std::vector<ObjectLandmark> ls = {landmark_at("chair", 0.12, 0.10, 100, 4),     // inside the next one
                                    landmark_at("chair", 0.0, 0.0, 0, 10),
                                    landmark_at("chair", 0.0, 0.45, 200, 5),      // beyond its 0.25 m half-width
                                    landmark_at("cabinet", 0.05, 0.0, 300, 3)};   // another class
  std::vector<size_t> placed_sizes;
  merge_contained_landmarks(ls, [&](ObjectLandmark& l) {
    placed_sizes.push_back(l.measurements.size());
    l.pose_measurement = l.measurements.front();
  });
  ASSERT_EQ(ls.size(), 3u);
  EXPECT_EQ(ls[0].measurements.size(), 14u);  // the order of the others is kept
  EXPECT_TRUE(std::is_sorted(ls[0].measurements.begin(), ls[0].measurements.end()));
  EXPECT_EQ(ls[0].pose_measurement, 0);
  EXPECT_EQ(placed_sizes, std::vector<size_t>{14});
  EXPECT_EQ(ls[1].measurements.front(), 200);
  EXPECT_EQ(ls[2].label, "cabinet");

  // The weaker of two is the one merged, whichever comes first; equal ones: the later.
  std::vector<ObjectLandmark> two = {landmark_at("chair", 0.0, 0.0, 0, 3), landmark_at("chair", 0.1, 0.0, 10, 3)};
  merge_contained_landmarks(two, [](ObjectLandmark&) {});
  ASSERT_EQ(two.size(), 1u);
  EXPECT_EQ(two[0].measurements, (std::vector<int>{0, 1, 2, 10, 11, 12}));

  // A fragment turned otherwise (aisle_straight_quick_1, seed 3: yaw -0.17 against -0.62) lies just
  // outside the stronger one's turned footprint but holds its centre: one object, merged.
  std::vector<ObjectLandmark> turned = {landmark_at("chair", 0.0, 0.0, 0, 36, -0.62),
                                        landmark_at("chair", 0.2, -0.19, 100, 12, -0.17)};
  ASSERT_GT((turned[0].pose.pose.inverse() * turned[1].pose.pose.translation()).x(), 0.25);
  const auto trusted = [](const ObjectLandmark&, const ObjectLandmark&) { return true; };
  const auto untrusted = [](const ObjectLandmark&, const ObjectLandmark&) { return false; };  // seen together
  std::vector<ObjectLandmark> kept = turned;
  merge_contained_landmarks(kept, [](ObjectLandmark&) {}, untrusted);
  EXPECT_EQ(kept.size(), 2u);
  merge_contained_landmarks(turned, [](ObjectLandmark&) {}, trusted);
  ASSERT_EQ(turned.size(), 1u);
  EXPECT_EQ(turned[0].measurements.size(), 48u);
  // Neighbours of a row 0.56 m apart stay apart, however they are turned.
  std::vector<ObjectLandmark> row = {landmark_at("chair", 0.0, 0.0, 0, 36, -0.62),
                                     landmark_at("chair", 0.56, 0.0, 100, 12, 0.0)};
  merge_contained_landmarks(row, [](ObjectLandmark&) {}, trusted);
  EXPECT_EQ(row.size(), 2u);
}

// A keyframe where two lists hold different measurements counts once, however many they hold there.
TEST(Association, KeyframesDetectedApartAreCountedOncePerKeyframe) {
  const std::vector<std::pair<int, int>> a = {{1, 10}, {2, 20}, {2, 21}, {3, 30}, {5, 50}};
  const std::vector<std::pair<int, int>> b = {{1, 11}, {2, 22}, {3, 30}, {4, 40}, {5, 51}};
  EXPECT_EQ(keyframes_detected_apart(a, b), 3);  // 1, 2 and 5; 3 is one shared measurement
  EXPECT_EQ(keyframes_detected_apart(b, a), 3);
  EXPECT_EQ(keyframes_detected_apart(a, b, 2), 2);
  EXPECT_EQ(keyframes_detected_apart(a, a), 0);
  EXPECT_TRUE(detected_apart_in_one_keyframe(a, b));
  EXPECT_FALSE(detected_apart_in_one_keyframe(a, {{3, 30}, {4, 40}}));
  // Shares of the keyframes of the one seen in fewer (a: 4, b: 5).
  EXPECT_TRUE(detected_apart_in_share(a, b, 0.75));
  EXPECT_FALSE(detected_apart_in_share(a, b, 0.8));
  // Fragments of one object: apart only where one holds a neighbour's box (1 of 4 keyframes).
  const std::vector<std::pair<int, int>> fragment = {{1, 10}, {6, 60}, {7, 70}, {8, 80}};
  EXPECT_FALSE(detected_apart_in_share(fragment, b, 0.5));
  EXPECT_TRUE(detected_apart_in_share(fragment, b, 0.25));
  EXPECT_FALSE(detected_apart_in_share({}, b, 0.1));
}

// Two chairs of a row seen end-on (aisle_straight_quick_5): the farther one's boxes were measured on
// the nearer in some keyframes, and its landmark was placed there. Detected apart, they are two
// objects: the one with more placed measurements outside the other's footprint is placed from those,
// and both stay; without place_apart it is merged.
TEST(Association, TwoChairsDetectedApartAreNotMergedButPlacedApart) {
  std::vector<ObjectMeasurement> ms;
  const auto add = [&](double x, double size = 0.5) {
    ObjectMeasurement m;
    m.id = static_cast<int>(ms.size());
    m.keyframe = m.id;
    m.label = "chair";
    m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(x, -1.0, 0.4)),
                        Eigen::Vector3d(size, size, 0.85)};
    ms.push_back(m);
    return m.id;
  };
  // The medoid along x of the placed measurements (Eq. 4-6 stand-in).
  const auto place = [&](ObjectLandmark& l) {
    double best = std::numeric_limits<double>::infinity();
    for (int i : l.measurements) {
      if (!ms[i].pose) continue;
      double sum = 0;
      for (int j : l.measurements)
        if (ms[j].pose) sum += std::abs(ms[i].pose->pose.translation().x() - ms[j].pose->pose.translation().x());
      if (sum < best) best = sum, l.pose_measurement = i, l.pose = *ms[i].pose;
    }
  };
  ObjectLandmark near, far;
  near.label = far.label = "chair";
  for (int i = 0; i < 6; ++i) near.measurements.push_back(add(10.27));
  for (int i = 0; i < 4; ++i) far.measurements.push_back(add(10.9));
  for (int i = 0; i < 3; ++i) far.measurements.push_back(add(10.3));
  place(near);
  far.pose = ms[far.measurements.back()].pose.value();  // placed on the nearer chair's measurements
  far.pose_measurement = far.measurements.back();
  const std::vector<int> far_ids = far.measurements;

  ObjectLandmark a = far, b = near;
  EXPECT_EQ(place_apart(a, b, ms, place, 5), nullptr);  // 4 placed outside: too few
  EXPECT_EQ(a.pose_measurement, far.pose_measurement);
  ASSERT_EQ(place_apart(a, b, ms, place, 3), &a);
  EXPECT_NEAR(a.pose.pose.translation().x(), 10.9, 1e-9);
  EXPECT_EQ(a.measurements, far_ids);  // measurements stay
  EXPECT_EQ(b.pose_measurement, near.pose_measurement);
  a = far, b = near;
  ASSERT_EQ(place_apart(b, a, ms, place, 3), &a);  // either order: the one with more outside moves
  EXPECT_NEAR(a.pose.pose.translation().x(), 10.9, 1e-9);
  EXPECT_NEAR(b.pose.pose.translation().x(), 10.27, 1e-9);

  // Placed from the outside ones, its footprint would hold the other's centre: not moved.
  ObjectLandmark wide = far;
  wide.measurements.erase(wide.measurements.begin(), wide.measurements.begin() + 4);  // the 3 at 10.3
  for (int i = 0; i < 3; ++i) wide.measurements.push_back(add(10.9, 1.6));
  EXPECT_EQ(place_apart(wide, b, ms, place, 3), nullptr);
  EXPECT_EQ(wide.pose_measurement, far.pose_measurement);

  const auto apart = [&](ObjectLandmark& x, ObjectLandmark& y, const FreePose& free) {
    return place_apart(x, y, ms, place, 3, free);
  };
  std::vector<ObjectLandmark> merged = {near, far}, kept = {near, far};
  merge_contained_landmarks(merged, place);
  EXPECT_EQ(merged.size(), 1u);
  merge_contained_landmarks(kept, place, nullptr, apart);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_NEAR(kept[1].pose.pose.translation().x(), 10.9, 1e-9);
  EXPECT_EQ(kept[1].measurements, far_ids);
  // Moved apart onto a third chair's place (ward_slow_5: a split chair between two neighbours), it
  // would stand in that one, and the other has nothing outside: the pair merges, as without
  // place_apart.
  ObjectLandmark third;
  third.label = "chair";
  for (int i = 0; i < 20; ++i) third.measurements.push_back(add(10.85));
  place(third);
  std::vector<ObjectLandmark> row = {third, near, far};
  merge_contained_landmarks(row, place, nullptr, apart);
  ASSERT_EQ(row.size(), 2u);
  EXPECT_EQ(row[0].measurements.size(), 20u);
  EXPECT_EQ(row[1].measurements.size(), 13u);
  EXPECT_NEAR(row[0].pose.pose.translation().x(), 10.85, 1e-9);

  // The first choice would land on a third chair, the second is free (aisle_straight_slow_5, noise
  // 3: chair 12's landmark has more measurements outside, on chair 11; chair 13's lie on chair 13).
  ObjectLandmark front, middle;
  front.label = middle.label = "chair";
  for (int i = 0; i < 20; ++i) front.measurements.push_back(add(9.61));
  place(front);
  for (int i = 0; i < 6; ++i) middle.measurements.push_back(add(10.22));
  for (int i = 0; i < 5; ++i) middle.measurements.push_back(add(9.61));
  place(middle);
  ASSERT_NEAR(middle.pose.pose.translation().x(), 10.22, 1e-9);
  ObjectLandmark first = middle, second = far;
  const auto free_of_front = [&](const ObjectLandmark&, const ObjectPose& pose) {
    return std::abs(pose.pose.translation().x() - 9.61) > 0.25;
  };
  EXPECT_EQ(place_apart(first, second, ms, place, 3), &first);  // without `free`: the first choice
  EXPECT_NEAR(first.pose.pose.translation().x(), 9.61, 1e-9);
  first = middle;
  EXPECT_EQ(place_apart(first, second, ms, place, 3, free_of_front), &second);
  EXPECT_NEAR(second.pose.pose.translation().x(), 10.9, 1e-9);
  EXPECT_NEAR(first.pose.pose.translation().x(), 10.22, 1e-9);
  std::vector<ObjectLandmark> three = {front, middle, far};
  merge_contained_landmarks(three, place, nullptr, apart);
  ASSERT_EQ(three.size(), 3u);
  EXPECT_NEAR(three[1].pose.pose.translation().x(), 10.22, 1e-9);
  EXPECT_NEAR(three[2].pose.pose.translation().x(), 10.9, 1e-9);
}

TEST(Association, PlaceApartShareLoadsAndABadValueIsNamed) {
  EXPECT_DOUBLE_EQ(SemanticOptions().association.place_apart_min_share, 0.5);
  EXPECT_DOUBLE_EQ(load_semantic_options(YAML::Load("association: {place_apart_min_share: 0}"), "s.yaml")
                       .association.place_apart_min_share,
                   0.0);
  test::expect_load_error_names("association: {place_apart_min_share: 1.5}", "association.place_apart_min_share");
}

// A landmark inside the 3-D box of a landmark of another class with more measurements is dropped;
// one above that box, of a support class or under one, with as many measurements, or of the same
// class (merge_contained's work) stays.
TEST(Association, LandmarkInsideAStrongerOneOfAnotherClassIsDropped) {
  auto at_height = [](ObjectLandmark l, double z) {
    Eigen::Vector3d t = l.pose.pose.translation();
    t.z() = z;
    l.pose.pose = slam::SE3(l.pose.pose.rotation(), t);
    return l;
  };
  std::vector<ObjectLandmark> ls = {
      landmark_at("cabinet", 0.1, 0.1, 100, 3),               // 0: inside the wheelchair's box: dropped
      landmark_at("wheelchair", 0.0, 0.0, 0, 10),             // 1
      at_height(landmark_at("tv", 0.05, 0.0, 200, 3), 1.0),   // 2: above it (its box ends at 0.825 m)
      landmark_at("chair", 3.0, 0.0, 300, 4),                 // 3: under the table
      landmark_at("table", 3.1, 0.1, 400, 20),                // 4: a support class
      landmark_at("cabinet", 6.0, 0.0, 500, 5),               // 5
      landmark_at("wheelchair", 6.1, 0.0, 600, 5),            // 6: as many measurements
      landmark_at("wheelchair", 0.1, -0.1, 700, 4)};          // 7: the same class
  drop_landmarks_inside_other_classes(ls, SemanticOptions().support_classes);
  ASSERT_EQ(ls.size(), 7u);
  const std::vector<std::string> labels = {"wheelchair", "tv", "chair", "table", "cabinet", "wheelchair", "wheelchair"};
  for (size_t i = 0; i < ls.size(); ++i) EXPECT_EQ(ls[i].label, labels[i]) << i;
  EXPECT_EQ(ls[0].measurements.size(), 10u);  // nothing joins the stronger one

  // Just outside the footprint (0.25 m half-width) stays too.
  std::vector<ObjectLandmark> beside = {landmark_at("wheelchair", 0.0, 0.0, 0, 10),
                                        landmark_at("cabinet", 0.0, 0.3 / std::cos(0.3), 100, 3)};
  drop_landmarks_inside_other_classes(beside, SemanticOptions().support_classes);
  EXPECT_EQ(beside.size(), 2u);
}

// A boolean association key: on by default, loads false over it, and a bad value is named.
void expect_bool_key_on_loads_and_names_a_bad_value(const std::string& key, bool AssociationOptions::*member,
                                                    const std::string& bad) {
  EXPECT_TRUE(SemanticOptions().association.*member);
  const auto o = load_semantic_options(YAML::Load("association: {" + key + ": false}"), "s.yaml");
  EXPECT_FALSE(o.association.*member);
  test::expect_load_error_names("association: {" + key + ": " + bad + "}", "association." + key);
}

// An object seen in `keyframes` keyframes by a still camera, at `x0` px from the image's left edge,
// with a pose in the first keyframe only (a chair cut by the border gets none) or in all of them,
// and a door in the middle of the view placed in every keyframe.
std::vector<ObjectMeasurement> object_at_border(const std::string& label, double x0, int keyframes = 5,
                                                bool all_placed = false) {
  std::vector<ObjectMeasurement> ms;
  for (int kf = 0; kf < 5; ++kf)
    for (int o = 0; o < 2; ++o) {
      if (o == 0 && kf >= keyframes) continue;
      ObjectMeasurement m;
      m.id = static_cast<int>(ms.size());
      m.keyframe = kf;
      m.timestamp = kf * 0.1;
      m.label = o == 0 ? label : "door";
      m.box = o == 0 ? Eigen::Vector4d(x0, 300, x0 + 120, 470) : Eigen::Vector4d(300, 100, 380, 380);
      m.score = 0.9f;
      m.embedding = Eigen::VectorXf::Unit(8, o);
      m.gt_instance = o;
      if (o == 1 || kf == 0 || all_placed)
        m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(o == 0 ? -1.0 : 0.0, 0.4, 3.0)),
                            Eigen::Vector3d(0.5, 0.5, 0.85)};
      ms.push_back(m);
    }
  return ms;
}

// An object seen mostly at the image's left or right border is reported with
// border_min_measurements measurements, and a chair, pole or wheelchair with
// border_min_placed_measurements placed ones; elsewhere, with the options at the general minimums,
// or without the keyframe views (no image size), it needs min_measurements and
// min_placed_measurements.
TEST(Association, ObjectSeenAtASideBorderNeedsFewerMeasurements) {
  slam::PinholeCamera cam;
  cam.fx = cam.fy = 525, cam.cx = 319.5, cam.cy = 239.5, cam.width = 640, cam.height = 480;
  const KeyframeViews views{cam, std::vector<slam::SE3>(5)};
  SemanticOptions on, off;
  on.association.border_min_measurements = 2;
  on.association.border_min_placed_measurements = 1;
  off.association.border_min_measurements = off.association.min_measurements;
  off.association.border_min_placed_measurements = off.association.min_placed_measurements;
  const auto groups = groups_of(5, on.groups.size, on.groups.overlap);
  const auto labels = [&](const std::vector<ObjectMeasurement>& ms, const SemanticOptions& o, const KeyframeViews* v) {
    const AssociationResult r = associate_objects(ms, groups, o, v);
    std::multiset<std::string> l;
    for (const auto& lm : r.landmarks) {
      l.insert(lm.label);
      for (int id : lm.measurements) {
        EXPECT_EQ(ms[id].label, lm.label);
      }
      if (lm.label != "door") {
        EXPECT_EQ(lm.pose_measurement, 0);  // its one placed measurement
      }
    }
    return l;
  };
  const std::multiset<std::string> door = {"door"};
  for (double x0 : {0.0, 5.0}) {  // at the border, or a jittered box ending a few pixels short of it
    EXPECT_EQ(labels(object_at_border("chair", x0), on, &views), (std::multiset<std::string>{"chair", "door"})) << x0;
    EXPECT_EQ(labels(object_at_border("door", x0, 2, true), on, &views), (std::multiset<std::string>{"door", "door"}));
  }
  EXPECT_EQ(labels(object_at_border("chair", 100), on, &views), door);
  EXPECT_EQ(labels(object_at_border("door", 100, 2, true), on, &views), door);
  EXPECT_EQ(labels(object_at_border("door", 0, 1, true), on, &views), door);
  EXPECT_EQ(labels(object_at_border("cabinet", 0), on, &views), door);  // not thin: its cuts are completed
  EXPECT_EQ(labels(object_at_border("chair", 0), on, nullptr), door);
  EXPECT_EQ(labels(object_at_border("chair", 0), off, &views), door);
  EXPECT_EQ(labels(object_at_border("door", 0, 2, true), off, &views), door);
  const auto o = load_semantic_options(
      YAML::Load("association: {border_min_measurements: 2, border_min_placed_measurements: 1, border_touch_px: 4}"),
      "s.yaml");
  EXPECT_EQ(o.association.border_min_measurements, 2);
  EXPECT_EQ(o.association.border_min_placed_measurements, 1);
  EXPECT_DOUBLE_EQ(o.association.border_touch_px, 4);
  test::expect_load_error_names("association: {border_min_measurements: 0}", "association.border_min_measurements");
  test::expect_load_error_names("association: {border_min_placed_measurements: 0}",
                                "association.border_min_placed_measurements");
  test::expect_load_error_names("association: {border_touch_px: -2}", "association.border_touch_px");
}

// Adds a detection of `label` in keyframe `kf` (box 150 x 180 px from column `x0`) placed at `at`
// as a 0.45 x 0.45 x 0.8 m box, with an embedding of its own per true instance.
void add_placed_box(std::vector<ObjectMeasurement>& ms, int kf, const std::string& label, double x0,
                    const Eigen::Vector3d& at, int instance) {
  ObjectMeasurement m;
  m.id = static_cast<int>(ms.size());
  m.keyframe = kf;
  m.timestamp = kf * 0.1;
  m.label = label;
  m.box = Eigen::Vector4d(x0, 120, x0 + 150, 300);
  m.score = 0.7f;
  m.embedding = Eigen::VectorXf::Unit(8, instance);
  m.gt_instance = instance;
  m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), at), Eigen::Vector3d(0.45, 0.45, 0.8)};
  ms.push_back(m);
}

// Landmark labels of `ms` associated over `keyframes` still keyframes of the VGA camera.
std::multiset<std::string> landmark_labels(const std::vector<ObjectMeasurement>& ms, int keyframes,
                                           const SemanticOptions& o) {
  const KeyframeViews views{test::vga_camera(525), std::vector<slam::SE3>(keyframes)};
  std::multiset<std::string> l;
  for (const auto& lm :
       associate_objects(ms, groups_of(keyframes, o.groups.size, o.groups.overlap), o, &views).landmarks)
    l.insert(lm.label);
  return l;
}

// Three detections of a cabinet at one place, each alone in its keyframe's group (keyframes 2, 9
// and 16): enough measurements, all placed, but no track holds two of them, so no landmark is
// reported (association.min_track_measurements); with two of them in adjacent keyframes, tracked,
// it is.
TEST(Association, DetectionsNeverTrackedIntoASecondKeyframeAreNotALandmark) {
  const int keyframes = 20;
  const auto measurements = [&](const std::set<int>& cabinet_keyframes) {
    std::vector<ObjectMeasurement> ms;
    for (int kf = 0; kf < keyframes; ++kf) {
      add_placed_box(ms, kf, "door", 400, Eigen::Vector3d(0.5, 0.4, 3.0), 0);
      if (cabinet_keyframes.count(kf)) add_placed_box(ms, kf, "cabinet", 100, Eigen::Vector3d(-1.2, 0.0, 3.0), 1);
    }
    return ms;
  };
  const SemanticOptions o;
  const auto lone = measurements({2, 9, 16});
  EXPECT_EQ(landmark_labels(lone, keyframes, o), (std::multiset<std::string>{"door"}));
  SemanticOptions off = o;
  off.association.min_track_measurements = 1;
  ASSERT_EQ(landmark_labels(lone, keyframes, off), (std::multiset<std::string>{"cabinet", "door"}))
      << "the three must make one landmark";
  EXPECT_EQ(landmark_labels(measurements({2, 3, 16}), keyframes, o), (std::multiset<std::string>{"cabinet", "door"}));
  SemanticOptions hdp = o;
  hdp.association.mode = "hdp-only";  // every keyframe its own group: not applied
  EXPECT_EQ(landmark_labels(lone, keyframes, hdp), (std::multiset<std::string>{"cabinet", "door"}));
  EXPECT_EQ(load_semantic_options(YAML::Load("association: {min_track_measurements: 1}"), "s.yaml")
                .association.min_track_measurements,
            1);
  test::expect_load_error_names("association: {min_track_measurements: 0}", "association.min_track_measurements");
}

// Two false positives of one class at one place, far apart in time (keyframes 2 and 17), one of
// them at the left border: the side-border minimums would report them as an object entering the
// view, but they do not lie in one pass, two adjacent keyframe groups
// (association.border_pass_groups), so they are not reported; the same cabinet at the border in
// keyframes 2 and 3 still is.
TEST(Association, DetectionsAtASideBorderInTwoPassesAreNotAnObjectEnteringTheView) {
  const int keyframes = 20;
  const auto measurements = [&](int second_cabinet_keyframe, double second_cabinet_x0) {
    std::vector<ObjectMeasurement> ms;
    for (int kf = 0; kf < keyframes; ++kf) {
      add_placed_box(ms, kf, "door", 300, Eigen::Vector3d(0.5, 0.4, 3.0), 0);
      if (kf == 2) add_placed_box(ms, kf, "cabinet", 5, Eigen::Vector3d(-1.2, 0.0, 3.0), 1);
      if (kf == second_cabinet_keyframe)
        add_placed_box(ms, kf, "cabinet", second_cabinet_x0, Eigen::Vector3d(-1.1, 0.05, 3.0), 1);
    }
    return ms;
  };
  const SemanticOptions o;
  const auto apart = measurements(17, 200);
  EXPECT_EQ(landmark_labels(apart, keyframes, o), (std::multiset<std::string>{"door"}));
  SemanticOptions off = o;
  off.association.border_pass_groups = 0;
  ASSERT_EQ(landmark_labels(apart, keyframes, off), (std::multiset<std::string>{"cabinet", "door"}))
      << "the two must make one landmark";
  // One pass: the same cabinet at the border in keyframes 2 and 3.
  EXPECT_EQ(landmark_labels(measurements(3, 5), keyframes, o), (std::multiset<std::string>{"cabinet", "door"}));
  EXPECT_EQ(load_semantic_options(YAML::Load("association: {border_pass_groups: 3}"), "s.yaml")
                .association.border_pass_groups,
            3);
  test::expect_load_error_names("association: {border_pass_groups: -1}", "association.border_pass_groups");
}

// A chair fragment reported only through the side-border minimums whose boxes lie where a chair
// landmark reported on its own projects was measured on that chair (its one placed measurement
// 0.9 m off): it is dropped. Keyframes 0-4 see the chair at the left border, keyframes 5-9 (the
// camera turned towards it) in the middle of the view.
TEST(Association, BorderLandmarkWhereAnotherOfItsClassProjectsIsDropped) {
  slam::PinholeCamera cam;
  cam.fx = cam.fy = 525, cam.cx = 319.5, cam.cy = 239.5, cam.width = 640, cam.height = 480;
  const Eigen::Vector3d chair(-1.6, 0.83, 3.0), size(0.5, 0.5, 0.85);
  KeyframeViews views{cam, {}};
  std::vector<ObjectMeasurement> ms;
  for (int kf = 0; kf < 10; ++kf) {
    const double yaw = kf < 5 ? 0.0 : std::atan2(chair.x(), chair.z());
    views.T_wc.push_back(slam::SE3(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix(), Eigen::Vector3d::Zero()));
    Eigen::Vector4d box(1e9, 1e9, -1e9, -1e9);
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner(c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5);
      const Eigen::Vector2d uv = cam.project(views.T_wc[kf].inverse() * (chair + corner.cwiseProduct(size)));
      box = Eigen::Vector4d(std::min(box(0), uv.x()), std::min(box(1), uv.y()), std::max(box(2), uv.x()),
                            std::max(box(3), uv.y()));
    }
    ObjectMeasurement m;
    m.id = kf;
    m.keyframe = kf;
    m.timestamp = kf * 0.1;
    m.box = box.cwiseMax(Eigen::Vector4d::Zero()) + Eigen::Vector4d::Constant(kf < 5 ? 4 : 0);  // a detector's few px
    m.label = "chair";
    m.score = 0.9f;
    m.embedding = Eigen::VectorXf::Unit(8, kf < 5 ? 0 : 1);
    m.gt_instance = 0;
    if (kf == 0 || kf >= 5)
      m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), chair + Eigen::Vector3d(kf == 0 ? 0.9 : 0.0, 0, 0)), size};
    ms.push_back(m);
  }
  ASSERT_LE(ms[0].box(0), 8);  // at the left border
  SemanticOptions o;
  o.association.border_min_placed_measurements = 1;
  const auto groups = groups_of(10, o.groups.size, o.groups.overlap);
  const AssociationResult r = associate_objects(ms, groups, o, &views);
  ASSERT_EQ(r.landmarks.size(), 1u);
  EXPECT_EQ(r.landmarks[0].measurements, (std::vector<int>{5, 6, 7, 8, 9}));
  o.association.border_reprojection_iou = 0.99;  // no projection matches this well: the fragment stays,
  o.association.reproject = "none";  // unless the projections take its measurements (then it drops too)
  EXPECT_EQ(associate_objects(ms, groups, o, &views).landmarks.size(), 2u);
  EXPECT_DOUBLE_EQ(load_semantic_options(YAML::Load("association: {border_reprojection_iou: 0.4}"), "s.yaml")
                       .association.border_reprojection_iou,
                   0.4);
  test::expect_load_error_names("association: {border_reprojection_iou: 1.5}", "association.border_reprojection_iou");
}

// A bed seen in keyframes 0-5 and cut by the left border in keyframes 6 and 7,
// where the detector called it a chair (its own box, another class): the two-measurement chair
// landmark that the side-border minimums would report lies where the bed projects in keyframes
// without a bed measurement, so it is dropped (association.border_other_classes). Where the bed
// was detected too, the chair's box is another detection beside it, and the chair stays.
TEST(Association, BorderLandmarkWhereAnotherClassProjectsUnmeasuredIsDropped) {
  slam::PinholeCamera cam;
  cam.fx = cam.fy = 525, cam.cx = 319.5, cam.cy = 239.5, cam.width = 640, cam.height = 480;
  const Eigen::Vector3d bed(0.0, 0.5, 4.0), size(1.0, 0.6, 2.0);
  KeyframeViews views{cam, {}};
  const auto measurements = [&](bool bed_seen_at_border) {
    std::vector<ObjectMeasurement> ms;
    views.T_wc.clear();
    for (int kf = 0; kf < 8; ++kf) {
      const double yaw = 0.09 * kf;  // turning right: the bed reaches the left border in keyframe 6
      views.T_wc.push_back(
          slam::SE3(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix(), Eigen::Vector3d::Zero()));
      const ObjectPose truth{slam::SE3(Eigen::Quaterniond::Identity(), bed), size};
      const auto box = project_box(truth, cam, views.T_wc[kf]);
      EXPECT_TRUE(box.has_value());
      const auto add = [&](const std::string& label, int gt, std::optional<ObjectPose> pose) {
        ObjectMeasurement m;
        m.id = static_cast<int>(ms.size());
        m.keyframe = kf;
        m.timestamp = kf * 0.1;
        m.box = *box;
        m.label = label;
        m.score = 0.9f;
        m.embedding = Eigen::VectorXf::Unit(8, 0);
        m.gt_instance = gt;
        m.pose = pose;
        ms.push_back(m);
      };
      if (kf < 6) add("bed", 0, truth);
      if (kf >= 6 && bed_seen_at_border) add("bed", 0, std::nullopt);  // cut by the border: no pose
      // The chair's one placed measurement lies on the bed's mattress.
      const ObjectPose on_bed{slam::SE3(Eigen::Quaterniond::Identity(), bed + Eigen::Vector3d(0, -0.4, 0)),
                              Eigen::Vector3d(0.5, 0.5, 0.85)};
      if (kf >= 6) add("chair", -1, kf == 6 ? std::optional<ObjectPose>(on_bed) : std::nullopt);
    }
    return ms;
  };
  SemanticOptions o;
  o.association.reproject = "none";
  const auto labels = [&](const std::vector<ObjectMeasurement>& ms, const SemanticOptions& opt) {
    const auto groups = groups_of(8, opt.groups.size, opt.groups.overlap);
    std::multiset<std::string> l;
    for (const auto& lm : associate_objects(ms, groups, opt, &views).landmarks) l.insert(lm.label);
    return l;
  };
  const auto confused = measurements(false);
  ASSERT_LE(confused.back().box(0), 8);  // at the left border
  EXPECT_EQ(labels(confused, o), (std::multiset<std::string>{"bed"}));
  EXPECT_EQ(labels(measurements(true), o), (std::multiset<std::string>{"bed", "chair"}));
  SemanticOptions off = o;
  off.association.border_other_classes = false;
  EXPECT_EQ(labels(confused, off), (std::multiset<std::string>{"bed", "chair"}));
  EXPECT_FALSE(load_semantic_options(YAML::Load("association: {border_other_classes: false}"), "s.yaml")
                   .association.border_other_classes);
}

// A chair seen only where the left border cuts it (keyframes 6 and 7 of a right turn) has no
// placed measurement, so its track never reaches the sampler; its boxes measured as if uncut
// (side_cut_pose) report it (association.border_side_cut_poses) where it stands on the floor that
// two chairs in view all along stand on, and apart from them unless detected beside them. A bed is
// placed as usual. A chair placed in the keyframe before is a landmark of its own already, and its
// border boxes add nothing. A pole's side cuts (a sliver of its base or shaft) report nothing.
TEST(Association, ThinObjectSeenOnlyAtASideBorderIsPlacedByItsSideCuts) {
  const slam::PinholeCamera cam = test::vga_camera();
  // Camera frame y down, the floor 1.2 m below the camera; boxes upright (their z axis up).
  const Eigen::Quaterniond upright(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  const auto box_at = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& size) {
    return ObjectPose{slam::SE3(upright, p), size};
  };
  const Eigen::Vector3d chair_size(0.5, 0.5, 0.85), chair(0.1, 1.2 - 0.425, 4.0);
  const ObjectPose bed = box_at(Eigen::Vector3d(0.9, 0.9, 6.5), Eigen::Vector3d(1.0, 2.0, 0.6));
  std::vector<ObjectPose> row = {box_at(Eigen::Vector3d(2.6, chair.y(), 6.0), chair_size),
                                 box_at(Eigen::Vector3d(3.4, chair.y(), 6.6), chair_size)};
  const ObjectPose chair_truth = box_at(chair, chair_size);
  // Measured as if uncut: its nearest surface's half, pushed back by the class's depth.
  const ObjectPose side_cut = box_at(chair + Eigen::Vector3d(0.15, 0.03, 0.1), chair_size);
  KeyframeViews views{cam, {}};
  for (int kf = 0; kf < 8; ++kf)
    views.T_wc.push_back(
        slam::SE3(Eigen::AngleAxisd(0.09 * kf, Eigen::Vector3d::UnitY()).toRotationMatrix(), Eigen::Vector3d::Zero()));
  const auto measurements = [&](const std::optional<ObjectPose>& side_cut_pose, bool placed_before,
                                const std::string& label = "chair", bool row_seen_at_border = true) {
    std::vector<ObjectMeasurement> ms;
    const auto add = [&](int kf, const std::string& label, const ObjectPose& truth, int gt, bool placed) {
      ObjectMeasurement m;
      m.id = static_cast<int>(ms.size());
      m.keyframe = kf;
      m.timestamp = kf * 0.1;
      m.box = *project_box(truth, cam, views.T_wc[kf]);
      m.label = label;
      m.score = 0.9f;
      m.embedding = Eigen::VectorXf::Unit(8, gt);
      m.gt_instance = gt;
      if (placed) m.pose = truth;
      ms.push_back(m);
    };
    for (int kf = 0; kf < 8; ++kf) {
      add(kf, "bed", bed, 0, true);
      if (kf < 6 || row_seen_at_border) add(kf, "chair", row[0], 2, true);
      add(kf, "chair", row[1], 3, true);
      if (kf == 5 && placed_before) add(kf, "chair", chair_truth, 1, true);
      if (kf >= 6) {
        add(kf, label, chair_truth, 1, false);
        ms.back().side_cut_pose = side_cut_pose;
      }
    }
    return ms;
  };
  SemanticOptions o;
  const auto groups = groups_of(8, o.groups.size, o.groups.overlap);
  // The landmarks of the border chair's measurements, if any.
  const auto border_chairs = [&](const std::vector<ObjectMeasurement>& ms, const SemanticOptions& opt) {
    std::vector<ObjectLandmark> out;
    const auto landmarks = associate_objects(ms, groups, opt, &views).landmarks;
    EXPECT_EQ(std::count_if(landmarks.begin(), landmarks.end(), [](const auto& l) { return l.label == "bed"; }), 1);
    for (const auto& lm : landmarks)
      if (std::any_of(lm.measurements.begin(), lm.measurements.end(), [&](int id) { return ms[id].gt_instance == 1; }))
        out.push_back(lm);
    EXPECT_EQ(landmarks.size(), 3 + out.size());
    return out;
  };
  const auto seen = measurements(side_cut, false);
  for (const auto& m : seen)
    if (m.gt_instance == 1) {
      ASSERT_LE(m.box(0), 0.5) << "keyframe " << m.keyframe;  // cut by the left border
    }
  const auto found = border_chairs(seen, o);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].measurements.size(), 2u);
  EXPECT_LT((found[0].pose.pose.translation() - side_cut.pose.translation()).norm(), 1e-9);
  EXPECT_TRUE(border_chairs(measurements(std::nullopt, false), o).empty());  // nothing to place it by
  // Completed down from a top that was not its own: 1.7 m under the floor.
  const ObjectPose sunk = box_at(chair + Eigen::Vector3d(0, 1.7, 0), chair_size);
  EXPECT_TRUE(border_chairs(measurements(sunk, false), o).empty());
  // Placed 0.3 m from a chair of the row (their footprints 0.5 m wide would overlap): that chair's
  // boxes, unless that chair was detected beside them.
  const std::vector<ObjectPose> far_row = row;
  row[0] = box_at(side_cut.pose.translation() + Eigen::Vector3d(0.3, 0, 0.1), chair_size);
  EXPECT_TRUE(border_chairs(measurements(side_cut, false, "chair", false), o).empty());
  EXPECT_EQ(border_chairs(measurements(side_cut, false), o).size(), 1u);
  row = far_row;
  EXPECT_TRUE(border_chairs(measurements(side_cut, false, "iv_pole"), o).empty());
  SemanticOptions off = o;
  off.association.border_side_cut_poses = false;
  EXPECT_TRUE(border_chairs(seen, off).empty());
  const auto before = border_chairs(measurements(side_cut, true), o);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_LT((before[0].pose.pose.translation() - chair).norm(), 1e-9);  // placed by its uncut measurement
  EXPECT_FALSE(load_semantic_options(YAML::Load("association: {border_side_cut_poses: false}"), "s.yaml")
                   .association.border_side_cut_poses);
  test::expect_load_error_names("association: {border_side_cut_poses: 3}", "association.border_side_cut_poses");
  EXPECT_DOUBLE_EQ(load_semantic_options(YAML::Load("association: {border_side_cut_floor_tolerance: 0.4}"), "s.yaml")
                       .association.border_side_cut_floor_tolerance,
                   0.4);
  test::expect_load_error_names("association: {border_side_cut_floor_tolerance: 0}",
                                "association.border_side_cut_floor_tolerance");
}

// A bed tracked through keyframes where none of its boxes got a pose: measurements 0-2 form
// landmark 0, 7-9 landmark 1 (measured 2 m off), and the unplaced group objects {2, 3, 4} and
// {4, 5, 6, 7} (sharing detections 2, 4 and 7 through overlapping keyframes) carry the track from
// one to the other: the two landmarks merge, unless they were measured together, one is a fragment
// below the reporting minimums, or the track is of another class.
TEST(Association, UnplacedTrackBridgesTheLandmarksItTouches) {
  const std::vector<std::vector<int>> unplaced = {{2, 3, 4}, {4, 5, 6, 7}};
  const std::vector<std::string> beds = {"bed", "bed"};
  const std::vector<std::string> dish_labels = {"bed", "bed", "chair"};
  const std::vector<bool> all(3, true);
  const std::vector<int> before = {0, 0, 0, -1, -1, -1, -1, 1, 1, 1, 2};
  const std::vector<std::vector<int>> dms = {{0, 1, 2}, {7, 8, 9}, {10}};
  const auto never = [](const std::vector<int>&, const std::vector<int>&) { return true; };
  auto d = before;
  EXPECT_EQ(link_through_unplaced_tracks(unplaced, beds, dish_labels, dms, all, never, d), 1);
  EXPECT_EQ(d, (std::vector<int>{0, 0, 0, -1, -1, -1, -1, 0, 0, 0, 2}));
  d = before;
  const auto seen_together = [](const std::vector<int>& a, const std::vector<int>& b) {
    EXPECT_EQ(a, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(b, (std::vector<int>{7, 8, 9}));
    return false;
  };
  EXPECT_EQ(link_through_unplaced_tracks(unplaced, beds, dish_labels, dms, all, seen_together, d), 0);
  EXPECT_EQ(d, before);
  EXPECT_EQ(link_through_unplaced_tracks(unplaced, beds, dish_labels, dms, {true, false, true}, never, d), 0);
  EXPECT_EQ(d, before);
  EXPECT_EQ(link_through_unplaced_tracks({{2, 3, 4}}, {"bed"}, dish_labels, dms, all, never, d), 0);  // a gap, no bridge
  EXPECT_EQ(link_through_unplaced_tracks(unplaced, {"chair", "chair"}, dish_labels, dms, all, never, d), 0);
  EXPECT_EQ(link_through_unplaced_tracks(unplaced, {"bed", "chair"}, dish_labels, dms, all, never, d), 0);
  EXPECT_EQ(d, before);
  // Through the whole association (groups of 6 keyframes overlapping by 2): the bed's track with
  // poses in keyframes 0-3 and 10-13, 2 m apart, none in group 1's keyframes 4-9. Without the
  // bridge the far part is a second bed.
  std::vector<ObjectMeasurement> ms;
  for (int kf = 0; kf < 14; ++kf) {
    ObjectMeasurement m;
    m.id = kf;
    m.keyframe = kf;
    m.timestamp = kf * 0.3;
    m.box = Eigen::Vector4d(200 + 5 * kf, 250, 500 + 5 * kf, 470);
    m.label = "bed";
    m.score = 0.9f;
    m.embedding = Eigen::VectorXf::Ones(8).normalized();
    m.gt_instance = 0;
    if (kf < 4 || kf > 9)
      m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(kf < 4 ? 0.0 : 2.0, 3, 0.5)),
                          Eigen::Vector3d(1.0, 2.1, 0.9)};
    ms.push_back(m);
  }
  SemanticOptions o;
  o.association.merge_contained = false;
  const auto groups = groups_of(14, o.groups.size, o.groups.overlap);
  ASSERT_EQ(groups.size(), 3u);
  const AssociationResult r = associate_objects(ms, groups, o);
  ASSERT_EQ(r.landmarks.size(), 1u);
  EXPECT_EQ(r.landmarks[0].measurements, (std::vector<int>{0, 1, 2, 3, 4, 5, 8, 9, 10, 11, 12, 13}));
  o.association.bridge_unplaced_tracks = false;
  EXPECT_EQ(associate_objects(ms, groups, o).landmarks.size(), 2u);
}

// Three doors along a wall, landmarks 0-2 (measurements {0, 1}, {5, 6}, {9, 10}); doors 0 and 1
// were detected in one keyframe (measurements 0 and 5), and so were doors 0 and 2 (0 and 9). Far
// boxes without a pose, tracked along the row with ID switches, touch all three: such a track
// bridges none of them. Two tracks that each touch two neighbours bridge the first pair only, as
// the merged landmark then holds a measurement taken together with the third.
TEST(Association, UnplacedTrackSwitchingBetweenObjectsBridgesNone) {
  const std::vector<std::string> dish_labels = {"door", "door", "door"};
  const std::vector<bool> all(3, true);
  const std::vector<int> before = {0, 0, -1, -1, -1, 1, 1, -1, -1, 2, 2};
  const std::vector<std::vector<int>> dms = {{0, 1}, {5, 6}, {9, 10}};
  const auto holds = [](const std::vector<int>& ids, int id) { return std::count(ids.begin(), ids.end(), id) > 0; };
  const auto apart_from = [&](std::vector<std::pair<int, int>> together) {
    return [&holds, together](const std::vector<int>& a, const std::vector<int>& b) {
      for (const auto& [x, y] : together)
        if ((holds(a, x) && holds(b, y)) || (holds(a, y) && holds(b, x))) return false;
      return true;
    };
  };
  auto d = before;
  const std::vector<std::vector<int>> along_the_row = {{1, 2, 3}, {3, 4, 5}, {5, 7, 8, 9}};
  EXPECT_EQ(link_through_unplaced_tracks(along_the_row, {"door", "door", "door"}, dish_labels, dms, all,
                                         apart_from({{0, 5}}), d),
            0);
  EXPECT_EQ(d, before);
  // Tracks {1, 2, 3} + {3, 4, 5} (doors 0 and 1) and {6, 7, 8} + {8, 9} (doors 1 and 2).
  const std::vector<std::vector<int>> two_tracks = {{1, 2, 3}, {3, 4, 5}, {6, 7, 8}, {8, 9}};
  const std::vector<std::string> doors(4, "door");
  d = before;
  EXPECT_EQ(link_through_unplaced_tracks(two_tracks, doors, dish_labels, dms, all, apart_from({{0, 9}}), d), 1);
  EXPECT_EQ(d, (std::vector<int>{0, 0, -1, -1, -1, 0, 0, -1, -1, 2, 2}));
  d = before;
  EXPECT_EQ(link_through_unplaced_tracks(two_tracks, doors, dish_labels, dms, all, apart_from({}), d), 2);
  EXPECT_EQ(d, (std::vector<int>{0, 0, -1, -1, -1, 0, 0, -1, -1, 0, 0}));
}

// The image box of an axis-aligned 3-D box (centre, size) seen by a camera at the origin, world =
// camera frame.
Eigen::Vector4d image_box(const slam::PinholeCamera& cam, const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
  Eigen::Vector4d b(1e9, 1e9, -1e9, -1e9);
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
    const Eigen::Vector2d uv = cam.project(centre + corner.cwiseProduct(size));
    b = Eigen::Vector4d(std::min(b(0), uv.x()), std::min(b(1), uv.y()), std::max(b(2), uv.x()), std::max(b(3), uv.y()));
  }
  return b;
}

// A chair 4 m ahead of a still camera, seen in keyframes 0-5 and again in 10-12, which measured it
// 2 m too far (another look, too: their embedding differs): a fragment landmark of 3 measurements. Its boxes
// lie on the chair's projection, so the landmarks' projections give two of them to the chair; the
// fragment, left with its pinned pose measurement, is no longer reported.
TEST(Association, LandmarkLeftBelowTheMinimumsByTheProjectionsIsDropped) {
  const slam::PinholeCamera cam = test::vga_camera(525);
  const KeyframeViews views{cam, std::vector<slam::SE3>(13)};
  const Eigen::Vector3d chair(0, 0.5, 4.0), size(0.5, 0.5, 0.85);
  const Eigen::Vector4d box = image_box(cam, chair, size);
  std::vector<ObjectMeasurement> ms;
  for (int kf : {0, 1, 2, 3, 4, 5, 10, 11, 12}) {
    ObjectMeasurement m;
    m.id = static_cast<int>(ms.size());
    m.keyframe = kf;
    m.timestamp = kf * 0.1;
    m.box = box;
    m.label = "chair";
    m.score = 0.9f;
    m.embedding = Eigen::VectorXf::Unit(8, kf < 10 ? 0 : 1);
    m.gt_instance = 0;
    m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), chair + Eigen::Vector3d(0, 0, kf < 10 ? 0.0 : 5.0)), size};
    ms.push_back(m);
  }
  SemanticOptions o;
  const auto groups = groups_of(13, o.groups.size, o.groups.overlap);
  // The test's world is the camera's frame (y down): the footprint of the merge would take the
  // fragment's depth for a height, and merge it.
  o.association.merge_contained = false;
  o.association.reproject = "none";
  ASSERT_EQ(associate_objects(ms, groups, o, &views).landmarks.size(), 2u);  // the fragment is a landmark
  o.association.reproject = "all";
  const AssociationResult r = associate_objects(ms, groups, o, &views);
  ASSERT_EQ(r.landmarks.size(), 1u);
  EXPECT_EQ(r.landmarks[0].measurements.size(), 8u);
  EXPECT_EQ(std::count(r.landmark_of.begin(), r.landmark_of.end(), -1), 1);
}

TEST(Association, BridgeUnplacedTracksKeyLoadsAndABadValueIsNamed) {
  expect_bool_key_on_loads_and_names_a_bad_value("bridge_unplaced_tracks", &AssociationOptions::bridge_unplaced_tracks,
                                                 "often");
}

// Two chairs side by side 4 m ahead of a still camera: in keyframe 0 both are placed; in keyframe 1
// their boxes got no pose and MOT swapped them; in keyframe 2 only the right chair is seen, without
// a pose, on the left chair's track, while a placed measurement of the right chair holds its
// landmark; in keyframe 3 an unplaced box lies where no chair projects.
TEST(Association, UnplacedMeasurementsFollowTheLandmarksProjections) {
  const slam::PinholeCamera cam = test::vga_camera(525);
  const KeyframeViews views{cam, std::vector<slam::SE3>(4)};
  const Eigen::Vector3d size(0.5, 0.5, 0.85);
  const std::vector<Eigen::Vector3d> chair = {{-0.6, 0.5, 4.0}, {0.6, 0.5, 4.0}};
  const auto box_of = [&](const Eigen::Vector3d& c) { return image_box(cam, c, size); };
  std::vector<ObjectMeasurement> ms;
  const auto add = [&](int kf, const Eigen::Vector4d& box, bool placed, const Eigen::Vector3d& c) {
    ObjectMeasurement m;
    m.id = static_cast<int>(ms.size());
    m.keyframe = kf;
    m.box = box;
    m.label = "chair";
    if (placed) m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), c), size};
    ms.push_back(m);
    return m.id;
  };
  const int l0 = add(0, box_of(chair[0]), true, chair[0]), r0 = add(0, box_of(chair[1]), true, chair[1]);
  // Keyframe 1's boxes are the detector's, a fifth narrower on each side than the projections (IoU 0.6).
  const auto narrower = [](Eigen::Vector4d b) {
    const double d = 0.2 * (b(2) - b(0));
    b(0) += d, b(2) -= d;
    return b;
  };
  const int l1 = add(1, narrower(box_of(chair[0])), false, chair[0]);
  const int r1 = add(1, narrower(box_of(chair[1])), false, chair[1]);
  const int r2 = add(2, box_of(chair[1]), true, chair[1]), r2u = add(2, box_of(chair[1]), false, chair[1]);
  const int far = add(3, Eigen::Vector4d(10, 10, 60, 90), false, chair[0]);
  std::vector<ObjectLandmark> lms(2);
  for (int i = 0; i < 2; ++i) {
    lms[i].label = "chair";
    lms[i].pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), chair[i]), size};
  }
  lms[0].measurements = {l0, r1, r2u, far};  // the swapped and the stray boxes on the left chair
  lms[1].measurements = {r0, l1, r2};
  reassign_by_projection(lms, ms, views, 0.3, 0.2, false);
  EXPECT_EQ(lms[0].measurements, (std::vector<int>{l0, l1, r2u, far}));
  EXPECT_EQ(lms[1].measurements, (std::vector<int>{r0, r1, r2}));
  // With a minimum IoU above theirs, the tracks' landmarks stay.
  lms[0].measurements = {l0, r1, r2u, far};
  lms[1].measurements = {r0, l1, r2};
  reassign_by_projection(lms, ms, views, 0.7, 0.2, false);
  EXPECT_EQ(lms[0].measurements, (std::vector<int>{l0, r1, r2u, far}));
  // With placed measurements too: keyframe 0's placed boxes swapped, but the left chair's gave its
  // landmark its pose and stays; keyframe 2's placed box of the right chair then frees nothing for
  // its unplaced twin, which stays on the left chair.
  lms[0].measurements = {r0, l1, r2u};
  lms[1].measurements = {l0, r1, r2};
  lms[0].pose_measurement = r0;
  lms[1].pose_measurement = r2;
  reassign_by_projection(lms, ms, views, 0.3, 0.2, true);
  EXPECT_EQ(lms[0].measurements, (std::vector<int>{r0, l1, r2u}));
  EXPECT_EQ(lms[1].measurements, (std::vector<int>{l0, r1, r2}));
  lms[0].pose_measurement = -1;  // no pose measurement among them: keyframe 0's swap is undone
  lms[1].pose_measurement = -1;
  reassign_by_projection(lms, ms, views, 0.3, 0.2, true);
  EXPECT_EQ(lms[0].measurements, (std::vector<int>{l0, l1, r2u}));  // r2 keeps the right chair (margin)
  EXPECT_EQ(lms[1].measurements, (std::vector<int>{r0, r1, r2}));
  EXPECT_EQ(SemanticOptions().association.reproject, "all");
  const auto o = load_semantic_options(
      YAML::Load("association: {reproject: unplaced, reproject_min_iou: 0.4, reproject_margin: 0.1}"), "s.yaml");
  EXPECT_EQ(o.association.reproject, "unplaced");
  EXPECT_DOUBLE_EQ(o.association.reproject_min_iou, 0.4);
  EXPECT_DOUBLE_EQ(o.association.reproject_margin, 0.1);
  test::expect_load_error_names("association: {reproject_min_iou: 1.5}", "association.reproject_min_iou");
  test::expect_load_error_names("association: {reproject_margin: -0.1}", "association.reproject_margin");
  test::expect_load_error_names("association: {reproject: placed}", "association.reproject");
}

// A chair in front of another, seen by a still camera: its boxes and the rear chair's both ended on
// the rear chair's landmark (an MOT track that switched objects). In keyframe 0 the front chair's
// box is the landmark's pose measurement, placed between the two chairs; in keyframe 1 neither is
// placed, and the rear chair's box is a fifth narrower on each side. Judged by the projection from
// that pose, keyframe 0 keeps the rear box (IoU 0.227 against 0.218) but keyframe 1 the front one
// (0.218 against 0.189); the pose measurement left, so the landmark is placed again from the rear
// chair's keyframe 2, and by that projection keyframe 1 keeps the rear box too (0.6 against 0.023).
// Without views the pose measurement stays, then a placed one, then the higher score.
TEST(Association, OneMeasurementPerKeyframeStaysOnALandmark) {
  const slam::PinholeCamera cam = test::vga_camera(525);
  const KeyframeViews views{cam, std::vector<slam::SE3>(3)};
  const Eigen::Vector3d size(0.5, 0.5, 0.85);
  const Eigen::Vector3d rear(0.6, 0.5, 4.0), front(0.9, 0.9, 3.2), between(0.75, 0.7, 3.6);
  std::vector<ObjectMeasurement> ms;
  const auto add = [&](int kf, const Eigen::Vector4d& box, bool placed, const Eigen::Vector3d& at, double score) {
    ObjectMeasurement m;
    m.id = static_cast<int>(ms.size());
    m.keyframe = kf;
    m.box = box;
    m.label = "chair";
    m.score = score;
    if (placed) m.pose = ObjectPose{slam::SE3(Eigen::Quaterniond::Identity(), at), size};
    ms.push_back(m);
    return m.id;
  };
  Eigen::Vector4d narrow_rear = image_box(cam, rear, size);
  const double d = 0.2 * (narrow_rear(2) - narrow_rear(0));
  narrow_rear(0) += d, narrow_rear(2) -= d;
  const int f0 = add(0, image_box(cam, front, size), true, between, 0.9);
  const int r0 = add(0, image_box(cam, rear, size), false, rear, 0.8);
  const int f1 = add(1, image_box(cam, front, size), false, front, 0.9), r1 = add(1, narrow_rear, false, rear, 0.8);
  const int r2 = add(2, image_box(cam, rear, size), true, rear, 0.8);
  std::vector<int> placed_with;  // the measurements the last call of `place` saw
  const auto place = [&](ObjectLandmark& l) {
    placed_with = l.measurements;
    for (int id : l.measurements)
      if (ms[id].pose) {
        l.pose_measurement = id;
        l.pose = *ms[id].pose;
        return;
      }
  };
  const auto landmark = [&]() {
    ObjectLandmark l;
    l.label = "chair";
    l.measurements = {f0, r0, f1, r1, r2};
    l.pose_measurement = f0;
    l.pose = *ms[f0].pose;
    return std::vector<ObjectLandmark>{l};
  };
  auto lms = landmark();
  EXPECT_EQ(keep_one_per_keyframe(lms, ms, &views, place), 2);
  EXPECT_EQ(lms[0].measurements, (std::vector<int>{r0, r1, r2}));
  EXPECT_EQ(placed_with, (std::vector<int>{r0, f1, r2}));  // placed from the first judgement's choices
  EXPECT_EQ(lms[0].pose_measurement, r2);
  EXPECT_EQ(keep_one_per_keyframe(lms, ms, &views, place), 0);  // nothing left to resolve
  // Without views: keyframe 0 keeps the pose measurement, keyframe 1 the higher score.
  lms = landmark();
  placed_with.clear();
  EXPECT_EQ(keep_one_per_keyframe(lms, ms, nullptr, place), 2);
  EXPECT_EQ(lms[0].measurements, (std::vector<int>{f0, f1, r2}));
  EXPECT_TRUE(placed_with.empty());  // the pose measurement stayed: no new placement
  EXPECT_EQ(lms[0].pose_measurement, f0);
}

TEST(Association, OnePerKeyframeKeyLoadsAndABadValueIsNamed) {
  expect_bool_key_on_loads_and_names_a_bad_value("one_per_keyframe", &AssociationOptions::one_per_keyframe, "1.5");
}

TEST(Association, DropInsideOtherClassKeyLoadsAndABadValueIsNamed) {
  expect_bool_key_on_loads_and_names_a_bad_value("drop_inside_other_class",
                                                 &AssociationOptions::drop_inside_other_class, "2");
}

TEST(Association, MergeContainedKeyLoadsAndABadValueIsNamed) {
  expect_bool_key_on_loads_and_names_a_bad_value("merge_contained", &AssociationOptions::merge_contained, "sometimes");
}

}  // namespace

// A misspelt key, or one in the wrong subsection, is an error naming it.
TEST(SemanticOptions, UnknownKeysAreErrors) {
  test::expect_load_error_names("groups: {sise: 4}", "semantics.groups.sise");
  test::expect_load_error_names("groups: {sise: 4}", "did you mean 'semantics.groups.size'");
  test::expect_load_error_names("association: {min_points: 3}", "semantics.association.min_points");
  test::expect_load_error_names("asociation: {chains: 2}", "semantics.asociation");
  test::expect_load_error_names("monocular: {scale_class: [door]}", "semantics.monocular.scale_class");
  EXPECT_EQ(load_semantic_options(YAML::Load("monocular: {scale_classes: [door]}"), "s.yaml").monocular.scale_classes.size(),
            1u);
}

}  // namespace wardmap::semantics
