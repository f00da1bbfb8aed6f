// Navigator: configuration, the per-frame dispatch, in-row following and the exit by odometry.
// Headland turn and corridor entry: navigator_headland.cpp.
#include "rownav/navigate/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rownav::navigate {

std::string Navigator::fmt(double v) {  // event texts: centimetres are enough
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << v;
  return s.str();
}

void NavigatorConfig::validate() const {
  core::check_positive(row_speed, "row_speed");
  core::check_positive(entry_speed, "entry_speed");
  core::check_non_negative(exit_distance, "exit_distance");
  core::check_positive(perception_timeout, "perception_timeout");
  core::check_non_negative(stop_distance, "stop_distance");
  core::check_positive(obstacle_min_points, "obstacle_min_points");
  core::check_positive(entry_check_depth, "entry_check_depth");
  core::check(entry_max_depth > entry_check_depth, "entry_max_depth",
              "must be > entry_check_depth");
  core::check_range(entry_gate, 0.05, 1.0, "entry_gate");
  core::check_positive(row_end_frames, "row_end_frames");
  core::check_positive(line_gain, "line_gain");
  core::check_positive(heading_gain, "heading_gain");
  core::validate_nested(turn, "turn");
  core::validate_nested(row_ends, "row_ends");
}

Navigator::Navigator(const NavigatorConfig& config, std::vector<int> order, TurnSide first_turn,
                     double end_box_near)
    : config_(config),
      order_(std::move(order)),
      changes_(corridor_changes(order_, first_turn)),
      end_box_near_(end_box_near) {
  config_.validate();
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

NavOutput Navigator::step(const NavInput& in) {
  NavOutput out;
  robot_ = in.robot;
  last_stamp_ = in.stamp;
  if (last_seen_ < 0.0) last_seen_ = in.stamp;
  switch (state_) {
    case NavState::in_row:
      in_row(in, out);
      break;
    case NavState::exiting:
      remember_row_geometry(in);
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

bool Navigator::obstacle_ahead(const NavInput& in) const {
  const double x0 = in.robot.base_to_front, x1 = x0 + config_.stop_distance;
  const double half = in.robot.width / 2.0;
  int n = 0;
  for (const auto& p : in.points_base)
    if (std::isfinite(p.x()) && std::isfinite(p.y()) && p.x() > x0 && p.x() < x1 &&
        std::abs(p.y()) < half)
      ++n;
  return n >= config_.obstacle_min_points;
}

Eigen::Vector2d Navigator::recent_median(std::deque<Eigen::Vector2d>& recent,
                                         const Eigen::Vector2d& p) const {
  // The latest frames give the end relative to the robot with the least odometry drift; the
  // median of a few of them drops single-frame outliers (a weed or post in the headland on the
  // row's line stretches the support).
  recent.push_back(p);
  while (static_cast<int>(recent.size()) > config_.row_end_frames) recent.pop_front();
  std::vector<std::pair<double, Eigen::Vector2d>> by_arc;
  for (const auto& q : recent) by_arc.emplace_back(centre_odom_->arc(q), q);
  const auto mid = by_arc.begin() + static_cast<std::ptrdiff_t>(by_arc.size() / 2);
  std::nth_element(by_arc.begin(), mid, by_arc.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  return mid->second;
}

void Navigator::remember_row_geometry(const NavInput& in) {
  const auto& t = in.tracking;
  if (t.status != track::TrackStatus::tracking) return;
  const core::Pose2& T = in.T_odom_base;
  // Past the row ends only a short stub of row remains behind the robot (and headland clutter
  // ahead): its line is no longer trusted, the exit keeps the last in-row centre line.
  const bool past_end = centre_odom_ && end_arc_ && centre_odom_->arc(T.translation()) > *end_arc_;
  if (!past_end) centre_odom_ = t.centre_line_base.transformed(T);
  if (t.row_spacing > 0.0) {  // running mean of the tracker's spacing (003 Table I row width)
    spacing_ = (spacing_ * spacing_n_ + t.row_spacing) / (spacing_n_ + 1);
    spacing_n_ = std::min(spacing_n_ + 1, 50);
  }
  // Row ends: the far end of the followed rows' support, once it is in view (not range-cut).
  // Only rows observed in this frame count: a coasting row keeps the extent of an older frame,
  // in that frame's base, which would push the end forward by the distance driven since.
  auto end_of = [&](int i) -> std::optional<Eigen::Vector2d> {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) return std::nullopt;
    const auto& r = t.rows[static_cast<std::size_t>(i)];
    if (r.x_max > 7.0 || r.support < 3 || r.last_seen < in.observation.stamp) return std::nullopt;
    return T * Eigen::Vector2d(r.x_max, r.line_base.y_at(r.x_max));
  };
  if (auto e = end_of(t.left)) left_end_ = recent_median(left_ends_, *e);
  if (auto e = end_of(t.right)) right_end_ = recent_median(right_ends_, *e);
  if (left_end_ || right_end_) {
    double arc = 0.0;
    int n = 0;
    for (const auto& e : {left_end_, right_end_})
      if (e) arc += centre_odom_->arc(*e), ++n;
    end_arc_ = arc / n;
  }
}

void Navigator::in_row(const NavInput& in, NavOutput& out) {
  const bool seen = in.observation.status != core::DetectionStatus::no_rows &&
                    in.tracking.status != track::TrackStatus::lost;
  if (seen) last_seen_ = in.stamp;
  if (in.stamp - last_seen_ > config_.perception_timeout)
    return stop(StopReason::perception_lost, out, in.stamp,
                "no rows for " + fmt(in.stamp - last_seen_) + " s");
  if (obstacle_ahead(in))
    return stop(StopReason::obstacle, out, in.stamp,
                "obstacle within " + fmt(config_.stop_distance) + " m");
  remember_row_geometry(in);
  control::ControlInput c;
  c.stamp = in.stamp;
  c.lateral_error = in.tracking.lateral_error;
  c.heading_error = in.tracking.heading_error;
  c.path_base = in.tracking.centre_line_base;
  c.steepness = in.tracking.steepness;
  c.speed_ref = config_.row_speed;
  c.speed = in.twist.v;
  out.control = c;
  if (in.end_of_row.end_detected && centre_odom_) {
    state_ = NavState::exiting;
    if (!end_arc_) {  // no row end seen: take the detector's distance, else the box's near edge
      const double ahead = in.end_of_row.distance_to_end.value_or(end_box_near_);
      end_arc_ = centre_odom_->arc(in.T_odom_base.translation()) + ahead;
    }
    out.events.push_back(
        {in.stamp, NavEventKind::row_end, order_[leg_], centre_odom_->at(*end_arc_),
         "row end detected, " + fmt(*end_arc_ - centre_odom_->arc(in.T_odom_base.translation())) +
             " m ahead"});
  }
}

core::Twist2 Navigator::follow_line(const core::Line2& line, const core::Pose2& T, double v) const {
  const double lat = line.signed_distance(T.translation());
  const double head = core::angle_diff(T.theta, line.heading());
  const double w = -config_.line_gain * v * lat - config_.heading_gain * head;
  return {v, 0.0, std::clamp(w, -1.0, 1.0)};
}

void Navigator::exiting(const core::Pose2& T, NavOutput& out, double stamp) {
  // 003 sec. II-B: leave the row by a fixed distance measured by odometry.
  const double s = centre_odom_->arc(T.translation());
  if (s < *end_arc_ + config_.exit_distance) {
    out.cmd = follow_line(*centre_odom_, T, config_.row_speed);
    return;
  }
  ++served_;
  if (left_end_) row_ends_.push_back(*left_end_);
  if (right_end_) row_ends_.push_back(*right_end_);
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
