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

TEST(Navigator, ARowEndSeenBeforeTheRowsBeginIsForgottenNotFollowed) {
  // Started 1.5 m before the rows: the followed rows begin 1.5 m ahead (> arm_reach 1 m), and
  // the end-of-row box, seeing only their first plants, declares an end.
  Fixture f;
  auto with_rows = [](double t, double x_min) {
    NavInput in = frame(t, true);
    in.tracking.rows.resize(2);
    for (auto& r : in.tracking.rows) r.x_min = x_min, r.x_max = x_min + 2.0;
    in.tracking.right = 0, in.tracking.left = 1;
    return in;
  };
  NavInput in = with_rows(0.0, 1.5);
  in.end_of_row.end_detected = true;
  in.end_of_row.distance_to_end = 3.0;
  NavOutput out = f.nav.step(in);
  EXPECT_EQ(out.state, NavState::in_row);
  EXPECT_TRUE(out.reset_end_of_row);  // the detector starts again at the rows
  // At the rows (they begin 0.5 m ahead): the detector's fresh answer decides.
  out = f.nav.step(with_rows(0.5, 0.5));
  EXPECT_EQ(out.state, NavState::in_row);
  EXPECT_FALSE(out.reset_end_of_row);
  in = with_rows(0.6, 0.4);
  in.end_of_row.end_detected = true;
  in.end_of_row.distance_to_end = 1.0;
  EXPECT_EQ(f.nav.step(in).state, NavState::exiting);
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

namespace rownav::navigate {
namespace {

// The followed rows of `in` begin x_min ahead of the base (left at +0.9 m, right at -0.9 m).
void rows_from(NavInput& in, double x_min) {
  for (const double y : {-0.9, 0.9}) {
    track::TrackedRow r;
    r.line_base = core::Line2(Eigen::Vector2d(0.0, y), Eigen::Vector2d(1.0, 0.0));
    r.offset = y;
    r.x_min = x_min;
    r.x_max = x_min + 3.0;
    in.tracking.rows.push_back(r);
  }
  in.tracking.right = 0;
  in.tracking.left = 1;
}

TEST(Navigator, RowEndIsNotArmedBeforeTheRobotReachesTheRows) {
  // A mission starts in the headland: the empty ground before the row start reads as a row
  // end; the end counts only once a followed row begins within arm_reach (issue 11).
  Navigator nav{NavigatorConfig{}, {0, 1}, TurnSide::left};
  for (int k = 0; k < 5; ++k) {
    NavInput in = frame(0.1 * k, true);
    rows_from(in, 2.0 - 0.1 * k);  // rows begin 2.0 .. 1.6 m ahead (> arm_reach 1 m)
    in.end_of_row.end_detected = true;
    in.end_of_row.distance_to_end = 3.0;
    EXPECT_EQ(nav.step(in).state, NavState::in_row) << "frame " << k;
  }
  NavInput in = frame(0.5, true);
  rows_from(in, 0.8);  // at the rows
  in.end_of_row.end_detected = true;
  in.end_of_row.distance_to_end = 3.0;
  EXPECT_EQ(nav.step(in).state, NavState::exiting);
}

TEST(Navigator, ArmReachIsValidated) {
  NavigatorConfig c;
  c.arm_reach = -0.1;
  try {
    c.validate();
    FAIL() << "negative arm_reach accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("arm_reach"), std::string::npos);
  }
}

}  // namespace
}  // namespace rownav::navigate

namespace rownav::navigate {
namespace {

TEST(Navigator, PerceptionLostWithAnEmptyWindowSaysSo) {
  // A 2D scanner mounted above 0.3 m cabbages returns nothing: the stop says why, not only
  // "no rows" (issue 11: ruby + model_filter + fir_pid stopped at once, 3/3 seeds).
  Navigator nav{NavigatorConfig{}, {0}, TurnSide::left};
  nav.step(frame(0.0, true));
  const NavOutput out = nav.step(frame(0.7, false));  // points_base empty
  ASSERT_EQ(out.stop_reason, StopReason::perception_lost);
  ASSERT_FALSE(out.events.empty());
  EXPECT_NE(out.events.back().text.find("no points in the detection window"), std::string::npos)
      << out.events.back().text;
  Navigator seen{NavigatorConfig{}, {0}, TurnSide::left};
  seen.step(frame(0.0, true));
  std::vector<Eigen::Vector2f> pts = {{2.0f, 1.5f}};
  NavInput in = frame(0.7, false);
  in.points_base = pts;
  const NavOutput out2 = seen.step(in);
  ASSERT_FALSE(out2.events.empty());
  EXPECT_EQ(out2.events.back().text.find("no points"), std::string::npos);
}

}  // namespace
}  // namespace rownav::navigate

namespace rownav::navigate {
namespace {

// Tracked rows at +-spacing / 2 with canopy half width h (centre lines), robot 0.32 m wide.
NavInput lane_frame(double t, double spacing, double h) {
  NavInput in = frame(t, true);
  for (const double y : {-0.5 * spacing, 0.5 * spacing}) {
    track::TrackedRow r;
    r.line_base = core::Line2(Eigen::Vector2d(0.0, y), Eigen::Vector2d(1.0, 0.0));
    r.offset = r.centre_offset = y;
    r.half_width = h;
    r.x_min = -1.0, r.x_max = 4.0;
    in.tracking.rows.push_back(r);
  }
  in.tracking.right = 0, in.tracking.left = 1;
  in.robot.width = 0.32;
  return in;
}

int narrow_events(Navigator& nav, double spacing, double h, int frames) {
  int n = 0;
  for (int k = 0; k < frames; ++k)
    for (const auto& e : nav.step(lane_frame(0.1 * k, spacing, h)).events)
      n += e.kind == NavEventKind::narrow_corridor ? 1 : 0;
  return n;
}

TEST(Navigator, ALaneNarrowerThanTheRobotIsReportedOnce) {
  NavigatorConfig on;
  on.narrow_frames = 10;  // as config/navigate/row_crop.yaml
  // 0.6 m cabbage rows with 0.225 m canopy half widths leave 0.15 m for a 0.32 m robot.
  Navigator narrow{on, {0}, TurnSide::left};
  EXPECT_EQ(narrow_events(narrow, 0.6, 0.225, 30), 1);
  // 1.0 m beds leave 0.55 m (> 0.32 + 2 x 0.05): nothing to say; nor before narrow_frames.
  Navigator wide{on, {0}, TurnSide::left};
  EXPECT_EQ(narrow_events(wide, 1.0, 0.225, 30), 0);
  Navigator brief{on, {0}, TurnSide::left};
  EXPECT_EQ(narrow_events(brief, 0.6, 0.225, on.narrow_frames - 1), 0);
  // Off by default (vine and tree canopies overhang the robot).
  Navigator off{NavigatorConfig{}, {0}, TurnSide::left};
  EXPECT_EQ(narrow_events(off, 0.6, 0.225, 30), 0);
}

}  // namespace
}  // namespace rownav::navigate
