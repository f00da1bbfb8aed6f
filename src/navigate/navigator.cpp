// Navigator: configuration, the per-frame dispatch, stops, obstacles and the exit by odometry.
// In-row following and the row end: navigator_in_row.cpp; headland and entry:
// navigator_headland.cpp.
#include "rownav/navigate/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rownav::navigate {

void NavigatorConfig::validate() const {
  core::check_positive(row_speed, "row_speed");
  core::check_positive(entry_speed, "entry_speed");
  core::check_non_negative(exit_distance, "exit_distance");
  core::check_non_negative(exit_clearance, "exit_clearance");
  core::check_positive(perception_timeout, "perception_timeout");
  core::check_non_negative(lost_rows_end_reach, "lost_rows_end_reach");
  core::check_non_negative(end_withdraw_reach, "end_withdraw_reach");
  core::check_non_negative(arm_reach, "arm_reach");
  core::check_non_negative(narrow_frames, "narrow_frames");
  core::check_non_negative(narrow_margin, "narrow_margin");
  core::check_non_negative(stop_distance, "stop_distance");
  core::check_non_negative(rotation_clearance, "rotation_clearance");
  core::check_positive(obstacle_min_points, "obstacle_min_points");
  core::check_positive(blocked_timeout, "blocked_timeout");
  core::check_non_negative(blocked_speed, "blocked_speed");
  core::check_positive(entry_check_depth, "entry_check_depth");
  core::check(entry_max_depth > entry_check_depth, "entry_max_depth",
              "must be > entry_check_depth");
  core::check_range(entry_gate, 0.05, 1.0, "entry_gate");
  core::check_range(entry_heading_gate_deg, 1.0, 90.0, "entry_heading_gate_deg");
  core::validate_nested(row_end_estimate, "row_end_estimate");
  core::check_positive(line_gain, "line_gain");
  core::check_positive(heading_gain, "heading_gain");
  core::validate_nested(turn, "turn");
  core::validate_nested(row_ends, "row_ends");
  core::validate_nested(place_gate, "place_gate");
}

Navigator::Navigator(const NavigatorConfig& config, std::vector<int> order, TurnSide first_turn,
                     const EndOfRowConfig& end_of_row)
    : config_(config),
      order_(std::move(order)),
      changes_(corridor_changes(order_, first_turn)),
      end_box_near_(end_of_row.box_x_min),
      exit_distance_(config.exit_distance),
      ends_(config.row_end_estimate) {
  config_.validate();
  // A declared row end is withdrawn by rows that go on beyond the reach that declares one.
  if (config_.end_withdraw_reach <= 0.0) config_.end_withdraw_reach = end_of_row.extent_distance;
  if (order_.empty()) state_ = NavState::done;
}

NavOutput Navigator::finish(NavOutput out) {
  out.state = state_;
  out.stop_reason = reason_;
  out.corridor = leg_ < order_.size() ? order_[leg_] : -1;
  out.served = served_;
  if (state_ == NavState::done || state_ == NavState::safe_stop) out.cmd = {}, out.control.reset();
  if (!std::isfinite(out.cmd.v) || !std::isfinite(out.cmd.omega)) out.cmd = {};
  return out;
}

void Navigator::stop(StopReason reason, NavOutput& out, double stamp, const std::string& why) {
  state_ = NavState::safe_stop;
  reason_ = reason;
  out.cmd = {};
  out.events.push_back({stamp, NavEventKind::safe_stop, leg_ < order_.size() ? order_[leg_] : -1,
                        Eigen::Vector2d::Zero(),
                        "safe stop: " + std::string(core::enum_name(reason)) + " (" + why + ")"});
}

void Navigator::stop_for_obstacle(NavOutput& out, double stamp, const std::string& where) {
  stop(StopReason::obstacle, out, stamp, where + " (" + std::string(core::enum_name(state_)) + ")");
}

NavOutput Navigator::step(const NavInput& in) {
  NavOutput out;
  robot_ = in.robot;
  last_stamp_ = in.stamp;
  place_ = in.place;
  if (last_seen_ < 0.0) last_seen_ = in.stamp;
  // Outside a row too (issue 13, a person walking in): the person's shadow on the rows ahead
  // looked like the row end, and `exiting` then drove into it by odometry.
  // A turn checks the command it is about to send instead (turning(): a rotation in place
  // sweeps a circle, it does not drive into the box ahead).
  if (state_ == NavState::exiting || state_ == NavState::entering)
    if (const auto obstacle = obstacle_ahead(in)) {
      stop_for_obstacle(out, in.stamp, *obstacle);
      return finish(std::move(out));
    }
  switch (state_) {
    case NavState::in_row:
      in_row(in, out);
      break;
    case NavState::exiting:
      ends_.update(in.tracking, in.T_odom_base, in.observation.stamp);
      if (withdraw_end(in, out)) break;
      bound_exit(in);
      exiting(in.T_odom_base, out, in.stamp);
      break;
    case NavState::turning:
    case NavState::headland:
      turning(&in, in.T_odom_base, out, in.stamp);
      break;
    case NavState::entering:
      entering(&in, in.T_odom_base, out, in.stamp);
      break;
    case NavState::done:
    case NavState::safe_stop:
      break;
  }
  return finish(std::move(out));
}

std::optional<StateEffort> Navigator::effort() const {
  switch (state_) {
    case NavState::exiting:
      return exit_effort_;
    case NavState::turning:
    case NavState::headland:
      if (manoeuvre_)
        return StateEffort{manoeuvre_->planned_distance(), manoeuvre_->planned_time()};
      return std::nullopt;
    case NavState::entering: {
      const double d = config_.entry_max_depth + exit_distance_;
      return StateEffort{d, d / config_.entry_speed};
    }
    default:
      return std::nullopt;
  }
}

NavOutput Navigator::abort(StopReason reason, double stamp, const std::string& why) {
  NavOutput out;
  if (state_ != NavState::done && state_ != NavState::safe_stop) stop(reason, out, stamp, why);
  return finish(std::move(out));
}

NavOutput Navigator::hold(double stamp, const core::Pose2& T_odom_base,
                          const core::Twist2& last_cmd) {
  NavOutput out;
  out.cmd = last_cmd;
  switch (state_) {
    case NavState::exiting:
      exiting(T_odom_base, out, stamp);
      break;
    case NavState::turning:
    case NavState::headland:
      turning(nullptr, T_odom_base, out, stamp);
      break;
    case NavState::entering:
      entering(nullptr, T_odom_base, out, stamp);
      break;
    default:
      break;
  }
  return finish(std::move(out));
}

std::optional<std::string> Navigator::obstacle_ahead(const NavInput& in) const {
  const double x0 = in.robot.base_to_front, x1 = x0 + config_.stop_distance;
  const double half = in.robot.width / 2.0;
  int n = 0;
  double nearest = x1, y_lo = half, y_hi = -half;
  for (const auto& p : in.obstacle_points_base.value_or(in.points_base))
    if (std::isfinite(p.x()) && std::isfinite(p.y()) && p.x() > x0 && p.x() < x1 &&
        std::abs(p.y()) < half) {
      ++n;
      nearest = std::min(nearest, double(p.x()) - x0);
      y_lo = std::min(y_lo, double(p.y())), y_hi = std::max(y_hi, double(p.y()));
    }
  if (n < config_.obstacle_min_points) return std::nullopt;
  // Where it is, so that a user can tell a person from a weed or a branch in the log.
  return "obstacle within " + fmt(config_.stop_distance) + " m: " + std::to_string(n) +
         " points, nearest " + fmt(nearest) + " m ahead of the front, y " + fmt(y_lo) + " to " +
         fmt(y_hi) + " m";
}

std::optional<std::string> Navigator::obstacle_in_swing(const NavInput& in) const {
  const double front = in.robot.base_to_front, back = in.robot.length - front;
  const double half = in.robot.width / 2.0;
  const double reach = std::max(std::hypot(front, half), std::hypot(back, half));
  const double r = reach + config_.rotation_clearance;
  int n = 0;
  double nearest = r;
  for (const auto& p : in.obstacle_points_base.value_or(in.points_base)) {
    const double d = p.cast<double>().norm();
    if (std::isfinite(d) && d < r) ++n, nearest = std::min(nearest, d);
  }
  if (n < config_.obstacle_min_points) return std::nullopt;
  return "obstacle within the rotating footprint's reach (" + fmt(r) + " m): " + std::to_string(n) +
         " points, nearest " + fmt(nearest) + " m from base_link";
}

std::optional<std::string> Navigator::held_by_obstacle(const NavInput& in) {
  if (!std::isfinite(in.obstacle_distance) || std::abs(in.twist.v) >= config_.blocked_speed) {
    blocked_since_.reset();
    return std::nullopt;
  }
  if (!blocked_since_) blocked_since_ = in.stamp;
  if (in.stamp - *blocked_since_ < config_.blocked_timeout) return std::nullopt;
  return "blocked for " + fmt(in.stamp - *blocked_since_) + " s by an obstacle " +
         fmt(in.obstacle_distance) + " m ahead of the front (fewer than " +
         std::to_string(config_.obstacle_min_points) + " points: not in the stop box)";
}

core::Twist2 Navigator::follow_line(const core::Line2& line, const core::Pose2& T, double v) const {
  const double lat = line.signed_distance(T.translation());
  const double head = core::angle_diff(T.theta, line.heading());
  const double w = -config_.line_gain * v * lat - config_.heading_gain * head;
  return {v, 0.0, std::clamp(w, -1.0, 1.0)};
}

void Navigator::exiting(const core::Pose2& T, NavOutput& out, double stamp) {
  // 003 sec. II-B: leave the row by a fixed distance measured by odometry.
  const core::Line2& centre = *ends_.centre();
  // The end moves with the tracked rows, by at most end_withdraw_reach past the declared one
  // unless the rows were seen to run on from it (bound_exit).
  const double end =
      exit_rows_run_on_
          ? *ends_.end_arc()
          : std::min(*ends_.end_arc(), centre.arc(declared_end_) + config_.end_withdraw_reach);
  const double past = centre.arc(T.translation()) - (end + exit_distance_);
  const GateVerdict gate =
      past < 0.0 ? GateVerdict::wait : exit_verdict(place_, past, config_.place_gate);
  if (gate == GateVerdict::wait) {
    out.cmd = follow_line(centre, T, config_.row_speed);
    return;
  }
  if (gate == GateVerdict::contradict)
    return stop(StopReason::place_contradicts_plan, out, stamp,
                "left the row end by " + fmt(past + exit_distance_) +
                    " m but the map still places the robot in a lane (no exit validated: a gap "
                    "in the rows?)");
  ++served_;
  if (ends_.left_end()) row_ends_.push_back(*ends_.left_end());
  if (ends_.right_end()) row_ends_.push_back(*ends_.right_end());
  out.events.push_back({stamp, NavEventKind::exit_done, order_[leg_], T.translation(),
                        "left corridor " + std::to_string(order_[leg_])});
  if (leg_ + 1 >= order_.size()) {
    state_ = NavState::done;
    reason_ = StopReason::done;
    out.events.push_back({stamp, NavEventKind::mission_done, order_[leg_], T.translation(),
                          "mission done: " + std::to_string(served_) + " corridors served"});
    return;
  }
  start_turn(T, out, stamp);
}

}  // namespace rownav::navigate
