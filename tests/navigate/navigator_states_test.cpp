// The navigator's states and transitions, driven by a small kinematic world: corridors 1.8 m
// apart (centre y = k * 1.8), rows from x = 0 to x = 10, the robot's pose integrated from the
// commands (odom = world). The perception answers are made from that world exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "rownav/core/angle.hpp"
#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate {
namespace {

constexpr double kSpacing = 1.8, kRowsEnd = 10.0, kDt = 0.01;

/// What the perception would report at pose T; `wrong` shifts the corridor seen by that many.
NavInput perceive(const core::Pose2& T, double t, int wrong, bool blind) {
  NavInput in;
  in.stamp = t;
  in.T_odom_base = T;
  in.observation.stamp = t;
  const bool along = std::abs(std::sin(T.theta)) < 0.5;
  const bool forward = std::cos(T.theta) > 0.0;
  if (blind || !along || T.x < -0.5 || T.x > kRowsEnd) return in;  // headland: no rows
  const int k = static_cast<int>(std::lround(T.y / kSpacing)) + wrong;
  const Eigen::Vector2d dir(forward ? 1.0 : -1.0, 0.0);
  const core::Pose2 Ti = T.inverse();
  in.tracking.status = track::TrackStatus::tracking;
  in.tracking.row_spacing = kSpacing;
  in.tracking.centre_line_base = core::Line2({0.0, k * kSpacing}, dir).transformed(Ti);
  in.tracking.lateral_error = -in.tracking.centre_line_base.y_at(0.0);
  in.tracking.heading_error = -in.tracking.centre_line_base.heading();
  const double ahead = forward ? kRowsEnd - T.x : T.x;  // to the end the robot drives towards
  for (double side : {-0.5, 0.5}) {
    track::TrackedRow r;
    r.line_base = core::Line2({0.0, k * kSpacing + side * kSpacing}, dir).transformed(Ti);
    r.x_max = ahead, r.support = 50, r.last_seen = t;
    in.tracking.rows.push_back(r);
  }
  in.tracking.right = forward ? 0 : 1, in.tracking.left = forward ? 1 : 0;
  in.observation.status = core::DetectionStatus::ok;
  in.observation.corridor = core::CorridorObservation{0.0, 0.0, kSpacing};
  // Lan 2021's box 3-5 m ahead empties 3 m before the row ends.
  in.end_of_row.end_detected = ahead < 3.0;
  in.end_of_row.distance_to_end = ahead;
  return in;
}

struct Drive {
  std::vector<NavState> states;  // each state once, in the order entered
  std::vector<NavEventKind> events;
  std::string stop_message;  // the safe_stop event's text
  NavOutput last;
  core::Pose2 T;  // where the robot ended
  bool reset_on_turn = false;
  double max_entry_offset = 0.0;  // [m] farthest from corridor 1's centre while entering
};

/// The map stage's validated place at a pose (NavInput::place); empty: the stage is off.
using PlaceMap = std::function<std::optional<map::Place>(const core::Pose2&)>;

/// The tracker's centre line turned by `angle` about its point nearest the robot: the same
/// offset at the robot, another heading (a tracker still settling after a rotation).
void skew_centre(NavInput& in, double angle) {
  core::Line2& c = in.tracking.centre_line_base;
  c = core::Line2(c.project(Eigen::Vector2d::Zero()), Eigen::Rotation2Dd(angle) * c.direction);
}

/// 10 Hz frames, 100 Hz control, for up to 120 s; `wrong` / `blind_entry` alter what is seen
/// while entering, `entry_skew` [rad] the tracked centre line's heading in its first 2 s seen;
/// `place` is the map stage's answer; `things`: obstacle points (odom = world).
Drive drive(int wrong_entry = 0, bool blind_entry = false, const PlaceMap& place = {},
            const NavigatorConfig& config = {}, const std::vector<Eigen::Vector2d>& things = {},
            double entry_skew = 0.0) {
  Navigator nav(config, {0, 1}, TurnSide::left);
  core::Pose2 T(0.0, 0.0, 0.0);
  core::Twist2 cmd;
  Drive run;
  int skewed = 0;  // tracked frames skewed so far
  for (int i = 1; i <= 12000; ++i) {
    const double t = i * kDt;
    const bool entering = nav.state() == NavState::entering;
    if (entering) run.max_entry_offset = std::max(run.max_entry_offset, std::abs(T.y - kSpacing));
    NavOutput out;
    if (i % 10 == 0) {
      NavInput in = perceive(T, t, entering ? wrong_entry : 0, entering && blind_entry);
      if (entering && skewed < 20 && in.tracking.status == track::TrackStatus::tracking)
        skew_centre(in, entry_skew), ++skewed;
      if (place) in.place = place(T);
      std::vector<Eigen::Vector2f> seen;
      for (const auto& p : things) seen.push_back((T.inverse() * p).cast<float>());
      in.obstacle_points_base = std::span<const Eigen::Vector2f>(seen);
      out = nav.step(in);
      if (out.control)  // the stack's controller: steer onto the corridor centre
        out.cmd = {out.control->speed_ref, 0.0,
                   -1.5 * out.control->lateral_error - 1.5 * out.control->heading_error};
    } else {
      out = nav.hold(t, T, cmd);
    }
    run.reset_on_turn |= out.reset_tracking;
    cmd = out.cmd;
    T = T * core::Pose2(cmd.v * kDt, 0.0, cmd.omega * kDt);
    if (run.states.empty() || run.states.back() != out.state) run.states.push_back(out.state);
    for (const auto& e : out.events) {
      run.events.push_back(e.kind);
      if (e.kind == NavEventKind::safe_stop) run.stop_message = e.text;
    }
    run.last = out;
    run.T = T;
    if (out.state == NavState::done || out.state == NavState::safe_stop) break;
  }
  return run;
}

/// A map that validates the lane `entry_lag` metres into it and the headland `exit_lag` metres
/// past its end, both ways along the rows (x from 0 to kRowsEnd); `in_lane` replaces the lane.
PlaceMap lagging_map(double entry_lag, double exit_lag = 0.3,
                     map::Place in_lane = map::Place::lane) {
  return [=](const core::Pose2& T) {
    const bool forward = std::cos(T.theta) > 0.0;
    const bool lane = forward ? T.x > entry_lag && T.x < kRowsEnd + exit_lag
                              : T.x > -exit_lag && T.x < kRowsEnd - entry_lag;
    return lane ? in_lane : map::Place::headland;
  };
}

bool contains_in_order(const std::vector<NavState>& seq, const std::vector<NavState>& want) {
  std::size_t j = 0;
  for (NavState s : seq)
    if (j < want.size() && s == want[j]) ++j;
  return j == want.size();
}

TEST(NavigatorStates, ServesTwoCorridorsThroughEveryStateOfAnInPlaceTurn) {
  const Drive r = drive();
  EXPECT_EQ(r.last.state, NavState::done);
  EXPECT_EQ(r.last.stop_reason, StopReason::done);
  EXPECT_EQ(r.last.served, 2);
  EXPECT_TRUE(
      contains_in_order(r.states, {NavState::in_row, NavState::exiting, NavState::turning,
                                   NavState::headland, NavState::turning, NavState::entering,
                                   NavState::in_row, NavState::exiting, NavState::done}));
  EXPECT_TRUE(r.reset_on_turn);  // the stack is asked to reset its tracker on the turn
  for (NavEventKind k :
       {NavEventKind::row_end, NavEventKind::exit_done, NavEventKind::turn_started,
        NavEventKind::turn_finished, NavEventKind::entered_corridor, NavEventKind::mission_done})
    EXPECT_NE(std::find(r.events.begin(), r.events.end(), k), r.events.end()) << core::enum_name(k);
}

/// A 4 x 3 cluster of points (2 cm apart) around `c`: a branch, a row end's canopy.
std::vector<Eigen::Vector2d> cluster(const Eigen::Vector2d& c) {
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) out.push_back(c + Eigen::Vector2d(0.02 * i, 0.02 * j));
  return out;
}

TEST(NavigatorStates, ARotationInPlaceStopsForWhatItsFootprintSweepsNotForTheBoxAhead) {
  // The turn rotates in place about (kRowsEnd + exit_distance, 0) from heading 0 to 90 deg.
  // Something 0.85 m away at 45 deg crosses the stop box ahead of the front (0.45-0.95 m) but
  // not the circle the 0.9 x 0.6 m footprint sweeps (0.54 m + 0.1 m clearance): the rotation is
  // safe (issue 10: row ends beside the turn stopped it). Something 0.5 m away is in that circle.
  const NavigatorConfig c;
  const Eigen::Vector2d pivot(kRowsEnd + c.exit_distance, 0.0);
  const Eigen::Vector2d diagonal = Eigen::Vector2d(1.0, 1.0).normalized();
  const Drive clear = drive(0, false, {}, c, cluster(pivot + 0.85 * diagonal));
  EXPECT_EQ(clear.last.state, NavState::done) << clear.stop_message;
  const Drive swept = drive(0, false, {}, c, cluster(pivot + 0.5 * diagonal));
  EXPECT_EQ(swept.last.state, NavState::safe_stop);
  EXPECT_EQ(swept.last.stop_reason, StopReason::obstacle);
  EXPECT_NE(swept.stop_message.find("rotating footprint"), std::string::npos) << swept.stop_message;
  EXPECT_NE(swept.stop_message.find("(turning)"), std::string::npos) << swept.stop_message;
  // The circle is the footprint's plus the clearance: a larger clearance reaches it.
  NavigatorConfig wide = c;
  wide.rotation_clearance = 0.5;
  EXPECT_EQ(drive(0, false, {}, wide, cluster(pivot + 0.85 * diagonal)).last.state,
            NavState::safe_stop);
}

TEST(NavigatorStates, EnteringTheWrongCorridorIsASafeStopThatSaysSo) {
  for (int wrong : {1, -1}) {
    const Drive r = drive(wrong);
    EXPECT_EQ(r.last.state, NavState::safe_stop) << wrong;
    EXPECT_EQ(r.last.stop_reason, StopReason::place_contradicts_plan) << wrong;
    EXPECT_EQ(r.last.served, 1);
    EXPECT_EQ(r.last.cmd.v, 0.0);
  }
}

TEST(NavigatorStates, AnEntrySteersOnlyOnATrackedCorridorThatRunsAlongThePlannedOne) {
  // Issue 10 (zoo:1:36): after the rotation the tracker gave a centre line 22-30 deg across the
  // rows through the robot; its offset at the robot passed the entry gate and the entry steered
  // along it into a row end. A line that far off the entry heading is no corridor.
  const NavigatorConfig c;
  const double skew = core::deg2rad(25.0);
  const Drive straight = drive(0, false, {}, c);
  for (double s : {skew, -skew}) {
    const Drive gated = drive(0, false, {}, c, {}, s);
    EXPECT_EQ(gated.last.state, NavState::done) << gated.stop_message;
    EXPECT_LT(gated.max_entry_offset, straight.max_entry_offset + 0.02) << s;
    // Without the heading gate (90 deg: any line) the same entry swerves off the corridor.
    NavigatorConfig open = c;
    open.entry_heading_gate_deg = 90.0;
    EXPECT_GT(drive(0, false, {}, open, {}, s).max_entry_offset, 0.15) << s;
  }
}

TEST(NavigatorStates, EnteringWithoutSeeingACorridorStopsAtTheMaximumDepth) {
  const Drive r = drive(0, true);
  EXPECT_EQ(r.last.state, NavState::safe_stop);
  EXPECT_EQ(r.last.stop_reason, StopReason::perception_lost);
  EXPECT_EQ(r.states.back(), NavState::safe_stop);
  EXPECT_EQ(r.states[r.states.size() - 2], NavState::entering);
}

// Something small in front (a weed: the controllers' front rectangle slows them to a halt from
// 3 points, the stop box needs obstacle_min_points) holding the robot still in a row.
TEST(NavigatorStates, AnObstacleThatHoldsTheRobotInARowEndsInASafeStopAfterTheTimeout) {
  NavigatorConfig c;
  Navigator nav(c, {0}, TurnSide::left);
  const core::Pose2 T(2.0, 0.0, 0.0);
  NavOutput out;
  double t = 0.1;
  for (; t < 2.0 * c.blocked_timeout && out.state != NavState::safe_stop; t += 0.1) {
    NavInput in = perceive(T, t, 0, false);
    in.obstacle_distance = 0.3;  // the robot does not move: in.twist is zero
    out = nav.step(in);
    if (t < c.blocked_timeout - 0.05) {
      ASSERT_EQ(out.state, NavState::in_row) << t;
    }
  }
  EXPECT_EQ(out.state, NavState::safe_stop);
  EXPECT_EQ(out.stop_reason, StopReason::obstacle);
  EXPECT_NEAR(t, c.blocked_timeout + 0.2, 0.15);
  // Moving, or with the rectangle clear, the same time passes without a stop.
  for (const bool moving : {true, false}) {
    Navigator n2(c, {0}, TurnSide::left);
    NavOutput o;
    for (double u = 0.1; u < 2.0 * c.blocked_timeout; u += 0.1) {
      NavInput in = perceive(T, u, 0, false);
      in.twist.v = moving ? 0.3 : 0.0;
      if (moving) in.obstacle_distance = 1.5;  // slowed down, not held
      o = n2.step(in);
    }
    EXPECT_EQ(o.state, NavState::in_row) << moving;
  }
}

// Issue 12: the map stage's place gates the exit and the entry (navigate/place_gate.hpp).
NavigatorConfig gated() {
  NavigatorConfig c;
  c.place_gate.enabled = true;
  return c;
}

TEST(NavigatorPlaceGate, AMapThatAgreesLateLetsTheMissionThroughAsWithoutIt) {
  const Drive plain = drive();
  // 2.5 m into the lane: past the tracker's entry check (1.5 m), within entry_max_depth (6 m).
  for (const double lag : {0.3, 2.5}) {
    const Drive r = drive(0, false, lagging_map(lag), gated());
    EXPECT_EQ(r.last.state, NavState::done) << lag << " " << r.stop_message;
    EXPECT_EQ(r.last.served, 2) << lag;
    EXPECT_EQ(r.states, plain.states) << lag;
  }
}

TEST(NavigatorPlaceGate, AMapThatStillSaysLanePastTheExitHoldsTheTurnThenStopsSayingWhy) {
  const NavigatorConfig c = gated();
  const Drive r = drive(
      0, false, [](const core::Pose2&) { return map::Place::lane; }, c);
  EXPECT_EQ(r.last.state, NavState::safe_stop);
  EXPECT_EQ(r.last.stop_reason, StopReason::place_contradicts_plan);
  EXPECT_EQ(r.last.served, 0);  // the corridor is not counted: its end is in doubt
  EXPECT_NE(r.stop_message.find("still places the robot in a lane"), std::string::npos)
      << r.stop_message;
  // It drove exit_wait past the exit point along the row line, then stopped: no turn.
  EXPECT_NEAR(r.T.x, kRowsEnd + c.exit_distance + c.place_gate.exit_wait, 0.1);
  EXPECT_EQ(std::count(r.states.begin(), r.states.end(), NavState::turning), 0);
}

TEST(NavigatorPlaceGate, AnEntryTheMapCallsAnAlleyOrAGateIsASafeStop) {
  for (const map::Place p : {map::Place::alley, map::Place::gate}) {
    // The lane of corridor 0 is a lane; everything the robot enters after the turn is `p`.
    const PlaceMap m = [p](const core::Pose2& T) {
      return std::cos(T.theta) > 0.0 ? lagging_map(0.3)(T) : lagging_map(0.3, 0.3, p)(T);
    };
    const Drive r = drive(0, false, m, gated());
    EXPECT_EQ(r.last.stop_reason, StopReason::place_contradicts_plan) << core::enum_name(p);
    EXPECT_EQ(r.last.served, 1);
    EXPECT_EQ(r.states[r.states.size() - 2], NavState::entering);
    EXPECT_NE(r.stop_message.find(std::string(core::enum_name(p))), std::string::npos)
        << r.stop_message;
  }
}

TEST(NavigatorPlaceGate, AMapStuckInTheHeadlandStopsTheEntryAtItsMaximumDepth) {
  const NavigatorConfig c = gated();
  const Drive r = drive(0, false, lagging_map(c.entry_max_depth + 3.0), c);
  EXPECT_EQ(r.last.stop_reason, StopReason::place_contradicts_plan);
  EXPECT_EQ(r.states[r.states.size() - 2], NavState::entering);
  EXPECT_NE(r.stop_message.find("in the headland"), std::string::npos) << r.stop_message;
}

TEST(NavigatorPlaceGate, OffTheDefaultTheGateIgnoresTheMap) {
  const Drive r = drive(0, false, [](const core::Pose2&) { return map::Place::alley; });
  EXPECT_EQ(r.last.state, NavState::done);
  EXPECT_EQ(r.last.served, 2);
}

}  // namespace
}  // namespace rownav::navigate
