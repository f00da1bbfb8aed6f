// Rows lost in a row: a safe stop, unless the rows ran out just before the end they were seen to
// have (issue 11: PEARL on a 2D scan loses rows shorter than ~3.5 m before the end of row fires).
#include <gtest/gtest.h>

#include <vector>

#include "corridor_frame.hpp"
#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate {
namespace {

constexpr double kSpeed = 0.8;  // [m/s] along odom x
constexpr double kEnd = 6.0;    // [m] odom x where the rows end

// The robot at x = kSpeed t, rows at +-0.9 m from x = 0 to kEnd (odom), seen when `rows`; the
// tracker keeps the followed rows while it coasts.
NavInput frame(double t, bool rows) {
  return testing::corridor_frame(t, kSpeed * t, 0.0, kEnd, rows);
}

// Drives with rows seen until the rows end 3.5 m ahead, then without; the state at `t_end`.
NavOutput lose_rows(const std::vector<Eigen::Vector2f>& points, bool box_seen,
                    double lost_from = (kEnd - 3.5) / kSpeed, double t_end = 4.0) {
  Navigator nav{NavigatorConfig{}, {0, 1}, TurnSide::left};
  NavOutput out;
  for (double t = 0.0; t <= t_end && out.state != NavState::safe_stop; t += 0.04) {
    NavInput in = frame(t, t < lost_from);
    in.points_base = points;
    in.end_of_row.box_seen = box_seen;
    out = nav.step(in);
    if (out.state != NavState::in_row) break;
  }
  return out;
}

TEST(NavigatorLostRows, RowsLostJustBeforeTheirSettledEndLeaveTheRow) {
  const NavOutput out = lose_rows({}, true);
  EXPECT_EQ(out.state, NavState::exiting);
  ASSERT_FALSE(out.events.empty());
  EXPECT_EQ(out.events.front().kind, NavEventKind::row_end);
}

TEST(NavigatorLostRows, ARowThatGoesOnPastThatEndIsALossOfPerception) {
  // Seen from the robot 2.5 m before the end: one row's face goes on for 2 m past it.
  std::vector<Eigen::Vector2f> row;
  for (double x = 4.0; x < 6.0; x += 0.15) row.emplace_back(float(x), 0.9f);
  EXPECT_EQ(lose_rows(row, true).stop_reason, StopReason::perception_lost);
}

TEST(NavigatorLostRows, AHiddenLaneIsALossOfPerception) {
  EXPECT_EQ(lose_rows({}, false).stop_reason, StopReason::perception_lost);
}

TEST(NavigatorLostRows, RowsLostFarBeforeTheirEndAreALossOfPerception) {
  // Lost 5.5 m before the end (beyond lost_rows_end_reach 5 m).
  EXPECT_EQ(lose_rows({}, true, 0.5 / kSpeed).stop_reason, StopReason::perception_lost);
}

// Rows seen for 1 s, then `blind_for` seconds of 3D sweeps without rows, with the end-of-row
// detector saying (`blind`) that the rays passed over the rows' band; the rows go on for 30 m.
NavOutput blind_sweeps(bool blind, track::TrackStatus status, double blind_for = 0.9) {
  Navigator nav{NavigatorConfig{}, {0, 1}, TurnSide::left};
  NavOutput out;
  for (double t = 0.0; t <= 1.0 + blind_for && out.state == NavState::in_row; t += 0.1) {
    const bool rows = t < 1.0;
    NavInput in = testing::corridor_frame(t, kSpeed * t, 0.0, 30.0, rows);
    in.sweep_3d = true;
    if (!rows) in.end_of_row.blind = blind, in.end_of_row.box_seen = !blind;
    if (!rows) in.tracking.status = status;
    out = nav.step(in);
  }
  return out;
}

TEST(NavigatorLostRows, SweepsOverTheRowsWhileTheTrackerCoastsAreNoLossOfPerception) {
  // A small robot pitched up on a bump: 0.9 s (> perception_timeout 0.5 s) of blind sweeps.
  const NavOutput out = blind_sweeps(true, track::TrackStatus::coasting);
  EXPECT_EQ(out.state, NavState::in_row);
  EXPECT_TRUE(out.control.has_value());
}

TEST(NavigatorLostRows, SweepsThatSawTheBandEmptyAreALossOfPerception) {
  EXPECT_EQ(blind_sweeps(false, track::TrackStatus::coasting).stop_reason,
            StopReason::perception_lost);
}

TEST(NavigatorLostRows, BlindSweepsAfterTheTrackerGaveUpAreALossOfPerception) {
  EXPECT_EQ(blind_sweeps(true, track::TrackStatus::lost).stop_reason, StopReason::perception_lost);
}

TEST(NavigatorLostRows, ReachIsValidated) {
  NavigatorConfig c;
  c.lost_rows_end_reach = -1.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::navigate
