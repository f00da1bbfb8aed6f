#include "rownav/navigate/row_end_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "rownav/core/angle.hpp"

namespace rownav::navigate {
namespace {

/// A corridor of two rows +-half_spacing ending `end_x` ahead of the robot, seen at `stamp`.
track::RowTracking corridor(double end_x, double stamp, double spacing = 1.8, int support = 40) {
  track::RowTracking t;
  t.stamp = stamp;
  t.status = track::TrackStatus::tracking;
  t.row_spacing = spacing;
  t.centre_line_base = core::Line2({0.0, 0.0}, {1.0, 0.0});
  for (double y : {-spacing / 2.0, spacing / 2.0}) {
    track::TrackedRow r;
    r.line_base = core::Line2({0.0, y}, {1.0, 0.0});
    r.x_max = end_x;
    r.support = support;
    r.last_seen = stamp;
    t.rows.push_back(r);
  }
  t.right = 0, t.left = 1;
  return t;
}

TEST(RowEndEstimator, RowEndsInViewAreMappedIntoOdomAlongTheCentreLine) {
  RowEndEstimator e;
  const core::Pose2 T(10.0, 5.0, 0.0);
  e.update(corridor(4.0, 1.0), T, 1.0);
  ASSERT_TRUE(e.left_end() && e.right_end() && e.end_arc() && e.centre());
  EXPECT_TRUE(e.left_end()->isApprox(Eigen::Vector2d(14.0, 5.9)));
  EXPECT_TRUE(e.right_end()->isApprox(Eigen::Vector2d(14.0, 4.1)));
  EXPECT_NEAR(*e.end_arc() - e.centre()->arc(T.translation()), 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(e.spacing(), 1.8);
}

TEST(RowEndEstimator, RowsThatEndApartGiveTheFartherEndSoTheExitClearsBoth) {
  // One row's last tree is missing (or the row is shorter): its support ends a tree spacing
  // before the other row's. Either side, ahead of or behind the robot.
  for (const double short_end : {0.5, -3.5}) {
    for (const int short_row : {0, 1}) {
      RowEndEstimator e;
      auto t = corridor(4.0, 1.0);
      t.rows[static_cast<std::size_t>(short_row)].x_max = short_end;
      e.update(t, {}, 1.0);
      ASSERT_TRUE(e.end_arc() && e.left_end() && e.right_end());
      EXPECT_NEAR(*e.end_arc(), 4.0, 1e-9) << "short row " << short_row << " at " << short_end;
    }
  }
}

TEST(RowEndEstimator, ARowAcrossTheCorridorGivesNoEndOfIt) {
  // Past the row ends the tracker can hold clutter: a line across the headland ending where the
  // row would be, 6 m ahead. Its far end is no end of this corridor; the same far end on a row
  // along the corridor is.
  const RowEndEstimatorConfig c;
  for (const double angle_deg : {2.0 * c.row_angle_gate_deg, 0.5 * c.row_angle_gate_deg}) {
    auto t = corridor(2.0, 1.0);  // spacing 1.8, both rows end 2 m ahead
    auto& r = t.rows[1];          // the left row, replaced by the clutter line
    r.x_max = 6.0;
    const double a = core::deg2rad(angle_deg);
    r.line_base = core::Line2({0.0, 0.9 - 6.0 * std::tan(a)}, {std::cos(a), std::sin(a)});
    RowEndEstimator e;
    e.update(t, {}, 1.0);
    ASSERT_TRUE(e.end_arc());
    const bool across = angle_deg > c.row_angle_gate_deg;
    EXPECT_EQ(e.left_end().has_value(), !across) << angle_deg << " deg";
    EXPECT_NEAR(*e.end_arc(), across ? 2.0 : 6.0, 1e-9) << angle_deg << " deg";
  }
}

TEST(RowEndEstimator, AnAngleGateOutsideZeroToNinetyDegreesIsRejectedByName) {
  for (const double deg : {0.0, 120.0}) {
    RowEndEstimatorConfig c;
    c.row_angle_gate_deg = deg;
    try {
      c.validate();
      ADD_FAILURE() << deg << " deg accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("row_angle_gate_deg"), std::string::npos) << e.what();
    }
  }
  RowEndEstimatorConfig c;
  c.row_angle_gate_deg = 90.0;
  EXPECT_NO_THROW(c.validate());
}

TEST(RowEndEstimator, FarThinOrStaleRowsGiveNoEnd) {
  const RowEndEstimatorConfig c;
  RowEndEstimator far, thin, stale;
  far.update(corridor(c.max_range + 0.5, 1.0), {}, 1.0);  // the sensor's reach, not the end
  thin.update(corridor(4.0, 1.0, 1.8, c.min_support - 1), {}, 1.0);
  stale.update(corridor(4.0, 0.9), {}, 1.0);  // coasting: an older frame's extent
  for (const auto* e : {&far, &thin, &stale}) {
    EXPECT_FALSE(e->left_end() || e->right_end());
    EXPECT_FALSE(e->end_arc());
    EXPECT_TRUE(e->centre());  // the corridor itself is still known
  }
}

TEST(RowEndEstimator, TheMedianOfTheLatestFramesDropsAnOutlier) {
  RowEndEstimator e;
  for (int k = 0; k < 4; ++k) e.update(corridor(4.0, k), {}, k);
  e.update(corridor(6.5, 4.0), {}, 4.0);  // a weed on the row line stretches one frame
  EXPECT_NEAR(e.left_end()->x(), 4.0, 1e-9);
}

TEST(RowEndEstimator, SpacingIsARunningMeanKeptAcrossCorridors) {
  RowEndEstimator e;
  e.update(corridor(4.0, 0.0, 1.7), {}, 0.0);
  e.update(corridor(4.0, 1.0, 1.9), {}, 1.0);
  EXPECT_NEAR(e.spacing(), 1.8, 1e-12);
  e.reset();
  EXPECT_FALSE(e.centre() || e.end_arc() || e.left_end());
  EXPECT_NEAR(e.spacing(), 1.8, 1e-12);
  track::RowTracking lost = corridor(4.0, 2.0);
  lost.status = track::TrackStatus::lost;
  e.update(lost, {}, 2.0);
  EXPECT_FALSE(e.centre());  // only tracked frames count
}

TEST(RowEndEstimator, WithoutATrackerSpacingTheTwoEndsGiveIt) {
  RowEndEstimator e;
  e.update(corridor(4.0, 0.0, 0.0), {}, 0.0);  // a tracker that gives no spacing
  EXPECT_NEAR(e.spacing(), 0.0, 1e-12);        // rows at +-0: the ends coincide
  RowEndEstimator f;
  track::RowTracking t = corridor(4.0, 0.0, 2.0);
  t.row_spacing = 0.0;
  f.update(t, {}, 0.0);
  EXPECT_NEAR(f.spacing(), 2.0, 1e-9);
}

TEST(RowEndEstimator, AnEndStandingStillInOdomSettlesAnExtentMovingWithTheRobotDoesNot) {
  // Driving 0.1 m a frame: a real end stays at x = 8 m (odom); an extent cut by the sensor's
  // reach or an occluder stays 4 m ahead of the robot and never settles (issue 11).
  const RowEndEstimatorConfig c;
  RowEndEstimator fixed, moving;
  for (int k = 0; k <= 20; ++k) {
    const double x = 0.1 * k;
    const core::Pose2 T(x, 0.0, 0.0);
    fixed.update(corridor(8.0 - x, k), T, k);
    moving.update(corridor(4.0, k), T, k);
    if (x + 1e-9 < c.settle_distance) {
      EXPECT_FALSE(fixed.settled_end_ahead()) << "at x = " << x;
    }
    EXPECT_FALSE(moving.settled_end_ahead()) << "at x = " << x;
  }
  ASSERT_TRUE(fixed.settled_end_ahead());
  EXPECT_NEAR(*fixed.settled_end_ahead(), 6.0, 1e-9);
  fixed.reset();
  EXPECT_FALSE(fixed.settled_end_ahead());
}

}  // namespace
}  // namespace rownav::navigate
