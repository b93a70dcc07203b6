// The keyframe database: inverted-index queries ranked by L1 score with ties broken by id, the
// shared-words filter, add / replace / erase, and the result limits.
#include "slam/place/keyframe_database.h"

#include <gtest/gtest.h>

namespace wardmap::slam::place {
namespace {

// A bag with equal weights on the given words.
BowVector uniform_bag(std::vector<WordId> words) {
  BowVector b;
  for (WordId w : words) b.emplace_back(w, 1.0 / static_cast<double>(words.size()));
  return b;
}

std::vector<std::uint64_t> ids(const std::vector<PlaceCandidate>& c) {
  std::vector<std::uint64_t> out;
  for (const auto& x : c) out.push_back(x.id);
  return out;
}

TEST(KeyframeDatabase, RanksByScoreThenById) {
  KeyframeDatabase db;
  db.add(7, uniform_bag({1, 2, 3, 4, 5}));
  db.add(5, uniform_bag({1, 2, 3, 4, 6}));
  db.add(3, uniform_bag({1, 2, 3, 4, 5}));  // same bag as 7
  db.add(9, uniform_bag({10, 11, 12}));     // nothing in common
  const auto c = db.query(uniform_bag({1, 2, 3, 4, 5}), 10);
  ASSERT_EQ(ids(c), (std::vector<std::uint64_t>{3, 7, 5}));
  EXPECT_NEAR(c[0].score, 1.0, 1e-12);
  EXPECT_NEAR(c[1].score, 1.0, 1e-12);
  EXPECT_NEAR(c[2].score, 0.8, 1e-12);
}

TEST(KeyframeDatabase, KeepsOnlyKeyframesSharingMostOfTheMostSharedWords) {
  KeyframeDatabase db;
  db.add(1, uniform_bag({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));    // shares 10
  db.add(2, uniform_bag({1, 2, 3, 4, 5, 6, 7, 8, 20, 21}));   // shares 8 = 0.8 x 10: kept
  db.add(3, uniform_bag({1, 2, 3, 4, 5, 6, 7, 30, 31, 32}));  // shares 7: dropped
  const auto query = uniform_bag({1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  EXPECT_EQ(ids(db.query(query, 0)), (std::vector<std::uint64_t>{1, 2}));
  PlaceOptions all;
  all.min_common_ratio = 0.0;
  KeyframeDatabase loose(all);
  for (std::uint64_t id : {1, 2, 3}) loose.add(id, *db.bow(id));
  EXPECT_EQ(ids(loose.query(query, 0)), (std::vector<std::uint64_t>{1, 2, 3}));
}

TEST(KeyframeDatabase, LimitsResultsAndScores) {
  KeyframeDatabase db{[] {
    PlaceOptions o;
    o.min_common_ratio = 0.0;
    return o;
  }()};
  db.add(1, uniform_bag({1, 2, 3, 4}));  // score 1
  db.add(2, uniform_bag({1, 2, 3, 9}));  // 0.75
  db.add(3, uniform_bag({1, 8, 9, 7}));  // 0.25
  const auto query = uniform_bag({1, 2, 3, 4});
  EXPECT_EQ(ids(db.query(query, 2)), (std::vector<std::uint64_t>{1, 2}));
  EXPECT_EQ(ids(db.query(query, 0, 0.5)), (std::vector<std::uint64_t>{1, 2}));
  EXPECT_TRUE(db.query({}, 5).empty());
}

TEST(KeyframeDatabase, EraseAndReplace) {
  KeyframeDatabase db;
  db.add(1, uniform_bag({1, 2, 3}));
  db.add(2, uniform_bag({1, 2, 3}));
  EXPECT_EQ(db.size(), 2u);
  EXPECT_TRUE(db.erase(1));
  EXPECT_FALSE(db.erase(1));
  EXPECT_FALSE(db.contains(1));
  EXPECT_EQ(ids(db.query(uniform_bag({1, 2, 3}), 0)), (std::vector<std::uint64_t>{2}));
  db.add(2, uniform_bag({7, 8}));  // replaces: no longer found by words 1-3
  EXPECT_EQ(db.size(), 1u);
  EXPECT_TRUE(db.query(uniform_bag({1, 2, 3}), 0).empty());
  EXPECT_EQ(ids(db.query(uniform_bag({7, 8}), 0)), (std::vector<std::uint64_t>{2}));
  db.clear();
  EXPECT_EQ(db.size(), 0u);
  EXPECT_TRUE(db.query(uniform_bag({7, 8}), 0).empty());
}

TEST(KeyframeDatabase, InvalidOptionsThrow) {
  PlaceOptions o;
  o.min_common_ratio = -0.1;
  EXPECT_THROW(KeyframeDatabase{o}, std::invalid_argument);
}

}  // namespace
}  // namespace wardmap::slam::place
