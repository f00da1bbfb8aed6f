// navigate::NavStack: raw stamped samples in, the command out; one code path for every adapter.
#include "rownav/navigate/nav_stack.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/nav_doubles.hpp"
#include "common/planar_scan.hpp"
#include "common/synthetic_rows.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/track/raw_corridor.hpp"

namespace rownav::navigate {
namespace {

/// Two corridors of rows 1.8 m apart, robot centred; optional obstacle points ahead.
std::vector<Eigen::Vector2f> corridor_points(std::uint64_t seed, double obstacle_x = -1.0) {
  test::SyntheticRows rows;
  rows.rows = 2;
  rows.seed = seed;
  auto pts = test::make_rows(rows).points;
  for (int i = 0; obstacle_x > 0.0 && i < 30; ++i)
    pts.emplace_back(static_cast<float>(obstacle_x), static_cast<float>(-0.15 + 0.01 * i));
  return pts;
}

NavStack make_stack(StackMode mode = StackMode::navigate) {
  NavStackConfig c;
  c.stack.mode = mode;
  NavStackParts parts;
  parts.pipeline =
      std::make_unique<detect::DetectionPipeline>(io::make_pipeline("parallel_lines", ""));
  if (mode != StackMode::detect) parts.tracker = std::make_unique<track::RawCorridorTracker>();
  // Stanley as shipped: its speed comes down with the front obstacle distance (003 sec. II-B).
  if (mode == StackMode::navigate) parts.controller = io::make_controller("stanley", "");
  return NavStack(c, std::move(parts), {0, 1}, TurnSide::left);
}

/// Drives 2 s: encoders of a robot moving at `v` (ticks of the default odometry) at 50 Hz, a
/// scan at 25 Hz, a command at 100 Hz. Returns every command.
std::vector<NavCommand> drive(NavStack& s, double v, bool encoders = true, double obstacle_x = -1) {
  const localize::WheelOdometryConfig w;
  const double ticks_per_m = w.ticks_per_rev / (2.0 * std::numbers::pi * w.wheel_radius);
  std::vector<NavCommand> out;
  for (int k = 1; k <= 200; ++k) {
    const double t = 0.01 * k;
    if (encoders && k % 2 == 0) {
      const auto ticks = static_cast<std::int64_t>(std::llround(v * t * ticks_per_m));
      s.on_encoders({t, ticks, ticks, 0.0});
    }
    if (k % 4 == 0)
      s.on_scan(
          test::planar_scan(corridor_points(static_cast<std::uint64_t>(k), obstacle_x), t - 0.04));
    out.push_back(s.command(t));
  }
  return out;
}

TEST(NavStack, TurnsRawSamplesIntoTrackedRowsAndACommand) {
  NavStack s = make_stack();
  const auto cmds = drive(s, 0.5);
  int frames = 0;
  for (const auto& c : cmds)
    if (c.frame) {
      ++frames;
      ASSERT_TRUE(c.frame->tracking.has_value()) << c.stamp;
      EXPECT_NE(c.frame->observation.status, core::DetectionStatus::no_rows) << c.stamp;
    }
  EXPECT_EQ(frames, 50);
  EXPECT_EQ(cmds.back().state, NavState::in_row);
  EXPECT_GT(cmds.back().cmd.v, 0.1);
  EXPECT_LT(std::abs(cmds.back().frame ? cmds.back().frame->tracking->lateral_error : 0.0), 0.1);
}

TEST(NavStack, ASecondCommandAtTheSameInstantKeepsTheAccelerationLimit) {
  NavStack s = make_stack();
  const localize::WheelOdometryConfig w;
  const double ticks_per_m = w.ticks_per_rev / (2.0 * std::numbers::pi * w.wheel_radius);
  const double max_accel = NavStackConfig{}.limits.max_accel;
  double last_v = 0.0, last_t = 0.0, top = 0.0;
  for (int k = 1; k <= 200; ++k) {
    const double t = 0.01 * k;
    if (k % 2 == 0) {
      const auto ticks = static_cast<std::int64_t>(std::llround(0.5 * t * ticks_per_m));
      s.on_encoders({t, ticks, ticks, 0.0});
    }
    if (k % 4 == 0)
      s.on_scan(test::planar_scan(corridor_points(static_cast<std::uint64_t>(k)), t - 0.04));
    // Twice per instant, as an adapter whose timer and frame callbacks share a stamp.
    const NavCommand first = s.command(t), second = s.command(t);
    EXPECT_EQ(second.cmd.v, first.cmd.v) << t;
    EXPECT_EQ(second.cmd.omega, first.cmd.omega) << t;
    EXPECT_LE(first.cmd.v - last_v, max_accel * (t - last_t) + 1e-12) << t;
    last_v = first.cmd.v, last_t = t, top = std::max(top, first.cmd.v);
  }
  EXPECT_GT(top, 0.5);  // it did drive, ramping up
}

TEST(NavStack, TheSameSamplesGiveBitIdenticalCommands) {
  NavStack a = make_stack(), b = make_stack();
  const auto ca = drive(a, 0.5), cb = drive(b, 0.5);
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t i = 0; i < ca.size(); ++i) {
    EXPECT_EQ(ca[i].cmd.v, cb[i].cmd.v) << i;
    EXPECT_EQ(ca[i].cmd.omega, cb[i].cmd.omega) << i;
  }
}

/// Whether NavStack levels a 3D sweep when the IMU measures gravity tilted by `tilt_deg` about
/// the base x axis (a roll), with StackConfig::max_level_tilt_deg at `max_deg`.
bool levels_sweep_at(double tilt_deg, double max_deg) {
  NavStackConfig c;
  c.stack.mode = StackMode::detect;
  c.stack.max_level_tilt_deg = max_deg;
  NavStackParts parts;
  parts.pipeline = std::make_unique<detect::DetectionPipeline>(io::make_pipeline("baseline", ""));
  NavStack s(c, std::move(parts));
  const double a = tilt_deg * std::numbers::pi / 180.0;
  for (int k = 0; k <= 20; ++k) {
    core::ImuSample imu;
    imu.stamp = 0.9 + 0.01 * k;
    imu.linear_acceleration = 9.81 * Eigen::Vector3d(0.0, std::sin(a), std::cos(a));
    s.on_imu(imu);
  }
  core::PointCloud cloud;
  cloud.stamp = 1.0;
  for (int i = 0; i < 50; ++i)
    cloud.points.push_back({2.0f + 0.1f * static_cast<float>(i), 0.9f, 0.5f, 0.0f, 0, 0, 0.0f});
  s.on_cloud(cloud);
  const NavCommand out = s.command(1.1);
  EXPECT_TRUE(out.frame.has_value());
  return out.frame && out.frame->levelled;
}

TEST(NavStack, LevelsASweepByGravityUpToTheConfiguredTilt) {
  EXPECT_TRUE(levels_sweep_at(5.0, 30.0));
  EXPECT_TRUE(levels_sweep_at(25.0, 30.0));
  EXPECT_FALSE(levels_sweep_at(35.0, 30.0));  // beyond the default: not trusted
  EXPECT_TRUE(levels_sweep_at(35.0, 40.0));   // the limit is the Config field's
}

TEST(NavStack, NeverCommandsMotionWithoutOdometry) {
  NavStack s = make_stack();
  for (const auto& c : drive(s, 0.5, false)) {
    EXPECT_EQ(c.cmd.v, 0.0) << c.stamp;
    EXPECT_EQ(c.cmd.omega, 0.0) << c.stamp;
    if (c.frame) {
      EXPECT_FALSE(c.frame->tracking.has_value());
    }
  }
}

TEST(NavStack, LateDuplicateAndNonFiniteSamplesAreDroppedAndCounted) {
  NavStack s = make_stack();
  drive(s, 0.5);
  const NavStackStats before = s.stats();
  s.on_encoders({1.0, 0, 0, 0.0});           // older than the newest
  s.on_encoders({std::nan(""), 0, 0, 0.0});  // not a time
  core::ImuSample imu;
  imu.stamp = 2.0;
  s.on_imu(imu);
  imu.stamp = 1.9;
  s.on_imu(imu);                                           // older than the newest
  s.on_scan(test::planar_scan(corridor_points(1), 1.0));   // older than the last frame
  s.on_scan(test::planar_scan(corridor_points(1), 1.96));  // the last frame again
  const NavCommand late = s.command(1.5);                  // older than the last command
  EXPECT_EQ(s.stats().dropped_encoders, before.dropped_encoders + 2);
  EXPECT_EQ(s.stats().dropped_imu, before.dropped_imu + 1);
  EXPECT_EQ(s.stats().imu, before.imu + 1);
  EXPECT_EQ(s.stats().dropped_frames, before.dropped_frames + 2);
  EXPECT_EQ(s.stats().late_commands, before.late_commands + 1);
  EXPECT_FALSE(late.frame.has_value());
  EXPECT_EQ(s.command(2.01).state, NavState::in_row);  // and the stack goes on
}

TEST(NavStack, AnObstacleAheadSlowsTheControllerThroughTheFrontRectangle) {
  NavStack clear = make_stack(), blocked = make_stack();
  const double front = NavStackConfig{}.robot.base_to_front;
  const auto c = drive(clear, 0.5), b = drive(blocked, 0.5, true, front + 1.0);
  EXPECT_EQ(b.back().state, NavState::in_row);  // 1 m ahead: slower, not a safe stop
  EXPECT_LT(b.back().cmd.v, 0.6 * c.back().cmd.v);
}

TEST(NavStack, DetectModeNeedsNoOdometryAndTrackModeNoController) {
  NavStack d = make_stack(StackMode::detect);
  int frames = 0;
  for (const auto& c : drive(d, 0.5, false))
    if (c.frame) {
      ++frames;
      EXPECT_EQ(c.frame->observation.status, core::DetectionStatus::ok);
      EXPECT_EQ(c.cmd.v, 0.0);
    }
  EXPECT_EQ(frames, 50);
  NavStack t = make_stack(StackMode::track);
  const auto cmds = drive(t, 0.5);
  EXPECT_EQ(cmds.back().cmd.v, 0.0);
  ASSERT_TRUE(cmds[199].frame && cmds[199].frame->tracking);
  EXPECT_EQ(cmds[199].frame->tracking->status, track::TrackStatus::tracking);
}

TEST(NavStack, AMissingPartIsAConstructionError) {
  NavStackParts parts;
  EXPECT_THROW(NavStack(NavStackConfig{}, std::move(parts)), std::invalid_argument);
  NavStackConfig bad;
  bad.stack.sweep_period = 0.0;
  NavStackParts p2;
  p2.pipeline =
      std::make_unique<detect::DetectionPipeline>(io::make_pipeline("parallel_lines", ""));
  p2.tracker = std::make_unique<track::RawCorridorTracker>();
  p2.controller = std::make_unique<test::ProportionalController>();
  EXPECT_THROW(NavStack(bad, std::move(p2)), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::navigate

namespace rownav::navigate {
namespace {

/// Drives `seconds` from `t0` with a scan every 0.04 s unless `scans` is false and encoders
/// every 0.02 s unless `encoders` is false (`frozen`: the ticks stop changing).
std::vector<NavCommand> drive_from(NavStack& s, double t0, double seconds, bool scans,
                                   bool encoders, bool frozen = false) {
  const localize::WheelOdometryConfig w;
  const double ticks_per_m = w.ticks_per_rev / (2.0 * std::numbers::pi * w.wheel_radius);
  std::vector<NavCommand> out;
  static double travelled = 0.0;  // the robot's true odometry distance
  if (t0 == 0.0) travelled = 0.0;
  const int steps = static_cast<int>(std::lround(seconds / 0.01));
  const int k0 = static_cast<int>(std::lround(t0 / 0.01));
  for (int k = k0 + 1; k <= k0 + steps; ++k) {
    const double t = 0.01 * k;
    if (!out.empty() && !frozen) travelled += out.back().cmd.v * 0.01;
    if (encoders && k % 2 == 0) {
      const auto ticks = static_cast<std::int64_t>(std::llround(travelled * ticks_per_m));
      s.on_encoders({t, ticks, ticks, 0.0});
    }
    if (scans && k % 4 == 0)
      s.on_scan(test::planar_scan(corridor_points(static_cast<std::uint64_t>(k)), t - 0.04));
    out.push_back(s.command(t));
  }
  return out;
}

bool has_event(const std::vector<NavCommand>& cmds, NavEventKind kind) {
  for (const auto& c : cmds)
    for (const auto& e : c.events)
      if (e.kind == kind) return true;
  return false;
}

TEST(NavStackWatchdog, ALidarBlackoutZeroesTheCommandWithinTheTimeoutAndMotionResumesAfter) {
  NavStack s = make_stack();
  const auto before = drive_from(s, 0.0, 2.0, true, true);
  ASSERT_GT(before.back().cmd.v, 0.1);
  const auto blind = drive_from(s, 2.0, 1.5, false, true);
  const WatchdogConfig w;
  for (const auto& c : blind) {
    if (c.stamp >
        2.0 + w.lidar_timeout + 0.01) {  // the last scan (1.96 s, 25 Hz) was complete at 2.0 s
      EXPECT_EQ(c.cmd.v, 0.0) << c.stamp;
      EXPECT_EQ(c.health, InputHealth::lidar_stale) << c.stamp;
    }
  }
  EXPECT_TRUE(has_event(blind, NavEventKind::input_stale));
  EXPECT_EQ(blind.back().state, NavState::in_row);  // held, not ended
  const auto after = drive_from(s, 3.5, 1.0, true, true);
  EXPECT_TRUE(has_event(after, NavEventKind::input_resumed));
  EXPECT_GT(after.back().cmd.v, 0.1);
  EXPECT_EQ(after.back().health, InputHealth::ok);
}

TEST(NavStackWatchdog, StaleOdometryZeroesTheCommand) {
  NavStack s = make_stack();
  drive_from(s, 0.0, 2.0, true, true);
  const auto no_odom = drive_from(s, 2.0, 0.5, true, false);
  EXPECT_EQ(no_odom.back().cmd.v, 0.0);
  EXPECT_EQ(no_odom.back().health, InputHealth::odometry_stale);
}

TEST(NavStackWatchdog, FrozenEncodersWhileDrivingAreASafeStop) {
  NavStack s = make_stack();
  drive_from(s, 0.0, 2.0, true, true);
  const auto frozen = drive_from(s, 2.0, 3.0, true, true, true);
  EXPECT_EQ(frozen.back().state, NavState::safe_stop);
  EXPECT_EQ(frozen.back().stop_reason, StopReason::odometry_implausible);
  EXPECT_EQ(frozen.back().cmd.v, 0.0);
}

TEST(NavStack, ARestartedMissionDrivesAgainFromWhereTheRobotStoodInTheSameOdomFrame) {
  NavStack s = make_stack();
  drive_from(s, 0.0, 2.0, true, true);
  const auto frozen = drive_from(s, 2.0, 3.0, true, true, true);
  ASSERT_EQ(frozen.back().state, NavState::safe_stop);
  const auto T_before = s.T_odom_base(5.0);
  ASSERT_TRUE(T_before);
  ASSERT_GT(T_before->x, 0.2);  // it had driven before the encoders froze
  // Still stopped: time alone does not restart it.
  EXPECT_EQ(drive_from(s, 5.0, 0.5, true, true).back().state, NavState::safe_stop);
  s.restart_mission();
  EXPECT_EQ(s.navigator().state(), NavState::in_row);
  EXPECT_EQ(s.navigator().stop_reason(), StopReason::none);
  const auto T_after = s.T_odom_base(5.5);
  ASSERT_TRUE(T_after);
  EXPECT_DOUBLE_EQ(T_after->x, T_before->x);  // localisation kept: no jump of the odom frame
  EXPECT_DOUBLE_EQ(T_after->y, T_before->y);
  const auto again = drive_from(s, 5.5, 2.0, true, true);
  EXPECT_EQ(again.back().state, NavState::in_row);
  EXPECT_EQ(again.back().corridor, 0);  // the plan's first corridor
  EXPECT_EQ(again.back().served, 0);
  EXPECT_GT(again.back().cmd.v, 0.1);
  EXPECT_FALSE(has_event(again, NavEventKind::safe_stop));  // a fresh plausibility window
  const auto T_end = s.T_odom_base(7.5);
  ASSERT_TRUE(T_end);
  EXPECT_GT(T_end->x, T_before->x + 0.2);  // driven on from there
}

TEST(NavStack, ARestartWithAnotherPlanServesThatPlanAndAnEmptyOneIsRefused) {
  NavStack s = make_stack();
  drive_from(s, 0.0, 1.0, true, true);
  EXPECT_THROW(s.restart_mission({}, TurnSide::left), std::invalid_argument);
  EXPECT_EQ(s.navigator().order(), (std::vector<int>{0, 1}));  // refused: nothing changed
  s.restart_mission({3, 4}, TurnSide::right);
  EXPECT_EQ(s.navigator().order(), (std::vector<int>{3, 4}));
  const auto again = drive_from(s, 1.0, 1.0, true, true);
  EXPECT_EQ(again.back().state, NavState::in_row);
  EXPECT_EQ(again.back().corridor, 3);  // the new plan's first corridor
  s.restart_mission();                  // a plain restart keeps the last plan
  EXPECT_EQ(s.navigator().order(), (std::vector<int>{3, 4}));
}

TEST(NavStack, AHeldStackTracksEveryFrameSendsExactZeroAndRampsUpWhenReleased) {
  // An operator's pause (issue 15): perception goes on, the command is zero, and a robot that
  // stands while held is no broken odometry.
  NavStack s = make_stack();
  ASSERT_GT(drive_from(s, 0.0, 2.0, true, true).back().cmd.v, 0.1);
  s.set_held(true);
  const auto held = drive_from(s, 2.0, 5.0, true, true);  // longer than the plausibility window
  int frames = 0;
  for (const auto& c : held) {
    EXPECT_EQ(c.cmd.v, 0.0) << c.stamp;
    EXPECT_EQ(c.cmd.omega, 0.0) << c.stamp;
    EXPECT_EQ(c.health, InputHealth::ok) << c.stamp;
    if (!c.frame) continue;
    ++frames;
    ASSERT_TRUE(c.frame->tracking) << c.stamp;
    EXPECT_EQ(c.frame->tracking->status, track::TrackStatus::tracking) << c.stamp;
  }
  EXPECT_EQ(frames, 125);  // every scan of 5 s at 25 Hz
  EXPECT_EQ(held.back().state, NavState::in_row);
  EXPECT_FALSE(has_event(held, NavEventKind::safe_stop));
  EXPECT_FALSE(has_event(held, NavEventKind::input_stale));
  s.set_held(false);
  const auto released = drive_from(s, 7.0, 2.0, true, true);
  const double max_accel = NavStackConfig{}.limits.max_accel;
  EXPECT_LE(released.front().cmd.v, max_accel * 0.01 + 1e-12);  // from zero, not a jump
  EXPECT_GT(released.back().cmd.v, 0.1);
  EXPECT_EQ(released.back().state, NavState::in_row);
}

TEST(NavStackWatchdog, AHeldStackStillReportsALidarThatStops) {
  NavStack s = make_stack();
  drive_from(s, 0.0, 1.0, true, true);
  s.set_held(true);
  const auto blind = drive_from(s, 1.0, 1.5, false, true);
  EXPECT_EQ(blind.back().health, InputHealth::lidar_stale);
  EXPECT_TRUE(has_event(blind, NavEventKind::input_stale));
}

TEST(NavStackWatchdog, AStateMayTakeItsBudgetButNotMore) {
  const WatchdogConfig w;
  const StateEffort exit{4.0, 5.0};  // 4 m at 0.8 m/s
  EXPECT_FALSE(budget_exceeded(exit, 5.0, 4.0, w));
  EXPECT_FALSE(budget_exceeded(exit, w.budget_factor * 5.0 + w.budget_time_margin, 4.0, w));
  EXPECT_TRUE(budget_exceeded(exit, w.budget_factor * 5.0 + w.budget_time_margin + 0.1, 4.0, w));
  EXPECT_TRUE(
      budget_exceeded(exit, 5.0, w.budget_factor * 4.0 + w.budget_distance_margin + 0.1, w));
}

}  // namespace
}  // namespace rownav::navigate
