// NavStack while held (an operator's pause, a mission not started, issue 15): the rows it keeps
// tracking tell when the robot was pushed or carried, and it says so once, while still held.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "common/planar_scan.hpp"
#include "common/synthetic_rows.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/navigate/nav_stack.hpp"

namespace rownav::navigate {
namespace {

/// The 2D stack a weeding robot runs: parallel_lines, model_filter, lookahead PID.
NavStack make_stack() {
  NavStackParts parts;
  parts.pipeline =
      std::make_unique<detect::DetectionPipeline>(io::make_pipeline("parallel_lines", ""));
  parts.tracker = io::make_tracker("model_filter", "");
  parts.controller = io::make_controller("lookahead_pid", "");
  return NavStack(NavStackConfig{}, std::move(parts), {0, 1}, TurnSide::left);
}

/// A standing robot (encoders fixed) in a 1.8 m corridor, `seconds` from `t0`: a scan every
/// 0.04 s of rows whose returns are drawn afresh each time (seeded), the robot displaced by
/// push(t) metres to the left (its odometry does not see it); a command every 0.01 s.
template <class Push>
std::vector<NavCommand> stand(NavStack& s, double t0, double seconds, Push push, bool rows = true) {
  std::vector<NavCommand> out;
  const int k0 = static_cast<int>(std::lround(t0 / 0.01));
  for (int k = k0 + 1; k <= k0 + static_cast<int>(std::lround(seconds / 0.01)); ++k) {
    const double t = 0.01 * k;
    if (k % 2 == 0) s.on_encoders({t, 0, 0, 0.0});
    if (k % 4 == 0) {
      test::SyntheticRows r;
      r.rows = 4;
      r.offset = -push(t);  // the rows move right as the robot moves left
      r.noise = 0.02;
      r.seed = static_cast<std::uint64_t>(k);
      s.on_scan(test::planar_scan(rows ? test::make_rows(r).points : std::vector<Eigen::Vector2f>{},
                                  t - 0.04));
    }
    out.push_back(s.command(t));
  }
  return out;
}

std::vector<NavEvent> moves(const std::vector<NavCommand>& cmds) {
  std::vector<NavEvent> out;
  for (const auto& c : cmds)
    for (const auto& e : c.events)
      if (e.kind == NavEventKind::moved_while_held) out.push_back(e);
  return out;
}

double max_lateral_change(const std::vector<NavCommand>& cmds) {
  double first = std::numeric_limits<double>::quiet_NaN(), worst = 0.0;
  for (const auto& c : cmds)
    if (c.frame && c.frame->tracking && c.frame->tracking->status == track::TrackStatus::tracking) {
      if (std::isnan(first)) first = c.frame->tracking->lateral_error;
      worst = std::max(worst, std::abs(c.frame->tracking->lateral_error - first));
    }
  return worst;
}

auto still = [](double) { return 0.0; };

TEST(NavStackHold, AHeldRobotThatStandsStillSendsNoMoveEvent) {
  NavStack s = make_stack();
  stand(s, 0.0, 1.0, still);
  s.set_held(true);
  const auto held = stand(s, 1.0, 10.0, still);
  const double noise = max_lateral_change(held);
  std::printf("standing, held 10 s: tracked offset moved at most %.3f m\n", noise);
  EXPECT_LT(noise, 0.5 * WatchdogConfig{}.held_move_lateral);
  EXPECT_TRUE(moves(held).empty());
}

TEST(NavStackHold, APushDuringAHoldIsReportedOnceWhileStillHeld) {
  NavStack s = make_stack();
  stand(s, 0.0, 1.0, still);
  s.set_held(true);
  // 1 s still, then pushed 0.4 m to the left over 2 s, then left there for 2 s.
  auto push = [](double t) { return std::clamp(0.2 * (t - 2.0), 0.0, 0.4); };
  const auto held = stand(s, 1.0, 5.0, push);
  const auto e = moves(held);
  ASSERT_EQ(e.size(), 1u);
  const double at = push(e[0].stamp);
  // At the limit, give or take the tracked offset's noise (AHeldRobotThatStandsStill...: 3 cm)
  // and the 0.8 cm the push moves between two scans.
  EXPECT_GT(at, WatchdogConfig{}.held_move_lateral - 0.05);
  EXPECT_LT(at, WatchdogConfig{}.held_move_lateral + 0.05);
  EXPECT_NE(e[0].text.find("sideways"), std::string::npos) << e[0].text;
  for (const auto& c : held) EXPECT_EQ(c.cmd.v, 0.0);
  // Released and held again: a new hold watches afresh (from where the robot stands now).
  s.set_held(false);
  s.set_held(true);
  EXPECT_TRUE(moves(stand(s, 6.0, 2.0, [](double) { return 0.4; })).empty());
  EXPECT_EQ(moves(stand(s, 8.0, 2.0, [](double t) { return 0.4 - 0.2 * (t - 8.0); })).size(), 1u);
}

TEST(NavStackHold, RowsLostDuringAHoldAreReported) {
  NavStack s = make_stack();
  stand(s, 0.0, 1.0, still);
  s.set_held(true);
  stand(s, 1.0, 1.0, still);
  const auto e = moves(stand(s, 2.0, 3.0, still, false));  // carried out of the rows
  ASSERT_EQ(e.size(), 1u);
  EXPECT_NE(e[0].text.find("lost"), std::string::npos) << e[0].text;
}

TEST(NavStackHold, AMoveWhileNotHeldIsNoHoldEvent) {
  NavStack s = make_stack();
  EXPECT_TRUE(moves(stand(s, 0.0, 4.0, [](double t) { return std::min(0.1 * t, 0.3); })).empty());
}

// The resume guard (issue 15): a pause in a row of a mission that has driven may only resume in
// the corridor it began in. A robot pushed over a row (a row crop's robot straddles it) ends the
// resume in a safe stop; a push inside the corridor, and any move while waiting for the start
// (the operator placing the robot), resume as before.

/// Pushed `distance` to the left over `seconds` (0.3 m/s or slower), from t = 2 s.
auto pushed(double distance, double seconds) {
  return [=](double t) { return std::clamp(distance * (t - 2.0) / seconds, 0.0, distance); };
}

bool drives(const std::vector<NavCommand>& cmds) {
  return std::any_of(cmds.begin(), cmds.end(), [](const NavCommand& c) { return c.cmd.v > 0.0; });
}

TEST(NavStackResume, APushInsideTheCorridorResumesAndSteersBack) {
  NavStack s = make_stack();
  ASSERT_TRUE(drives(stand(s, 0.0, 1.0, still)));
  s.set_held(true);
  const auto push = pushed(0.3, 2.0);  // a sixth of the 1.8 m spacing
  const auto held = stand(s, 1.0, 4.0, push);
  EXPECT_EQ(moves(held).size(), 1u);  // reported while held, as before
  EXPECT_FALSE(s.resume_blocker()) << *s.resume_blocker();
  s.set_held(false);
  const auto resumed = stand(s, 5.0, 1.0, [&](double t) { return push(t); });
  EXPECT_EQ(resumed.back().state, NavState::in_row);
  EXPECT_TRUE(drives(resumed));
}

TEST(NavStackResume, APushIntoTheNextCorridorEndsTheResumeInASafeStop) {
  NavStack s = make_stack();
  ASSERT_TRUE(drives(stand(s, 0.0, 1.0, still)));
  s.set_held(true);
  const auto push = pushed(1.8, 6.0);  // one spacing: the next corridor's centre
  stand(s, 1.0, 8.0, push);
  const auto why = s.resume_blocker();
  ASSERT_TRUE(why);
  std::printf("pushed one spacing while held: %s\n", why->c_str());
  s.set_held(false);
  const auto resumed = stand(s, 9.0, 0.5, push);
  EXPECT_EQ(resumed.front().state, NavState::safe_stop);
  EXPECT_EQ(resumed.front().stop_reason, StopReason::moved_while_held);
  EXPECT_FALSE(drives(resumed));
  // A new mission from where it stands (the operator has put it in a corridor) drives again.
  s.restart_mission();
  const auto again = stand(s, 9.5, 1.0, [](double) { return 0.0; });
  EXPECT_EQ(again.back().state, NavState::in_row);
  EXPECT_TRUE(drives(again));
}

TEST(NavStackResume, RowsLostDuringAPauseEndTheResumeInASafeStop) {
  NavStack s = make_stack();
  ASSERT_TRUE(drives(stand(s, 0.0, 1.0, still)));
  s.set_held(true);
  stand(s, 1.0, 1.0, still);
  // Carried off for 4 s: no rows, longer than the tracker coasts (TrackerConfig max_coast_time)
  stand(s, 2.0, 4.0, still, false);
  stand(s, 6.0, 1.0, still);  // and back where it was, as far as the rows tell
  ASSERT_TRUE(s.resume_blocker());
  EXPECT_NE(s.resume_blocker()->find("lost"), std::string::npos) << *s.resume_blocker();
  s.set_held(false);
  const auto resumed = stand(s, 7.0, 0.5, still);
  EXPECT_EQ(resumed.front().stop_reason, StopReason::moved_while_held);
  EXPECT_FALSE(drives(resumed));
}

TEST(NavStackResume, RowsLostBeforeTheMissionDroveAreTheOperatorPlacingTheRobot) {
  // The same carry as RowsLostDuringAPauseEndTheResumeInASafeStop, while waiting for the start.
  NavStack s = make_stack();
  s.set_held(true);
  stand(s, 0.0, 2.0, still);
  stand(s, 2.0, 4.0, still, false);
  stand(s, 6.0, 1.0, still);
  EXPECT_FALSE(s.resume_blocker()) << *s.resume_blocker();
  s.set_held(false);
  const auto started = stand(s, 7.0, 1.0, still);
  EXPECT_EQ(started.back().state, NavState::in_row);
  EXPECT_TRUE(drives(started));
}

}  // namespace
}  // namespace rownav::navigate
