#include "rownav/navigate/navigator.hpp"

#include <gtest/gtest.h>


namespace rownav::navigate {
namespace {

NavInput frame(double t, bool rows) {
  NavInput in;
  in.stamp = t;
  in.T_odom_base = core::Pose2(0.8 * t, 0.0, 0.0);
  if (rows) {
    in.observation.status = core::DetectionStatus::ok;
    in.observation.corridor = core::CorridorObservation{0.0, 0.0, 1.8};
  }
  in.tracking.status = rows ? track::TrackStatus::tracking : track::TrackStatus::lost;
  in.tracking.row_spacing = 1.8;
  return in;
}

struct Fixture {
  Navigator nav{NavigatorConfig{}, {0, 1}, TurnSide::left};
};

TEST(Navigator, PerceptionLostInARowForMoreThanTimeoutStops) {
  Fixture f;
  EXPECT_EQ(f.nav.step(frame(0.0, true)).state, NavState::in_row);
  EXPECT_EQ(f.nav.step(frame(0.3, false)).state, NavState::in_row);  // 0.3 s < 0.5 s
  const NavOutput out = f.nav.step(frame(0.7, false));
  EXPECT_EQ(out.state, NavState::safe_stop);
  EXPECT_EQ(out.stop_reason, StopReason::perception_lost);
  EXPECT_EQ(out.cmd.v, 0.0);
  ASSERT_FALSE(out.events.empty());
  EXPECT_EQ(out.events.back().kind, NavEventKind::safe_stop);
}

TEST(Navigator, ObstacleInsideStopDistanceStops) {
  Fixture f;
  std::vector<Eigen::Vector2f> pts(20, Eigen::Vector2f(0.7f, 0.0f));  // 0.25 m before the front
  NavInput in = frame(0.0, true);
  in.points_base = pts;
  const NavOutput out = f.nav.step(in);
  EXPECT_EQ(out.stop_reason, StopReason::obstacle);
}

TEST(Navigator, EndOfRowLeadsToExitingThenTurning) {
  Fixture f;
  NavInput in = frame(0.0, true);
  const NavOutput first = f.nav.step(in);
  ASSERT_TRUE(first.control.has_value());  // in a row: a request for the stack's controller
  EXPECT_GT(first.control->speed_ref, 0.0);
  in = frame(0.1, true);
  in.end_of_row.end_detected = true;
  in.end_of_row.distance_to_end = 1.0;
  EXPECT_EQ(f.nav.step(in).state, NavState::exiting);
  NavState s = NavState::exiting;
  for (double t = 0.2; t < 5.0 && s == NavState::exiting; t += 0.1)
    s = f.nav.step(frame(t, false)).state;
  EXPECT_EQ(s, NavState::turning);  // past the row end + exit distance (0.8 m/s)
}

}  // namespace
}  // namespace rownav::navigate
