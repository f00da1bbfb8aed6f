// The node's processing class on synthetic messages: simulated OS1-16 sweeps of a small
// vineyard as PointCloud2 plus nav_msgs/Odometry, no ROS master.
#include "rownav_ros/row_nav_core.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "row_nav_scene.hpp"

using namespace row_nav_test;

namespace {

/// Five frames of 0.1 s from `t` (advanced past them); the last one's result.
rb::FrameResult steps(rb::RowNavCore& core, Sweeps& sweeps, const Scene& scene, double& t) {
  rb::FrameResult r;
  for (int k = 0; k < 5; ++k, t += 0.1) r = step(core, sweeps, scene.pose, t);
  return r;
}

/// A robot at the centre of corridor 2, driven for 0.5 s (`driven`: the last frame's result),
/// and the scene `offset` m to its left where a pause will carry it (`after`).
struct Carry {
  explicit Carry(double offset) : before(0.0, 0.0), after(offset, 0.0) {
    core.set_mount(sweeps_before.mount());
    driven = steps(core, sweeps_before, before, t);
  }
  Scene before, after;
  rb::RowNavCore core{vineyard_setup()};
  Sweeps sweeps_before{before}, sweeps_after{after};
  double t = 100.0;
  rb::FrameResult driven;
};

}  // namespace

TEST(RowNavCore, DrivesForwardAndSeesTheOffset) {
  const Scene scene(0.3, 0.1);  // left of the centre, heading left
  rb::RowNavCore core(vineyard_setup());
  const rb::FrameResult r = drive(scene, core, 8);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.state, rownav::navigate::NavState::in_row);
  EXPECT_EQ(r.tracking.status, rownav::track::TrackStatus::tracking);
  EXPECT_GT(r.tracking.lateral_error, 0.15);
  EXPECT_LT(r.tracking.lateral_error, 0.45);
  EXPECT_GT(r.tracking.heading_error, 0.0);
  EXPECT_GT(r.cmd.v, 0.05);     // forward, ramped up by the acceleration limit
  EXPECT_LT(r.cmd.omega, 0.0);  // steers back to the right
  EXPECT_FALSE(core.last_points().empty());
}

TEST(RowNavCore, MirroredOffsetMirrorsTheSign) {
  const Scene scene(-0.3, 0.0);
  rb::RowNavCore core(vineyard_setup());
  const rb::FrameResult r = drive(scene, core, 5);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_LT(r.tracking.lateral_error, -0.15);
}

TEST(RowNavCore, StopsWithoutMountOrOdometry) {
  rb::RowNavCore core(vineyard_setup());
  rownav::core::PointCloud empty;
  empty.stamp = 10.0;
  auto r = core.on_cloud(rb::to_cloud_msg(empty));
  EXPECT_FALSE(r.ok);  // no mount
  EXPECT_EQ(r.cmd.v, 0.0);
  core.set_mount(Eigen::Isometry3d::Identity());
  r = core.on_cloud(rb::to_cloud_msg(empty));
  EXPECT_FALSE(r.ok);  // no odometry
  EXPECT_NE(r.error.find("odometry"), std::string::npos);
  core.on_odom(odom_msg(5.0, {}));
  r = core.on_cloud(rb::to_cloud_msg(empty));
  EXPECT_FALSE(r.ok);  // odometry too old for the frame
  sensor_msgs::PointCloud2 broken;
  broken.header.stamp.fromSec(5.0);
  broken.width = broken.height = 1;
  r = core.on_cloud(broken);  // no x/y/z fields: caught, not thrown
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.cmd.v, 0.0);
}

TEST(RowNavCore, BadNamesFailAtStartUp) {
  rb::NodeConfig n;
  n.detector = "no_such_detector";
  EXPECT_ANY_THROW(rb::RowNavCore(rb::load_stack(n)));
  n = {};
  n.input = "radar";
  EXPECT_THROW(rb::load_stack(n), std::invalid_argument);
}

TEST(OdomBuffer, InterpolatesAndExtrapolates) {
  rb::OdomBuffer b(1.0, 0.2);
  EXPECT_FALSE(b.at(0.0));
  EXPECT_TRUE(b.push({1.0, Pose2(0, 0, 0), {1.0, 0.0, 0.0}}));
  EXPECT_TRUE(b.push({2.0, Pose2(1, 0, 0.2), {1.0, 0.0, 0.0}}));
  EXPECT_FALSE(b.push({1.5, Pose2(), {}}));  // older than the newest
  const auto mid = b.at(1.5);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->x, 0.5, 1e-12);
  EXPECT_NEAR(mid->theta, 0.1, 1e-12);
  const auto ahead = b.at(2.1);
  ASSERT_TRUE(ahead);
  EXPECT_NEAR(ahead->x, 1.0 + 0.1 * std::cos(0.2), 1e-12);
  EXPECT_FALSE(b.at(2.5));  // beyond max_extrapolation
  EXPECT_FALSE(b.at(0.5));  // before the history
  b.push({4.0, Pose2(2, 0, 0), {}});
  EXPECT_FALSE(b.at(1.5));  // trimmed (history 1 s)
}

TEST(RowNavCore, TheWatchdogTickStopsTheRobotWhenMessagesStop) {
  const Scene scene(0.0, 0.0);
  rb::RowNavCore core(vineyard_setup());
  EXPECT_EQ(core.tick(50.0).cmd.v, 0.0);            // before any frame: stand still
  const rb::FrameResult r = drive(scene, core, 8);  // frames and odometry up to t = 100.75
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_GT(r.cmd.v, 0.0);
  const rb::TickResult fresh = core.tick(100.76);
  EXPECT_EQ(fresh.health, rownav::navigate::InputHealth::ok);
  const rb::TickResult stale = core.tick(101.5);  // no message for 0.75 s
  EXPECT_NE(stale.health, rownav::navigate::InputHealth::ok);
  EXPECT_EQ(stale.cmd.v, 0.0);
  EXPECT_EQ(stale.cmd.omega, 0.0);
  bool said = false;
  for (const auto& e : stale.events) said |= e.kind == rownav::navigate::NavEventKind::input_stale;
  EXPECT_TRUE(said);
}

TEST(RowNavCore, APausedMissionSendsZeroAndResumesWithoutASafeStop) {
  const Scene scene(0.0, 0.0);
  rb::RowNavCore core(vineyard_setup());
  Sweeps sweeps(scene);
  core.set_mount(sweeps.mount());
  double t = 100.0;
  rb::FrameResult r;
  r = steps(core, sweeps, scene, t);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_GT(r.cmd.v, 0.0);
  EXPECT_TRUE(core.pause().success);
  EXPECT_EQ(core.state_name(core.navigator().state()), "paused");
  // 5 s paused, the robot standing: odometry at 20 Hz, watchdog ticks, sweeps at 10 Hz.
  sensor_msgs::PointCloud2 cloud = sweeps.at(t);
  for (int k = 0; k < 100; ++k, t += 0.05) {
    if (const auto c = core.on_odom(odom_msg(t, scene.pose))) expect_zero(*c);
    const rb::TickResult tick = core.tick(t + 0.01);
    expect_zero(tick.cmd);
    for (const auto& e : tick.events)
      EXPECT_NE(e.kind, rownav::navigate::NavEventKind::input_stale);
    if (k % 2 != 0) continue;
    cloud.header.stamp.fromSec(t);
    const rb::FrameResult held = core.on_cloud(cloud);
    EXPECT_TRUE(held.ok) << held.error;  // tracked while paused
    for (const auto& e : held.events)    // standing still: nothing to report
      EXPECT_NE(e.kind, rownav::navigate::NavEventKind::moved_while_held) << e.text;
    EXPECT_TRUE(held.held);
    EXPECT_EQ(held.tracking.status, rownav::track::TrackStatus::tracking);
    expect_zero(held.cmd);
  }
  // A stack that commanded motion while the robot is held still would have ended in a safe stop
  // (odometry_implausible, HeldStillWhileTheStackCommandsMotionEndsInASafeStop).
  EXPECT_EQ(core.navigator().state(), rownav::navigate::NavState::in_row);
  const rb::MissionAnswer a = core.start();
  EXPECT_TRUE(a.success);
  EXPECT_EQ(a.message, "resumed in in_row");
  r = steps(core, sweeps, scene, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.state, rownav::navigate::NavState::in_row);
  EXPECT_EQ(core.state_name(r.state), "in_row");
  EXPECT_GT(r.cmd.v, 0.05);
}

TEST(RowNavCore, APauseKeepsTrackingSoTheResumeStartsFromWhereTheRowsAreNow) {
  // The robot is carried 0.15 m to the left during a pause, its odometry seeing nothing of it
  // (lifted, or pushed with the wheels locked): the rows seen while paused place it, so the
  // first command after the resume already steers back (issue 15: a pause no longer holds
  // frames back from the tracker).
  const double carried = 0.15;
  Carry c(carried);
  auto& [before, after, core, sweeps_before, sweeps_after, t, r] = c;
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_NEAR(r.tracking.lateral_error, 0.0, 0.05);
  ASSERT_TRUE(core.pause().success);
  int told = 0;  // moved_while_held events: the carry is reported while paused, once
  for (int k = 0; k < 20; ++k, t += 0.1) {
    core.on_odom(odom_msg(t, before.pose));  // the odometry does not see the carry
    core.on_odom(odom_msg(t + 0.05, before.pose));
    r = core.on_cloud(sweeps_after.at(t));
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_TRUE(r.held);
    expect_zero(r.cmd);
    for (const auto& e : r.events)
      told += e.kind == rownav::navigate::NavEventKind::moved_while_held;
  }
  EXPECT_NEAR(r.tracking.lateral_error, carried, 0.05);  // tracked while paused
  EXPECT_EQ(told, 1);
  ASSERT_TRUE(core.start().success);
  core.on_odom(odom_msg(t, before.pose));
  core.on_odom(odom_msg(t + 0.05, before.pose));
  r = core.on_cloud(sweeps_after.at(t));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_FALSE(r.held);
  EXPECT_NEAR(r.tracking.lateral_error, carried, 0.05);
  // The frame's command goes out with the next odometry message (the frame came at the
  // instant of the last one: NavStack::limit keeps the first command of an instant).
  const auto cmd = core.on_odom(odom_msg(t + 0.1, before.pose));
  ASSERT_TRUE(cmd);
  EXPECT_LT(cmd->omega, 0.0);  // left of the centre line: steers right at once
}

TEST(RowNavCore, AStartAfterThePausedRobotWasCarriedOutOfItsRowsIsRefused) {
  // Carried 15 m to the left (out of the 6-row vineyard) for 4 s, longer than the tracker
  // coasts, then back: the rows cannot tell which corridor it was put back in, so ~start does
  // not resume; ~stop and ~start begin a new mission from where it stands (issue 15).
  Carry c(15.0);
  auto& [before, away, core, sweeps_before, sweeps_away, t, r] = c;
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_GT(r.cmd.v, 0.0);
  ASSERT_TRUE(core.pause().success);
  for (int k = 0; k < 40; ++k, t += 0.1) step(core, sweeps_away, before.pose, t);
  r = steps(core, sweeps_before, before, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.tracking.status, rownav::track::TrackStatus::tracking);
  const rb::MissionAnswer refused = core.start();
  EXPECT_FALSE(refused.success);
  EXPECT_NE(refused.message.find("not resumed"), std::string::npos) << refused.message;
  EXPECT_EQ(core.state_name(core.navigator().state()), "paused");
  r = steps(core, sweeps_before, before, t);
  expect_zero(r.cmd);
  ASSERT_TRUE(core.stop().success);
  const rb::MissionAnswer started = core.start();
  EXPECT_TRUE(started.success) << started.message;
  EXPECT_TRUE(started.new_mission);
  r = steps(core, sweeps_before, before, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.state, rownav::navigate::NavState::in_row);
  EXPECT_GT(r.cmd.v, 0.0);
}

namespace {

// Frames every 0.1 s from `t` with the robot held at the scene's pose, at most 40 of them, until
// the stack's watchdog safe-stops it (a robot that does not move while commanded to); `t` ends
// after the last frame sent.
rb::FrameResult hold_still_until_safe_stop(rb::RowNavCore& core, Sweeps& sweeps, const Scene& scene,
                                           double& t) {
  rb::FrameResult r;
  for (int k = 0; k < 40 && r.state != rownav::navigate::NavState::safe_stop; ++k, t += 0.1)
    r = step(core, sweeps, scene.pose, t);
  return r;
}

}  // namespace

TEST(RowNavCore, HeldStillWhileTheStackCommandsMotionEndsInASafeStop) {
  // Why a pause holds frames back: the stack's own watchdog takes a robot that does not move
  // while commanded to for a broken odometry.
  const Scene scene(0.0, 0.0);
  rb::RowNavCore core(vineyard_setup());
  Sweeps sweeps(scene);
  core.set_mount(sweeps.mount());
  double t = 100.0;
  const rb::FrameResult r = hold_still_until_safe_stop(core, sweeps, scene, t);
  EXPECT_EQ(r.state, rownav::navigate::NavState::safe_stop);
  EXPECT_EQ(r.stop_reason, rownav::navigate::StopReason::odometry_implausible);
}

TEST(RowNavCore, WaitsForStartAndAfterAStopStartBeginsANewMission) {
  const Scene scene(0.0, 0.0);
  rb::StackSetup setup = vineyard_setup();
  setup.node.autostart = false;
  rb::RowNavCore core(setup);
  Sweeps sweeps(scene);
  core.set_mount(sweeps.mount());
  EXPECT_EQ(core.state_name(core.navigator().state()), "waiting");
  double t = 100.0;
  rb::FrameResult r;
  for (int k = 0; k < 3; ++k, t += 0.1) {
    r = step(core, sweeps, scene.pose, t);
    EXPECT_TRUE(r.ok) << r.error;  // tracked before the start
    EXPECT_TRUE(r.held);
    expect_zero(r.cmd);
  }
  expect_zero(core.tick(t).cmd);
  EXPECT_EQ(core.start().message, "mission started in in_row");
  r = steps(core, sweeps, scene, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_GT(r.cmd.v, 0.05);
  EXPECT_TRUE(core.stop().success);
  EXPECT_EQ(core.state_name(core.navigator().state()), "stopped");
  const auto after = core.on_odom(odom_msg(t, scene.pose));
  ASSERT_TRUE(after);
  expect_zero(*after);
  r = core.on_cloud(sweeps.at(t));
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.held);
  expect_zero(r.cmd);
  expect_zero(core.tick(t + 0.01).cmd);
  const auto T_stopped = core.stack().T_odom_base(t);
  const rb::MissionAnswer again = core.start();
  EXPECT_TRUE(again.success);
  EXPECT_TRUE(again.new_mission);
  r = steps(core, sweeps, scene, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.state, rownav::navigate::NavState::in_row);
  EXPECT_EQ(core.state_name(r.state), "in_row");
  EXPECT_GT(r.cmd.v, 0.05);
  // The same odom frame: the robot's own odometry goes on (REP 105).
  ASSERT_TRUE(T_stopped);
  EXPECT_NEAR(core.stack().T_odom_base(t - 0.1)->x, T_stopped->x, 1e-9);
}

TEST(RowNavCore, AfterASafeStopStartBeginsANewMissionThatDrives) {
  const Scene scene(0.0, 0.0);
  rb::RowNavCore core(vineyard_setup());
  Sweeps sweeps(scene);
  core.set_mount(sweeps.mount());
  double t = 100.0;
  rb::FrameResult r = hold_still_until_safe_stop(core, sweeps, scene, t);
  ASSERT_EQ(r.state, rownav::navigate::NavState::safe_stop);  // held still while commanded
  expect_zero(r.cmd);
  const rb::MissionAnswer a = core.start();
  EXPECT_TRUE(a.success);
  EXPECT_EQ(a.message, "new mission started (the last one safe_stop)");
  EXPECT_EQ(core.navigator().state(), rownav::navigate::NavState::in_row);
  r = steps(core, sweeps, scene, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.state, rownav::navigate::NavState::in_row);
  EXPECT_GT(r.cmd.v, 0.05);
}

TEST(RowNavCore, ANewMissionReadsTheMissionFileAfreshAndABadOneStartsNothing) {
  // Issue 15: after a stop, the operator names another plan (the field's corridors 2-4) and
  // starts it where the robot stands, without restarting the node.
  const std::string dir = ::testing::TempDir();
  const std::string good = dir + "/rownav_restart_mission.yaml",
                    bad = dir + "/rownav_restart_mission_bad.yaml";
  std::ofstream(good) << "first_turn: right\nstart_corridor: 2\n";
  std::ofstream(bad) << "start_corridor: 7\n";  // beyond the block's 5 corridors
  const Scene scene(0.0, 0.0);
  rb::RowNavCore core(vineyard_setup());
  Sweeps sweeps(scene);
  core.set_mount(sweeps.mount());
  double t = 100.0;
  rb::FrameResult r;
  r = steps(core, sweeps, scene, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(core.navigator().order(), std::vector<int>{0});
  rb::NodeConfig node = core.setup().node;
  node.corridor_count = 5;
  node.mission = good;
  // Running: a start is no new mission, the plan stays.
  EXPECT_EQ(core.start(node).message, "already running (in_row)");
  EXPECT_EQ(core.navigator().order(), std::vector<int>{0});
  ASSERT_TRUE(core.stop().success);
  node.mission = bad;
  const rb::MissionAnswer refused = core.start(node);
  EXPECT_FALSE(refused.success);
  EXPECT_EQ(refused.message.rfind("no new mission: ", 0), 0u) << refused.message;
  EXPECT_NE(refused.message.find("start_corridor"), std::string::npos) << refused.message;
  EXPECT_EQ(refused.message.find('\n'), std::string::npos);
  EXPECT_EQ(core.state_name(core.navigator().state()), "stopped");
  node.mission = good;
  const rb::MissionAnswer a = core.start(node);
  EXPECT_TRUE(a.success);
  EXPECT_TRUE(a.new_mission);
  EXPECT_EQ(a.message,
            "new mission started (the last one stopped in in_row), 3 corridors from corridor 2");
  EXPECT_EQ(core.navigator().order(), (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(core.setup().mission.first_turn, rownav::navigate::TurnSide::right);
  r = steps(core, sweeps, scene, t);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.state, rownav::navigate::NavState::in_row);
  EXPECT_GT(r.cmd.v, 0.05);
  // The new plan is the node's now: a later plain restart keeps it.
  ASSERT_TRUE(core.stop().success);
  EXPECT_TRUE(core.start().new_mission);
  EXPECT_EQ(core.navigator().order(), (std::vector<int>{2, 3, 4}));
}

TEST(RowNavCore, NavSatFixesReachTheStackRejectedOnesAsOutages) {
  rb::RowNavCore core(vineyard_setup());
  sensor_msgs::NavSatFix f;
  f.header.stamp.fromSec(10.0);
  f.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  f.latitude = 51.597, f.longitude = -0.977, f.altitude = 80.0;
  EXPECT_TRUE(core.on_fix(f).fix.valid);
  f.header.stamp.fromSec(10.2);
  f.status.status = sensor_msgs::NavSatStatus::STATUS_NO_FIX;
  const rb::NavSatConversion none = core.on_fix(f);
  EXPECT_FALSE(none.fix.valid);
  EXPECT_FALSE(none.rejected.empty());
  EXPECT_EQ(core.stack().stats().gnss, 2u);  // both stamped samples accepted by the stack
  f.header.stamp.fromSec(9.0);               // older than the newest: dropped by the stack
  f.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  core.on_fix(f);
  EXPECT_EQ(core.stack().stats().dropped_gnss, 1u);
}
