// Row clusters from labelled points in F_l (Emmi 2021 sec. "Perception").
#include "rownav/map/labelled_clusters.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "map/map_scene.hpp"

namespace rownav::map {
namespace {

using test::SynthScene;

TEST(LabelledClusters, OneLinePerRowAcrossAGap) {
  SynthScene s;
  s.range = 6.0;
  s.rows = test::block(1, 1.0, 0.0, 8.0);
  s.rows[0].gaps = {{2.0, 3.5}};  // 1.5 m without plants in the right row
  std::mt19937_64 rng(3);
  LabelledClusters c;
  const core::Pose2 T(2.5, 0.5, 0.0);
  const auto f = test::scan(s, T, rng);
  c.add(f.points, f.labels, T);
  const auto& rows = c.update(T);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& r : rows) {
    EXPECT_LT(std::abs(r.line.direction.y()), 0.02);
    EXPECT_GT(r.arc_max - r.arc_min, 6.0);
  }
  const bool gap_row_merged = rows[0].merged == 2 || rows[1].merged == 2;
  EXPECT_TRUE(gap_row_merged);
}

TEST(LabelledClusters, OnlyCropPointsAndFinitePointsAreKept) {
  LabelledClusters c;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Eigen::Vector3f> pts{{1, 0, 0}, {2, 0, 0}, {nan, 0, 0}, {3, 0, 0}};
  const std::vector<PointLabel> labels{PointLabel::crop, PointLabel::other_crop, PointLabel::crop,
                                       PointLabel::weed};
  EXPECT_EQ(c.add(pts, labels, core::Pose2()), 1);
  EXPECT_EQ(c.stored_points(), 1u);
}

/// A 3 m lane (two rows 1 m apart) scanned once from T and stored.
LabelledClusters one_lane_seen_from(const core::Pose2& T) {
  SynthScene s;
  s.rows = test::block(1, 1.0, 0.0, 3.0);
  std::mt19937_64 rng(5);
  LabelledClusters c;
  const auto f = test::scan(s, T, rng);
  c.add(f.points, f.labels, T);
  return c;
}

TEST(LabelledClusters, PointsFarBehindAreForgotten) {
  const core::Pose2 T(1.5, 0.5, 0.0);
  LabelledClusters c = one_lane_seen_from(T);
  EXPECT_EQ(c.update(T).size(), 2u);
  EXPECT_TRUE(c.update(core::Pose2(10.0, 0.5, 0.0)).empty());  // 7 m past the rows
  EXPECT_EQ(c.stored_points(), 0u);
}

// Issue 12: row ends seen through a headland turn under odometry drift landed between the next
// corridor's rows; what the robot saw before it turned keep_turn_deg is forgotten.
TEST(LabelledClusters, PointsSeenBeforeTheRobotTurnedAreForgotten) {
  const core::Pose2 T(1.5, 0.5, 0.0);
  LabelledClusters c = one_lane_seen_from(T);
  const double deg = std::numbers::pi / 180.0, keep = c.config().keep_turn_deg;
  // Turned on the spot: within keep_turn_deg the rows stay, beyond it they are gone.
  EXPECT_EQ(c.update(core::Pose2(1.5, 0.5, (keep - 5.0) * deg)).size(), 2u);
  EXPECT_GT(c.stored_points(), 0u);
  EXPECT_TRUE(c.update(core::Pose2(1.5, 0.5, -(keep + 5.0) * deg)).empty());
  EXPECT_EQ(c.stored_points(), 0u);
}

TEST(LabelledClusters, InvalidConfigNamesTheField) {
  LabelledClustersConfig cfg;
  cfg.eps = 0.0;
  try {
    cfg.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("eps"), std::string::npos);
  }
  LabelledClustersConfig turn;
  turn.keep_turn_deg = -1.0;
  EXPECT_THROW(turn.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::map
