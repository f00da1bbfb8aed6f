// A declared row end is withdrawn when the followed rows go on past it from beside the robot
// (issue 10: a gap between trees or a blind frame ended the rows; the exit then followed the rows
// on until its time budget ran out).
#include <gtest/gtest.h>

#include <algorithm>

#include "corridor_frame.hpp"
#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate {
namespace {

constexpr double kSpeed = 0.8;  // [m/s] along odom x
constexpr double kStep = 0.1;   // [s] between LiDAR frames

// The robot at x = kSpeed t; rows at +-0.9 m, tracked from odom x `from` to `to`; the end-of-row
// detector says `end`.
NavInput frame(double t, double from, double to, bool end, bool sweep_3d) {
  NavInput in = testing::corridor_frame(t, kSpeed * t, from, to, true);
  in.end_of_row.end_detected = end;
  in.sweep_3d = sweep_3d;
  return in;
}

struct Outcome {
  std::vector<NavState> states;
  bool withdrawn = false;
};

// 2 s in a row whose rows seem to end at x = 4 m (the detector declares the end at 1.5 s), then
// rows tracked from `from_after` to `to_after` (odom x) for 3 s more; 3D sweeps unless told.
Outcome run(double from_after, double to_after, NavigatorConfig config = {}, bool sweep_3d = true) {
  Navigator nav{config, {0, 1}, TurnSide::left};
  Outcome r;
  for (double t = 0.0; t < 5.0; t += kStep) {
    const bool before = t < 2.0;
    const NavOutput out = nav.step(frame(t, before ? -2.0 : from_after, before ? 4.0 : to_after,
                                         before && t >= 1.5, sweep_3d));
    r.states.push_back(out.state);
    r.withdrawn = r.withdrawn || std::any_of(out.events.begin(), out.events.end(), [](auto& e) {
                    return e.kind == NavEventKind::row_end_withdrawn;
                  });
  }
  return r;
}

TEST(NavigatorWithdrawEnd, RowsThatGoOnFromBesideTheRobotWithdrawTheEndAndTheRobotStaysInTheRow) {
  // A gap: the rows reappear, tracked from behind the robot to 8 m (4 m past the declared end).
  const Outcome r = run(-2.0, 8.0);
  EXPECT_TRUE(r.withdrawn);
  EXPECT_NE(std::find(r.states.begin(), r.states.end(), NavState::exiting), r.states.end());
  EXPECT_EQ(r.states.back(), NavState::in_row);
}

TEST(NavigatorWithdrawEnd, RowsAheadThatDoNotRunBesideTheRobotLeaveTheEnd) {
  // A next block's rows beyond the headland: they start 2 m past the end, ahead of the robot.
  const Outcome r = run(6.0, 8.0);
  EXPECT_FALSE(r.withdrawn);
  EXPECT_NE(r.states.back(), NavState::in_row);
}

TEST(NavigatorWithdrawEnd, AnEndThatHoldsIsNotWithdrawn) {
  const Outcome r = run(-2.0, 4.0);
  EXPECT_FALSE(r.withdrawn);
  EXPECT_NE(r.states.back(), NavState::in_row);
}

TEST(NavigatorWithdrawEnd, APlanarScanKeepsItsEnd) {
  // What stands in a scan plane beyond a row end runs the rows on (zoo:7:5): planar scans keep
  // the exit they declared.
  const Outcome r = run(-2.0, 8.0, {}, false);
  EXPECT_FALSE(r.withdrawn);
  EXPECT_NE(r.states.back(), NavState::in_row);
}

TEST(NavigatorWithdrawEnd, OffTheExitFollowsTheRowsOnAsBefore) {
  NavigatorConfig c;
  c.withdraw_end = false;
  const Outcome r = run(-2.0, 8.0, c);
  EXPECT_FALSE(r.withdrawn);
  EXPECT_EQ(r.states.back(), NavState::exiting);
}

TEST(NavigatorWithdrawEnd, ReachIsValidated) {
  NavigatorConfig c;
  c.end_withdraw_reach = -1.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::navigate
