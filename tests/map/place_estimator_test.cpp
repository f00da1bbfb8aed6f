// The map stage end to end on synthetic fields with known row ends (Emmi 2021 Fig. 2a).
#include "rownav/map/place_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "map/map_scene.hpp"

namespace rownav::map {
namespace {

using test::Waypoint;

// True place in a block of rows y = 0, 1, ..., lanes (x from 0 to 20): Emmi 2021 Fig. 1a.
Place true_place(const core::Pose2& T, int lanes) {
  if (T.x < 0.0 || T.x > 20.0) return Place::headland;
  if (T.y > 0.0 && T.y < lanes) return Place::lane;
  return Place::alley;
}

// Fraction of frames whose validated place is the true one, outside `band` [m] of x = 0, 20.
double accuracy(const std::vector<PlaceEstimate>& e, const std::vector<core::Pose2>& poses,
                int lanes, double band) {
  int n = 0, ok = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (std::abs(poses[i].x) < band || std::abs(poses[i].x - 20.0) < band) continue;
    ++n;
    ok += e[i].place == true_place(poses[i], lanes) ? 1 : 0;
  }
  return n ? static_cast<double>(ok) / n : 0.0;
}

TEST(PlaceEstimator, TwoLanesAndAUTurnGiveFourTransitionsAtTheRowEnds) {
  test::SynthScene s;
  s.rows = test::block(3, 1.0, 0.0, 20.0);
  const auto poses = test::path(
      {{-2.5, 0.5}, {22.0, 0.5}, {22.6, 1.0}, {22.0, 1.5}, {-2.5, 1.5}}, 0.05);
  PlaceEstimator est;
  const auto e = test::drive(est, s, poses, 21);
  const auto& tr = est.map().transitions();
  ASSERT_EQ(tr.size(), 4u);
  const std::array<Eigen::Vector2d, 4> truth{
      {{0.0, 0.5}, {20.0, 0.5}, {20.0, 1.5}, {0.0, 1.5}}};
  const std::array<Place, 4> to{Place::lane, Place::headland, Place::lane, Place::headland};
  // F_f is the first pose (-2.5, 0.5, 0): truth shifted into it.
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(tr[i].to, to[i]) << i;
    const Eigen::Vector2d p = tr[i].key.p + Eigen::Vector2d(-2.5, 0.5);
    EXPECT_NEAR(p.x(), truth[i].x(), 0.15) << i;
    EXPECT_NEAR(p.y(), truth[i].y(), 0.05) << i;
  }
  EXPECT_GE(accuracy(e, poses, 3, 0.5), 0.99);
}

TEST(PlaceEstimator, BackAndForthBeforeAndAfterTheEntryMakeOneTransition) {
  test::SynthScene s;
  s.rows = test::block(1, 1.0, 0.0, 20.0);
  const auto poses = test::path({{-3.0, 0.5},
                                 {-0.8, 0.5},
                                 {-2.5, 0.5, true},
                                 {-0.5, 0.5},
                                 {-2.0, 0.5, true},
                                 {2.0, 0.5},
                                 {1.0, 0.5, true},
                                 {2.5, 0.5},
                                 {1.5, 0.5, true},
                                 {8.0, 0.5}},
                                0.05);
  PlaceEstimator est;
  const auto e = test::drive(est, s, poses, 22);
  ASSERT_EQ(test::count_transitions(e), 1);
  EXPECT_EQ(est.map().transitions()[0].to, Place::lane);
  EXPECT_EQ(e.back().place, Place::lane);
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e[i].transition) {
      EXPECT_GT(poses[i].x, -0.3);
    }
}

TEST(PlaceEstimator, GapsInBothRowsAreNotARowEnd) {
  test::SynthScene s;
  s.rows = test::block(1, 1.0, 0.0, 20.0);
  for (auto& r : s.rows) r.gaps = {{8.0, 9.6}};
  const auto poses = test::path({{-2.5, 0.5}, {23.0, 0.5}}, 0.05);
  PlaceEstimator est;
  const auto e = test::drive(est, s, poses, 23);
  EXPECT_EQ(test::count_transitions(e), 2);
  EXPECT_GE(accuracy(e, poses, 1, 0.5), 0.99);
}

TEST(PlaceEstimator, AnAlleyBesideAnotherCropIsAnAlley) {
  test::SynthScene s;
  s.rows = test::block(2, 1.0, 0.0, 20.0);
  for (auto& r : test::block(2, 1.0, 0.0, 20.0, PointLabel::other_crop, 3.0)) s.rows.push_back(r);
  const auto poses = test::path({{-2.5, 2.5}, {23.0, 2.5}}, 0.05);
  PlaceEstimator est;
  const auto e = test::drive(est, s, poses, 24);
  ASSERT_EQ(test::count_transitions(e), 2);
  EXPECT_EQ(est.map().transitions()[0].to, Place::alley);
  for (const auto& x : e) EXPECT_NE(x.filtered, Place::lane);
  EXPECT_GE(accuracy(e, poses, 2, 0.5), 0.99);
}

TEST(PlaceEstimator, FramesWithoutLabelsInALaneKeepTheLane) {
  test::SynthScene s;
  s.rows = test::block(1, 1.0, 0.0, 20.0);
  PlaceEstimatorConfig cfg;
  cfg.initial_place = Place::lane;
  PlaceEstimator est(cfg);
  std::mt19937_64 rng(25);
  for (int k = 0; k < 200; ++k) {
    const core::Pose2 T(2.0 + 0.05 * k, 0.5, 0.0);
    auto f = test::scan(s, T, rng);
    if (k % 7 == 3) std::fill(f.labels.begin(), f.labels.end(), PointLabel::obstacle);
    const auto r = est.update(f.points, f.labels, T, 0.1 * k);
    EXPECT_EQ(r.place, Place::lane) << k;
    EXPECT_FALSE(r.transition);
  }
}

TEST(PlaceEstimator, BadInputIsReportedNotThrown) {
  PlaceEstimator est;
  const auto r = est.update({{1, 0, 0}}, {}, core::Pose2(), 0.0);
  EXPECT_EQ(r.status, EstimateStatus::invalid_input);
  const auto q = est.update({}, {}, core::Pose2(std::nan(""), 0.0, 0.0), 0.1);
  EXPECT_EQ(q.status, EstimateStatus::invalid_input);
  EXPECT_EQ(q.place, Place::headland);
}

}  // namespace
}  // namespace rownav::map
