// Navigator: configuration, the per-frame dispatch, in-row following and the exit by odometry.
// Headland turn and corridor entry: navigator_headland.cpp.
#include "rownav/navigate/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rownav::navigate {

namespace {

/// The robot is at the rows unless every followed row is seen to begin farther than `reach`
/// ahead of the base (a tracking without row extents cannot tell: at the rows).
bool reached_rows(const track::RowTracking& t, double reach) {
  if (t.status == track::TrackStatus::lost) return false;
  bool any = false;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) continue;
    const double x = t.rows[static_cast<std::size_t>(i)].x_min;
    if (!std::isfinite(x) || x <= reach) return true;
    any = true;
  }
  return !any;
}

/// Whether a followed row goes on past x = from (base frame): the returns within `across` of
/// its line span more than `length` along it beyond from (a ridge or a weed that hid the rows
/// leaves them there; clutter across the headland crosses the line in a point or two). Without a
/// followed row: true.
bool row_goes_on(const track::RowTracking& t, std::span<const Eigen::Vector2f> pts, double from,
                 double across, double length) {
  bool any = false;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) continue;
    any = true;
    const core::Line2& line = t.rows[static_cast<std::size_t>(i)].line_base;
    double lo = 1e300, hi = -1e300;
    for (const auto& p : pts) {
      const Eigen::Vector2d q = p.cast<double>();
      if (q.x() <= from || std::abs(line.signed_distance(q)) > across) continue;
      lo = std::min(lo, q.x()), hi = std::max(hi, q.x());
    }
    if (hi - lo > length) return true;
  }
  return !any;  // no followed row left to look along: cannot tell, it may go on
}

/// [m] free width between the followed rows' inner canopy edges; nullopt without both rows.
std::optional<double> clear_width(const track::RowTracking& t) {
  if (t.left < 0 || t.right < 0 || t.left >= static_cast<int>(t.rows.size()) ||
      t.right >= static_cast<int>(t.rows.size()))
    return std::nullopt;
  const auto edge = [](const track::TrackedRow& r, double side) {
    if (std::isfinite(r.centre_offset) && r.half_width > 0.0)
      return r.centre_offset + side * r.half_width;
    return r.offset;  // a fitted face (planar scan): already the edge
  };
  const double w = edge(t.rows[static_cast<std::size_t>(t.left)], -1.0) -
                   edge(t.rows[static_cast<std::size_t>(t.right)], 1.0);
  return std::isfinite(w) ? std::optional<double>(w) : std::nullopt;
}

}  // namespace

void Navigator::check_lane(const NavInput& in, NavOutput& out) {
  if (config_.narrow_frames == 0 || narrow_said_ ||
      in.tracking.status != track::TrackStatus::tracking)
    return;
  const auto w = clear_width(in.tracking);
  if (!w) return;
  ++lane_frames_;
  if (*w < in.robot.width + 2.0 * config_.narrow_margin) ++narrow_count_;
  // Most of the corridor's frames so far, and at least narrow_frames of them (a gap or a
  // wrong frame is not a narrow corridor).
  if (narrow_count_ < config_.narrow_frames || 2 * narrow_count_ <= lane_frames_) return;
  narrow_said_ = true;
  out.events.push_back({in.stamp, NavEventKind::narrow_corridor, order_[leg_],
                        in.T_odom_base.translation(),
                        "lane " + fmt(*w) + " m clear between the rows' canopies, robot " +
                            fmt(in.robot.width) + " m wide: it will brush or crush plants"});
}

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
  core::check_non_negative(exit_clearance, "exit_clearance");
  core::check_positive(perception_timeout, "perception_timeout");
  core::check_non_negative(lost_rows_end_reach, "lost_rows_end_reach");
  core::check_non_negative(arm_reach, "arm_reach");
  core::check_non_negative(narrow_frames, "narrow_frames");
  core::check_non_negative(narrow_margin, "narrow_margin");
  core::check_non_negative(stop_distance, "stop_distance");
  core::check_positive(obstacle_min_points, "obstacle_min_points");
  core::check_positive(blocked_timeout, "blocked_timeout");
  core::check_non_negative(blocked_speed, "blocked_speed");
  core::check_positive(entry_check_depth, "entry_check_depth");
  core::check(entry_max_depth > entry_check_depth, "entry_max_depth",
              "must be > entry_check_depth");
  core::check_range(entry_gate, 0.05, 1.0, "entry_gate");
  core::validate_nested(row_end_estimate, "row_end_estimate");
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
      end_box_near_(end_box_near),
      exit_distance_(config.exit_distance),
      ends_(config.row_end_estimate) {
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
  // Outside a row too (issue 13, a person walking in): the person's shadow on the rows ahead
  // looked like the row end, and `exiting` then drove into it by odometry.
  if (state_ != NavState::in_row && state_ != NavState::done && state_ != NavState::safe_stop)
    if (const auto obstacle = obstacle_ahead(in)) {
      stop(StopReason::obstacle, out, in.stamp,
           *obstacle + " (" + std::string(core::enum_name(state_)) + ")");
      return finish(std::move(out));
    }
  switch (state_) {
    case NavState::in_row:
      in_row(in, out);
      break;
    case NavState::exiting:
      ends_.update(in.tracking, in.T_odom_base, in.observation.stamp);
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

void Navigator::in_row(const NavInput& in, NavOutput& out) {
  const bool seen = in.observation.status != core::DetectionStatus::no_rows &&
                    in.tracking.status != track::TrackStatus::lost;
  if (seen) last_seen_ = in.stamp;
  if (in.stamp - last_seen_ > config_.perception_timeout) {
    // Rows lost just before the end they were seen to have (standing still in odom) while the
    // lane ahead is in view: the detector ran out of row, a planar one with a few metres left
    // (issue 11), not a blind robot. Leave the row as at a detected end. A ridge or a weed
    // also stands still in odom, but hides the lane (end-of-row shadow test), and rows that go
    // on leave their returns beyond it.
    const auto ahead = ends_.settled_end_ahead();
    const auto& settle = config_.row_end_estimate;
    if (at_rows_ && in.end_of_row.box_seen && ahead && *ahead <= config_.lost_rows_end_reach &&
        !row_goes_on(in.tracking, in.points_base, *ahead + settle.settle_tolerance,
                     settle.settle_tolerance, settle.settle_distance)) {
      start_exit(in, out, "rows lost " + fmt(*ahead) + " m before their settled end");
      return exiting(in.T_odom_base, out, in.stamp);
    }
    return stop(StopReason::perception_lost, out, in.stamp,
                "no rows for " + fmt(in.stamp - last_seen_) + " s" +
                    (in.points_base.empty()
                         ? " and no points in the detection window (sensor above the crop, "
                           "or pointed away from it?)"
                         : ""));
  }
  if (const auto obstacle = obstacle_ahead(in))
    return stop(StopReason::obstacle, out, in.stamp, *obstacle);
  if (const auto blocked = held_by_obstacle(in))
    return stop(StopReason::obstacle, out, in.stamp, *blocked);
  ends_.update(in.tracking, in.T_odom_base, in.observation.stamp);
  check_lane(in, out);
  control::ControlInput c;
  c.stamp = in.stamp;
  c.lateral_error = in.tracking.lateral_error;
  c.heading_error = in.tracking.heading_error;
  c.path_base = in.tracking.centre_line_base;
  c.steepness = in.tracking.steepness;
  c.speed_ref = config_.row_speed;
  c.speed = in.twist.v;
  out.control = c;
  const auto& centre = ends_.centre();
  at_rows_ = at_rows_ || reached_rows(in.tracking, config_.arm_reach);
  // Before the rows (a start in the headland) the end-of-row box sees the rows' first plants
  // only: that is no row end, and the detector latches what it declares, so its evidence starts
  // at the rows (issue 10: leek fields of the zoo latched a row end 1.5 m before the first plant
  // and drove out by odometry at once).
  if (!at_rows_) out.reset_end_of_row = true;
  if (in.end_of_row.end_detected && centre && at_rows_) start_exit(in, out, "row end detected");
}

void Navigator::start_exit(const NavInput& in, NavOutput& out, const std::string& why) {
  const core::Line2& centre = *ends_.centre();
  state_ = NavState::exiting;
  blocked_since_.reset();
  exit_distance_ = exit_distance(in);
  if (!ends_.end_arc()) {  // no row end seen: the detector's distance, else the box's near edge
    const double ahead = in.end_of_row.distance_to_end.value_or(end_box_near_);
    ends_.set_end_arc(centre.arc(in.T_odom_base.translation()) + ahead);
  }
  const double end = *ends_.end_arc();
  const double left = end - centre.arc(in.T_odom_base.translation()) + exit_distance_;
  exit_effort_ = StateEffort{std::max(0.0, left), std::max(0.0, left) / config_.row_speed};
  out.events.push_back(
      {in.stamp, NavEventKind::row_end, order_[leg_], centre.at(end),
       why + ", " + fmt(end - centre.arc(in.T_odom_base.translation())) + " m ahead"});
}

double Navigator::exit_distance(const NavInput& in) const {
  double canopy = 0.0;  // widest measured half width of the followed rows
  for (const int i : {in.tracking.left, in.tracking.right}) {
    if (i < 0 || i >= static_cast<int>(in.tracking.rows.size())) continue;
    const double h = in.tracking.rows[static_cast<std::size_t>(i)].half_width;
    if (std::isfinite(h)) canopy = std::max(canopy, h);
  }
  return std::max(config_.exit_distance, canopy + 0.5 * in.robot.width + config_.exit_clearance);
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
  if (centre.arc(T.translation()) < *ends_.end_arc() + exit_distance_) {
    out.cmd = follow_line(centre, T, config_.row_speed);
    return;
  }
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
