// The operator's start / pause / stop of a mission (rownav_node's ~start, ~pause, ~stop), without
// ROS: phases, answers, the command gate and the state shown.
#include "rownav_ros/mission_control.hpp"

#include <gtest/gtest.h>

namespace rb = rownav::ros_bridge;
using rb::MissionPhase;
using rownav::navigate::NavState;

namespace {

const rownav::core::Twist2 kDrive{0.8, 0.01, -0.2};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void expect_zero(const rownav::core::Twist2& c) {
  EXPECT_EQ(c.v, 0.0);
  EXPECT_EQ(c.vy, 0.0);
  EXPECT_EQ(c.omega, 0.0);
}

}  // namespace

TEST(MissionControl, AutostartRunsAndPassesTheCommandThrough) {
  const rb::MissionControl m(true);
  EXPECT_TRUE(m.running());
  const auto c = m.gate(kDrive);
  EXPECT_EQ(c.v, kDrive.v);
  EXPECT_EQ(c.vy, kDrive.vy);
  EXPECT_EQ(c.omega, kDrive.omega);
  EXPECT_EQ(m.state(NavState::turning), "turning");
}

TEST(MissionControl, WaitsForStartWithoutAutostart) {
  rb::MissionControl m(false);
  EXPECT_EQ(m.phase(), MissionPhase::waiting);
  expect_zero(m.gate(kDrive));
  EXPECT_EQ(m.state(NavState::in_row), "waiting");
  const auto paused = m.pause(NavState::in_row);  // nothing runs: zero already
  EXPECT_TRUE(paused.success);
  EXPECT_TRUE(contains(paused.message, "not started")) << paused.message;
  EXPECT_EQ(m.phase(), MissionPhase::waiting);
  const auto a = m.start(NavState::in_row);
  EXPECT_TRUE(a.success);
  EXPECT_EQ(a.message, "mission started in in_row");
  EXPECT_TRUE(m.running());
}

TEST(MissionControl, PauseZeroesTheCommandAndStartResumes) {
  rb::MissionControl m(true);
  const auto p = m.pause(NavState::in_row);
  EXPECT_TRUE(p.success);
  EXPECT_EQ(p.message, "paused in in_row: command zero, ~start resumes");
  EXPECT_EQ(m.phase(), MissionPhase::paused);
  expect_zero(m.gate(kDrive));
  EXPECT_EQ(m.state(NavState::in_row), "paused");
  const auto again = m.pause(NavState::in_row);
  EXPECT_TRUE(again.success);
  EXPECT_TRUE(contains(again.message, "already paused")) << again.message;
  const auto r = m.start(NavState::in_row);
  EXPECT_TRUE(r.success);
  EXPECT_EQ(r.message, "resumed in in_row");
  EXPECT_EQ(m.gate(kDrive).v, kDrive.v);
  const auto twice = m.start(NavState::in_row);
  EXPECT_TRUE(twice.success);
  EXPECT_TRUE(contains(twice.message, "already running")) << twice.message;
}

TEST(MissionControl, APauseInAManoeuvreWarnsOfItsTimeBudget) {
  for (const NavState s :
       {NavState::exiting, NavState::turning, NavState::headland, NavState::entering}) {
    rb::MissionControl m(true);
    const auto p = m.pause(s);
    EXPECT_TRUE(p.success);
    EXPECT_TRUE(contains(p.message, "time budget")) << p.message;
  }
  rb::MissionControl m(true);
  EXPECT_FALSE(contains(m.pause(NavState::in_row).message, "budget"));
}

TEST(MissionControl, AStopHoldsUntilStartBeginsANewMission) {
  rb::MissionControl m(true);
  const auto s = m.stop(NavState::turning);
  EXPECT_TRUE(s.success);
  EXPECT_FALSE(s.new_mission);
  EXPECT_TRUE(contains(s.message, "mission stopped in turning")) << s.message;
  EXPECT_EQ(m.phase(), MissionPhase::stopped);
  expect_zero(m.gate(kDrive));
  EXPECT_EQ(m.state(NavState::turning), "stopped");
  EXPECT_EQ(m.state(NavState::safe_stop), "stopped");
  EXPECT_FALSE(m.pause(NavState::turning).success);
  EXPECT_TRUE(m.stop(NavState::turning).success);  // idempotent
  EXPECT_EQ(m.phase(), MissionPhase::stopped);
  expect_zero(m.gate(kDrive));
  const auto restart = m.start(NavState::turning);
  EXPECT_TRUE(restart.success);
  EXPECT_TRUE(restart.new_mission);  // not a resume of the stopped turn
  EXPECT_EQ(restart.message, "new mission started (the last one stopped in turning)");
  EXPECT_EQ(m.phase(), MissionPhase::running);
  EXPECT_EQ(m.gate(kDrive).v, kDrive.v);
}

TEST(MissionControl, AResumeOrAFirstStartIsNoNewMission) {
  rb::MissionControl waiting(false);
  EXPECT_FALSE(waiting.start(NavState::in_row).new_mission);
  rb::MissionControl m(true);
  EXPECT_FALSE(m.start(NavState::in_row).new_mission);  // already running
  EXPECT_TRUE(m.pause(NavState::turning).success);
  EXPECT_FALSE(m.start(NavState::turning).new_mission);
}

TEST(MissionControl, AMissionTheNavigatorEndedIsNotResumedButStartedAnew) {
  rb::MissionControl m(true);
  EXPECT_TRUE(m.pause(NavState::turning).success);
  // e.g. the stack's budget watchdog during a long pause in a turn
  EXPECT_EQ(m.state(NavState::safe_stop), "safe_stop");
  const auto a = m.start(NavState::safe_stop);
  EXPECT_TRUE(a.success);
  EXPECT_TRUE(a.new_mission);
  EXPECT_EQ(a.message, "new mission started (the last one safe_stop)");
  EXPECT_EQ(m.phase(), MissionPhase::running);
  rb::MissionControl done(true);
  EXPECT_EQ(done.state(NavState::done), "done");
  const auto d = done.start(NavState::done);
  EXPECT_TRUE(d.success);
  EXPECT_TRUE(d.new_mission);
}
