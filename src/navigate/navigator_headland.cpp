// Navigator: the headland turn (row ends re-anchoring the target) and the corridor entry with
// its place check (Malavazi 2018, 004 sec. 4: dead-reckoned turns often enter the wrong row).
#include <algorithm>
#include <cmath>
#include <optional>

#include "rownav/core/angle.hpp"
#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate {

namespace {

/// The tracked corridor centre in odom, directed along the planned entry line.
core::Line2 seen_centre(const track::RowTracking& tracking, const core::Pose2& T_odom_base,
                        const core::Line2& line) {
  core::Line2 seen = tracking.centre_line_base.transformed(T_odom_base);
  if (seen.direction.dot(line.direction) < 0.0) seen.direction = -seen.direction;
  return seen;
}

/// [m] how far across from the planned entry `line` the `seen` centre lies at the robot; nullopt
/// when it runs more than `max_angle` [rad] across it: a line across the rows is no corridor,
/// whatever its offset at the robot (issue 10).
std::optional<double> entry_offset(const core::Line2& seen, const core::Line2& line,
                                   const Eigen::Vector2d& robot, double max_angle) {
  if (std::abs(core::angle_diff(seen.heading(), line.heading())) >= max_angle) return std::nullopt;
  return std::abs(seen.signed_distance(robot) - line.signed_distance(robot));
}

}  // namespace

void Navigator::start_turn(const core::Pose2& T, NavOutput& out, double stamp) {
  const CorridorChange& change = changes_[leg_];
  const double spacing = ends_.spacing();
  if (!(spacing > 0.0))
    return stop(StopReason::perception_lost, out, stamp, "row spacing never estimated");
  spacing_ = spacing;
  const Eigen::Vector2d origin = ends_.centre()->at(*ends_.end_arc());
  const core::Pose2 T_odom_turn(origin.x(), origin.y(), ends_.centre()->heading());
  const TurnPlan plan = choose_turn(config_.manoeuvre, change.shift, spacing, robot_.turn);
  manoeuvre_ = std::make_unique<HeadlandManoeuvre>(config_.turn, plan, T_odom_turn, change.shift,
                                                   change.side, spacing, exit_distance_);
  out.reset_tracking = true;
  out.reset_end_of_row = true;
  state_ = NavState::turning;
  out.events.push_back({stamp, NavEventKind::turn_started, change.to, T.translation(),
                        std::string(core::enum_name(plan.kind)) + " turn " +
                            std::string(core::enum_name(change.side)) + " by " +
                            std::to_string(change.shift) + " corridor(s), spacing " + fmt(spacing) +
                            " m, towards corridor " + std::to_string(change.to)});
  ends_.reset();
  entry_seen_.reset();
}

void Navigator::turning(const NavInput* in, const core::Pose2& T, NavOutput& out, double stamp) {
  std::vector<Eigen::Vector2d> ends;
  if (in != nullptr) {
    // Row ends in the headland (003 sec. II-C), rows' direction = the turn frame's x axis.
    const double heading_base = core::angle_diff(manoeuvre_->T_odom_turn().theta, T.theta);
    const RowEnds re = estimate_row_ends(in->points_base, heading_base, spacing_, config_.row_ends);
    for (const auto& p : re.poles)
      if (p.allFinite()) ends.push_back(T * p);
    out.row_end_points = ends;
  }
  const ManoeuvreStep s = manoeuvre_->step(T, ends);
  if (in != nullptr) {
    // The command about to be sent decides what it could hit (issue 10).
    const bool rotation = s.cmd.v == 0.0 && s.cmd.omega != 0.0;
    if (const auto o = rotation ? obstacle_in_swing(*in) : obstacle_ahead(*in))
      return stop_for_obstacle(out, stamp, *o);
  }
  out.cmd = s.cmd;
  const int to = order_[leg_ + 1];
  if (s.row_passed)
    out.events.push_back({stamp, NavEventKind::row_passed, to, T.translation(),
                          "row ends passed: " + std::to_string(manoeuvre_->rows_passed())});
  if (s.reanchored)
    out.events.push_back({stamp, NavEventKind::reanchored, to, T.translation(),
                          "target corridor re-anchored on row ends at " +
                              fmt(manoeuvre_->target_y()) + " m across"});
  if (s.phase != ManoeuvrePhase::done) {
    state_ = s.phase == ManoeuvrePhase::headland ? NavState::headland : NavState::turning;
    return;
  }
  ++turns_;
  state_ = NavState::entering;
  out.events.push_back({stamp, NavEventKind::turn_finished, to, T.translation(),
                        "turn finished, entering corridor " + std::to_string(to)});
  out.cmd = follow_line(manoeuvre_->entry_line_odom(), T, config_.entry_speed);
}

void Navigator::entering(const NavInput* in, const core::Pose2& T, NavOutput& out, double stamp) {
  const core::Line2 line = manoeuvre_->entry_line_odom();
  // Once the target corridor's two rows are tracked and agree with the plan (along it, near it),
  // steer on them rather than on the dead-reckoned entry line (004 sec. 4: dead reckoning alone
  // misses rows); the seen line is kept in odom for the control steps between LiDAR frames.
  std::optional<double> observed;  // the tracked corridor's offset from the plan, when along it
  if (in != nullptr && in->tracking.status == track::TrackStatus::tracking) {
    const core::Line2 seen = seen_centre(in->tracking, T, line);
    observed =
        entry_offset(seen, line, T.translation(), core::deg2rad(config_.entry_heading_gate_deg));
    if (observed && *observed < config_.entry_gate * spacing_ && in->tracking.left >= 0 &&
        in->tracking.right >= 0)
      entry_seen_ = seen;
  }
  out.cmd = follow_line(entry_seen_.value_or(line), T, config_.entry_speed);
  if (in == nullptr) return;
  const double depth = line.arc(T.translation()) - exit_distance_;
  const int to = order_[leg_ + 1];
  if (depth >= config_.entry_check_depth && observed && in->observation.corridor) {
    // The corridor the tracker sees must be the planned one: same centre within the gate.
    const double diff = *observed;
    if (diff > config_.entry_gate * spacing_)
      return stop(StopReason::place_contradicts_plan, out, stamp,
                  "corridor seen " + fmt(diff) + " m from the planned one");
    // Issue 12: the map must call it a lane too (headland: not validated yet, drive on).
    const GateVerdict gate = entry_verdict(place_, config_.place_gate);
    if (gate == GateVerdict::contradict)
      return stop(StopReason::place_contradicts_plan, out, stamp,
                  "the map calls the corridor seen '" + std::string(core::enum_name(*place_)) +
                      "', not a lane");
    if (gate == GateVerdict::wait) {
      if (depth > config_.entry_max_depth)
        stop(StopReason::place_contradicts_plan, out, stamp,
             "entered " + fmt(depth) + " m but the map still places the robot in the " +
                 std::string(core::enum_name(*place_)));
      return;
    }
    ++leg_;
    state_ = NavState::in_row;
    at_rows_ = true;  // entered past entry_check_depth: between the rows
    narrow_count_ = lane_frames_ = 0, narrow_said_ = false;
    // The end-of-row detector saw no rows ahead all through the headland and latches; the new
    // corridor starts with a fresh decision.
    out.reset_end_of_row = true;
    last_seen_ = stamp;
    manoeuvre_.reset();
    out.events.push_back(
        {stamp, NavEventKind::entered_corridor, to, T.translation(),
         "entered corridor " + std::to_string(to) + " (offset from plan " + fmt(diff) + " m)"});
    return;
  }
  if (depth > config_.entry_max_depth)
    stop(StopReason::perception_lost, out, stamp, "no corridor seen while entering");
}

}  // namespace rownav::navigate
