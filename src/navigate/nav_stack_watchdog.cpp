// NavStack's watchdog (navigate/nav_stack.hpp, StackConfig::watchdog): the command is zero while
// the LiDAR or the odometry is stale, and a state decided by odometry alone (exiting, a turn, an
// entry) that takes far longer or farther than planned ends in a safe stop (issue 13: with
// ticks_per_rev 1 the robot stayed `exiting` for 1,766 s and drove 878 m outside the field).
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "rownav/navigate/nav_stack.hpp"

namespace rownav::navigate {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

std::string fixed(double v) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << v;
  return s.str();
}

/// Turning and headland are one manoeuvre: one budget.
int phase_of(NavState s) {
  return s == NavState::headland ? static_cast<int>(NavState::turning) : static_cast<int>(s);
}

}  // namespace

std::optional<std::string> budget_exceeded(const StateEffort& planned, double elapsed,
                                           double distance, const WatchdogConfig& w) {
  const double time_budget = w.budget_factor * planned.time + w.budget_time_margin;
  const double dist_budget = w.budget_factor * planned.distance + w.budget_distance_margin;
  if (elapsed <= time_budget && distance <= dist_budget) return std::nullopt;
  return "took " + fixed(elapsed) + " s / " + fixed(distance) + " m, budget " + fixed(time_budget) +
         " s / " + fixed(dist_budget) + " m";
}

void NavStack::watch_inputs(NavCommand& c, NavOutput& out, double stamp) {
  const auto& w = config_.stack.watchdog;
  // A sweep stamped at its start is complete one period later.
  c.lidar_age = last_frame_stamp_ ? stamp - (*last_frame_stamp_ + sweep_period_) : kNever;
  double odom = -kNever;
  if (config_.stack.odometry == OdometryInput::wheels_imu)
    odom = last_encoder_;
  else if (const auto latest = external_.latest())
    odom = latest->stamp;
  c.odometry_age = stamp - odom;
  InputHealth h = InputHealth::ok;
  if (!(c.lidar_age <= w.lidar_timeout)) h = InputHealth::lidar_stale;
  if (!(c.odometry_age <= w.odometry_timeout)) h = InputHealth::odometry_stale;
  c.health = h;
  if (h != InputHealth::ok) out.cmd = {};  // never move on old data
  if (h == health_) {
    inputs_seen_ |= h == InputHealth::ok;
    return;
  }
  // Events on transitions only, once inputs have been fresh (not while starting up).
  if (h != InputHealth::ok && inputs_seen_)
    out.events.push_back(
        {stamp, NavEventKind::input_stale, out.corridor, Eigen::Vector2d::Zero(),
         std::string("watchdog: ") +
             (h == InputHealth::lidar_stale ? "LiDAR " + fixed(c.lidar_age)
                                            : "odometry " + fixed(c.odometry_age)) +
             " s old, command zero"});
  if (h == InputHealth::ok && inputs_seen_)
    out.events.push_back({stamp, NavEventKind::input_resumed, out.corridor, Eigen::Vector2d::Zero(),
                          "watchdog: inputs fresh again"});
  inputs_seen_ |= h == InputHealth::ok;
  health_ = h;
}

void NavStack::watch_budget(NavOutput& out, double stamp, const std::optional<core::Pose2>& T) {
  const int phase = phase_of(out.state);
  if (phase != phase_) {
    phase_ = phase;
    phase_start_ = stamp, phase_distance_ = 0.0;
    phase_effort_ = navigator_->effort();
    phase_last_T_ = T;
    return;
  }
  if (T && phase_last_T_)
    phase_distance_ += (T->translation() - phase_last_T_->translation()).norm();
  if (T) phase_last_T_ = T;
  if (!phase_effort_) return;
  if (const auto why = budget_exceeded(*phase_effort_, stamp - phase_start_, phase_distance_,
                                       config_.stack.watchdog))
    safe_stop(out, StopReason::budget_exceeded, stamp,
              std::string(core::enum_name(out.state)) + " " + *why);
}

void NavStack::watch_odometry(NavOutput& out, double stamp, const std::optional<core::Pose2>& T) {
  const auto& w = config_.stack.watchdog;
  // The command sent last has been applied since the previous call.
  const double dt = last_command_stamp_ ? stamp - *last_command_stamp_ : 0.0;
  const double measured =
      T && motion_last_T_ ? (T->translation() - motion_last_T_->translation()).norm() : 0.0;
  if (T) motion_last_T_ = T;
  motion_.push_back({stamp, std::abs(sent_cmd_.v) * dt, measured});
  commanded_sum_ += motion_.back().commanded, measured_sum_ += measured;
  while (!motion_.empty() && motion_.front().stamp < stamp - w.plausibility_window) {
    commanded_sum_ -= motion_.front().commanded, measured_sum_ -= motion_.front().measured;
    motion_.pop_front();
  }
  if (commanded_sum_ < w.plausibility_distance ||
      measured_sum_ >= w.plausibility_ratio * commanded_sum_)
    return;
  safe_stop(out, StopReason::odometry_implausible, stamp,
            "commanded " + fixed(commanded_sum_) + " m in " + fixed(w.plausibility_window) +
                " s, odometry moved " + fixed(measured_sum_) + " m");
}

void NavStack::set_held(bool held) {
  // A new hold watches from the rows as the last frame tracked them: a robot carried off at the
  // pause's first instant is as moved as one pushed later.
  if (held && !held_) {
    hold_reference_ = last_tracked_, hold_reported_ = false;
    hold_blocker_.reset();
    // The wait before a start is when the operator places the robot: only a pause in a row of
    // a mission that has driven guards its resume (in a manoeuvre no corridor is tracked).
    hold_guards_resume_ = driven_ && navigator_->state() == NavState::in_row;
  }
  if (!held && held_ && hold_guards_resume_ && hold_blocker_) resume_refused_ = hold_blocker_;
  held_ = held;
}

std::optional<std::string> NavStack::resume_blocker() const {
  if (held_ && hold_guards_resume_) return hold_blocker_;
  return std::nullopt;
}

void NavStack::watch_hold(const FrameReport& report, NavOutput& out, double stamp) {
  if (!report.tracking) return;  // no pose at the frame: nothing was tracked
  const track::RowTracking& t = *report.tracking;
  const bool tracked = t.status == track::TrackStatus::tracking;
  const bool lost = t.status == track::TrackStatus::lost;
  const auto& w = config_.stack.watchdog;
  if (held_ && hold_guards_resume_ && !hold_blocker_ && hold_reference_) {
    // Out of the corridor: on or past a followed row (the offset moved half a spacing since the
    // hold began), or in another corridor (the offset jumps by about a spacing in one tracked
    // frame, a coasting gap between the two included).
    const double spacing = t.row_spacing > 0.0 ? t.row_spacing : t.corridor_width;
    const double limit = w.held_corridor_fraction * spacing;
    const double step = tracked && last_tracked_ ? t.lateral_error - last_tracked_->x() : 0.0;
    const double moved = tracked ? t.lateral_error - hold_reference_->x() : 0.0;
    const std::string rows = ", rows " + fixed(100.0 * spacing) + " cm apart";
    if (lost)
      hold_blocker_ = "the rows tracked when the hold began were lost (carried out of them?)";
    else if (spacing > 0.0 && std::abs(step) > limit)
      hold_blocker_ = "the tracked corridor centre jumped " + fixed(100.0 * step) +
                      " cm in one frame" + rows + ": pushed into another corridor";
    else if (spacing > 0.0 && std::abs(moved) > limit)
      hold_blocker_ = "pushed " + fixed(100.0 * moved) + " cm sideways" + rows +
                      ": onto or past a row of its corridor";
  }
  if (tracked) last_tracked_ = Eigen::Vector2d(t.lateral_error, t.heading_error);
  if (lost && !held_) last_tracked_.reset();  // a hold begun now has no rows to watch from
  if (!held_ || hold_reported_) return;
  std::string why;
  if (tracked) {
    if (!hold_reference_) hold_reference_ = last_tracked_;
    const Eigen::Vector2d moved = *last_tracked_ - *hold_reference_;
    if (std::abs(moved.x()) > w.held_move_lateral ||
        std::abs(moved.y()) > w.held_move_heading_deg * std::numbers::pi / 180.0)
      why = "moved " + fixed(100.0 * moved.x()) + " cm sideways and " +
            fixed(moved.y() * 180.0 / std::numbers::pi) + " deg";
  } else if (hold_reference_) {  // coasting already: the rows are not seen
    why = "the rows tracked when the hold began are lost";
  }
  if (why.empty()) return;
  hold_reported_ = true;
  out.events.push_back({stamp, NavEventKind::moved_while_held, out.corridor,
                        Eigen::Vector2d::Zero(),
                        "held: " + why +
                            " (left +): check the robot stands in the planned "
                            "corridor before resuming"});
}

void NavStack::safe_stop(NavOutput& out, StopReason reason, double stamp, const std::string& why) {
  NavOutput stop = navigator_->abort(reason, stamp, why);
  for (auto& e : stop.events) out.events.push_back(std::move(e));
  out.state = stop.state;
  out.stop_reason = stop.stop_reason;
  out.cmd = {};
}

}  // namespace rownav::navigate
