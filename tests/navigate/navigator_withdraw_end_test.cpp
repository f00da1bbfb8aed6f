// A declared row end is withdrawn when the followed rows go on past it from beside the robot
// (issue 10: a gap between trees or a blind frame ended the rows; the exit then followed the rows
// on until its time budget ran out).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "corridor_frame.hpp"
#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate {
namespace {

constexpr double kSpeed = 0.8;  // [m/s] along odom x
constexpr double kStep = 0.1;   // [s] between LiDAR frames

// The robot at x = kSpeed t; rows at +-0.9 m, tracked from odom x `from` to `to`, with returns
// every 0.1 m along them from beside the robot to `to` (or, with `stub`, only in the last 0.2 m:
// a few returns of one ring); the end-of-row detector says `end`.
struct Frame {
  NavInput in;
  std::vector<Eigen::Vector2f> points;
};
Frame frame(double t, double from, double to, bool end, bool sweep_3d, bool stub = false) {
  Frame f{testing::corridor_frame(t, kSpeed * t, from, to, true), {}};
  const double x = kSpeed * t;
  for (double ox = stub ? to - 0.2 : std::max(from, x); ox <= to + 1e-9; ox += 0.1)
    for (const double y : {-0.9, 0.9}) f.points.emplace_back(float(ox - x), float(y));
  f.in.end_of_row.end_detected = end;
  f.in.sweep_3d = sweep_3d;
  return f;
}

struct Outcome {
  std::vector<NavState> states;
  bool withdrawn = false;
};

// 2 s in a row whose rows seem to end at x = 4 m (the detector declares the end at 1.5 s), then
// rows tracked from `from_after` to `to_after` (odom x) for 3 s more; 3D sweeps unless told.
Outcome run(double from_after, double to_after, NavigatorConfig config = {}, bool sweep_3d = true,
            bool stub = false, double duration = 5.0) {
  Navigator nav{config, {0, 1}, TurnSide::left};
  Outcome r;
  for (double t = 0.0; t < duration; t += kStep) {
    const bool before = t < 2.0;
    Frame f = frame(t, before ? -2.0 : from_after, before ? 4.0 : to_after, before && t >= 1.5,
                    sweep_3d, stub && !before);
    f.in.points_base = f.points;
    const NavOutput out = nav.step(f.in);
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

TEST(NavigatorWithdrawEnd, RowModelsStretchedByAFewFarReturnsLeaveTheEnd) {
  // The models reach 8 m, but only by returns in their last 0.2 m (one ring on a bump in an
  // uphill headland, zoo:1:11): nothing runs on from the declared end.
  const Outcome r = run(-2.0, 8.0, {}, true, true);
  EXPECT_FALSE(r.withdrawn);
  EXPECT_NE(r.states.back(), NavState::in_row);
}

// [m] odom x at which the robot left `exiting` (NaN: it never did).
double exit_left_at(const Outcome& r) {
  for (std::size_t k = 1; k < r.states.size(); ++k)
    if (r.states[k - 1] == NavState::exiting && r.states[k] != NavState::exiting)
      return kSpeed * kStep * double(k);
  return std::nan("");
}

TEST(NavigatorWithdrawEnd, AnEndStretchedByAFewFarReturnsMovesTheExitByTheReachAtMost) {
  // Declared at 4 m; the models then reach 12 m by returns in their last 0.2 m only. The exit
  // ends past 4 m + the reach (3 m, the end of row's extent_distance) + its exit distance, not
  // past 12 m (zoo:1:11: it followed them until its budget ran out).
  const Outcome r = run(-2.0, 12.0, {}, true, true, 16.0);
  EXPECT_FALSE(r.withdrawn);
  const double left = exit_left_at(r);
  ASSERT_TRUE(std::isfinite(left));
  EXPECT_GT(left, 4.0 + 3.0);
  EXPECT_LT(left, 12.0);
}

TEST(NavigatorWithdrawEnd, RowsThatRunOnPastTheEndKeepTheExitFollowingThem) {
  // The same end, but rows whose returns fill them on from 6 m, and no withdrawal (as when the
  // rows are not tracked beside the robot): the exit follows them as before, to 12 m and more
  // (a row crop's blind frames ended a row that goes on: the exit's budget stops it, it does
  // not turn into the crop).
  NavigatorConfig c;
  c.withdraw_end = false;
  const Outcome r = run(6.0, 12.0, c, true, false, 16.0);
  const double left = exit_left_at(r);
  EXPECT_TRUE(!std::isfinite(left) || left > 12.0) << left;
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
