// NavStack: the one per-frame path from raw sensor samples to the command (navigate/nav_stack.hpp).
#include "rownav/navigate/nav_stack.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

#include "rownav/control/front_obstacle.hpp"
#include "rownav/localize/gravity_up.hpp"

namespace rownav::navigate {

namespace {

using Clock = std::chrono::steady_clock;

bool terminal(NavState s) {
  return s == NavState::done || s == NavState::safe_stop;
}

bool finite(const core::Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

/// Accepts a sample of a stream whose newest stamp is `last` (updated); counts a drop otherwise.
bool accept(double stamp, double& last, std::uint64_t& accepted, std::uint64_t& dropped) {
  if (!std::isfinite(stamp) || stamp <= last) return ++dropped, false;
  last = stamp;
  ++accepted;
  return true;
}

}  // namespace

struct NavStack::Pending {
  std::variant<core::PointCloud, core::Scan2D> data;
  std::vector<map::PointLabel> labels;  // per cloud point, for the map stage (may be empty)
  double stamp() const {
    return std::visit([](const auto& d) { return d.stamp; }, data);
  }
};

NavStack::NavStack(const NavStackConfig& config, NavStackParts parts, std::vector<int> order,
                   TurnSide first_turn)
    : config_(config),
      parts_(std::move(parts)),
      order_(std::move(order)),
      first_turn_(first_turn),
      localizer_(config.localizer),
      scale_(config.stack.odometry_scale),
      external_(config.stack.odometry_history, config.stack.max_extrapolation),
      place_input_((config.validate(), config.place)),
      cover_(config.stack.obstacles.cover),
      canopy_(config.stack.obstacles.canopy) {
  const StackMode mode = config_.stack.mode;
  core::check(parts_.pipeline != nullptr, "pipeline", "missing");
  core::check(mode == StackMode::detect || parts_.tracker != nullptr, "tracker", "missing");
  core::check(mode != StackMode::navigate || parts_.controller != nullptr, "controller", "missing");
  // Centroids of neighbouring voxels of one surface lie within two edges (end of row's shadow
  // test, issue 11).
  if (config_.end_of_row.shadow_link <= 0.0)
    config_.end_of_row.shadow_link = 2.0 * parts_.pipeline->preprocess_config().voxel.voxel_size;
  end_of_row_ = std::make_unique<EndOfRowDetector>(config_.end_of_row);
  begin_mission();
  // The front rectangle is the robot's own (Bertoglio 2023 sec. II-B).
  config_.stack.front.robot_width = config_.robot.width;
  config_.stack.front.front_x = config_.robot.base_to_front;
  sweep_period_ = config_.stack.sweep_period;
}

NavStack::~NavStack() = default;

void NavStack::begin_mission() {
  // The constructor's plan, from where the robot stands: a fresh navigator and map stage.
  navigator_ =
      std::make_unique<Navigator>(config_.navigator, order_, first_turn_, config_.end_of_row);
  place_.reset();
  if (config_.place.enabled)
    place_ = std::make_unique<map::PlaceEstimator>(config_.place.estimator);
}

void NavStack::restart_mission(std::vector<int> order, TurnSide first_turn) {
  core::check(!order.empty(), "order", "must name at least one corridor");
  order_ = std::move(order);
  first_turn_ = first_turn;
  restart_mission();
}

void NavStack::restart_mission() {
  begin_mission();
  if (parts_.tracker) parts_.tracker->reset();
  if (parts_.controller) parts_.controller->reset();
  end_of_row_->reset();
  cover_.reset();
  canopy_.reset();
  // The watchdog's budget and plausibility windows belong to the mission that ended; the
  // input health (fresh or stale samples) does not.
  phase_ = -1;
  phase_start_ = phase_distance_ = 0.0;
  phase_last_T_.reset();
  phase_effort_.reset();
  motion_.clear();
  commanded_sum_ = measured_sum_ = 0.0;
  motion_last_T_.reset();
  nav_cmd_ = sent_cmd_ = {};
  // A new mission from where the robot stands: the operator has placed it.
  driven_ = hold_guards_resume_ = false;
  hold_blocker_.reset();
  resume_refused_.reset();
}

bool NavStack::on_encoders(const core::WheelEncoderSample& s) {
  if (!accept(s.stamp, last_encoder_, stats_.encoders, stats_.dropped_encoders)) return false;
  localizer_.add_encoders(s);
  return true;
}

void NavStack::on_imu(const core::ImuSample& s) {
  const double last = imu_.empty() ? -1e300 : imu_.back().stamp;
  double newest = last;
  if (!accept(s.stamp, newest, stats_.imu, stats_.dropped_imu)) return;
  localizer_.add_imu(s);
  imu_.push_back(s);  // the last imu_history seconds, to level each sweep by gravity
  while (!imu_.empty() && imu_.front().stamp < s.stamp - config_.stack.imu_history)
    imu_.pop_front();
}

void NavStack::on_gnss(const core::GnssFix& s) {
  if (accept(s.stamp, last_gnss_, stats_.gnss, stats_.dropped_gnss)) localizer_.add_gnss(s);
}

bool NavStack::on_odometry(const localize::StampedPose& s) {
  const bool ok = external_.push(s);
  ++(ok ? stats_.odometry : stats_.dropped_odometry);
  return ok;
}

void NavStack::measure_period(double t) {
  // The sweep period from successive frames (levelling over the whole sweep, the watchdog).
  if (last_cloud_stamp_ && t - *last_cloud_stamp_ > 0.0 &&
      t - *last_cloud_stamp_ <= config_.stack.max_frame_dt)
    sweep_period_ = t - *last_cloud_stamp_;
  last_cloud_stamp_ = t;
}

bool NavStack::accept_frame(double t) {
  if (!std::isfinite(t) || (last_frame_stamp_ && t <= *last_frame_stamp_) ||
      (pending_ && t <= pending_->stamp()))
    return ++stats_.dropped_frames, false;
  measure_period(t);
  if (pending_) ++stats_.replaced_frames;
  return true;
}

void NavStack::on_cloud(core::PointCloud cloud, std::vector<map::PointLabel> labels) {
  if (accept_frame(cloud.stamp))
    pending_ = std::make_unique<Pending>(Pending{std::move(cloud), std::move(labels)});
}

void NavStack::on_scan(core::Scan2D scan) {
  if (accept_frame(scan.stamp)) pending_ = std::make_unique<Pending>(Pending{std::move(scan), {}});
}

std::optional<core::Pose2> NavStack::T_odom_base(double stamp) const {
  if (config_.stack.odometry == OdometryInput::external) return external_.at(stamp);
  return localizer_.T_odom_base(stamp);
}

core::Twist2 NavStack::twist() const {
  if (config_.stack.odometry == OdometryInput::wheels_imu) return localizer_.latest().twist;
  const auto latest = external_.latest();
  if (!latest) return {};
  core::Twist2 w = latest->twist;
  // A robot's odometry often integrates wheel yaw rate only; the gyro is better (Lan 2021 2.1).
  if (config_.stack.gyro_yaw_rate && !imu_.empty() &&
      std::abs(imu_.back().stamp - latest->stamp) < config_.stack.gyro_max_age &&
      std::isfinite(imu_.back().angular_velocity.z()))
    w.omega = imu_.back().angular_velocity.z();
  return w;
}

core::RowObservation NavStack::detect_frame(Pending& frame, bool& levelled) {
  auto& pipeline = *parts_.pipeline;
  if (auto* scan = std::get_if<core::Scan2D>(&frame.data)) return pipeline.process(*scan);
  const auto& cloud = std::get<core::PointCloud>(frame.data);
  if (config_.stack.level_by_gravity) {
    imu_buf_.assign(imu_.begin(), imu_.end());  // contiguous, no per-frame allocation
    const double t0 = cloud.stamp;
    const auto up = localize::gravity_up(imu_buf_, t0, t0 + sweep_period_, twist().v);
    const double max_tilt = config_.stack.max_level_tilt_deg * std::numbers::pi / 180.0;
    if (up && up->z() >= std::cos(max_tilt)) {  // gravity_up: a unit vector, finite
      levelled = true;
      return pipeline.process(cloud, *up);
    }
  }
  return pipeline.process(cloud);
}

FrameReport NavStack::process_frame(Pending& frame, const std::optional<core::Pose2>& T) {
  FrameReport r;
  r.stamp = frame.stamp();
  if (config_.stack.mode == StackMode::detect) {
    r.observation = detect_frame(frame, r.levelled);
    return r;
  }
  // The frame is stamped at the start of the sweep: the tracker gets the pose of that instant.
  std::optional<core::Pose2> pose = T_odom_base(r.stamp);
  if (!pose) pose = T;
  // Malavazi 2018 sec. 2.3.1: the followed models, moved to this frame, select its points.
  parts_.pipeline->set_data_filter(pose ? parts_.tracker->data_filter(*pose) : std::nullopt);
  r.observation = detect_frame(frame, r.levelled);
  if (!pose) return r;  // no odometry yet: nothing to track against
  // A headland manoeuvre's frames see the rows at every angle: the tracker keeps what it learnt
  // of the field's geometry through them (issue 10: a 0.61 m "lattice" in 2.8 m rows).
  const NavState state = navigator_->state();
  parts_.tracker->set_manoeuvring(state == NavState::turning || state == NavState::headland);
  r.tracking = parts_.tracker->update(r.observation, *pose);
  // Issue 11: the frames of straight stretches measure the odometry's alpha (Bertoglio eq. (2)).
  if (config_.stack.odometry_scale.enabled && config_.stack.odometry == OdometryInput::wheels_imu &&
      !localizer_.gnss_aligned()) {
    const auto alpha =
        scale_.add_frame(parts_.pipeline->last_points(), *pose, localizer_.odometry_alpha());
    if (alpha) localizer_.set_odometry_alpha(*alpha);
  }
  if (place_) estimate_place(frame, r, *pose);
  if (config_.stack.mode == StackMode::track) return r;
  const auto& p = *parts_.pipeline;
  r.end_of_row = end_of_row_->update(p.last_cloud_base(), p.last_points(), *r.tracking,
                                     p.last_sensor_base().cast<float>());
  return r;
}

void NavStack::estimate_place(const Pending& frame, FrameReport& r, const core::Pose2& T) {
  // Emmi 2021's d starts from the lane width: the tracker's row spacing while it follows the
  // rows on both sides (not only in a lane: the first entry needs it; issue 12, BENCHMARK.md).
  const auto& t = r.tracking;
  if (config_.place.lane_width_from_tracker && t && t->status == track::TrackStatus::tracking &&
      t->left >= 0 && t->right >= 0 && t->row_spacing > 0.0)
    place_->set_lane_width(t->row_spacing);
  const auto& p = *parts_.pipeline;
  if (std::holds_alternative<core::Scan2D>(frame.data))
    place_input_.collect(p.last_points(), r.observation);
  else
    place_input_.collect(p.last_cloud_base(), p.last_ground(), frame.labels, r.observation);
  r.place = place_->update(place_input_.points(), place_input_.labels(), T, r.stamp);
}

ObstacleBandConfig NavStack::obstacle_band(const core::PointCloud& cloud_base) {
  ObstacleBandConfig band = config_.stack.obstacles;
  // Issue 10: what the robot drives through is no obstacle (ground_cover.hpp).
  cover_.update(cloud_base, parts_.pipeline->last_ground(),
                {config_.robot.base_to_front, config_.robot.width / 2.0});
  band.min_height = cover_.obstacle_min_height(band.min_height);
  band.max_height = std::max(band.min_height, band.max_height);
  return band;
}

void NavStack::drop_row_canopy(const core::PointCloud& cloud_base, const ObstacleBandConfig& band,
                               const track::RowTracking& tracking,
                               std::vector<Eigen::Vector2f>& points) {
  // Only along a tracked corridor: its rows are what stands at the flanks (issue 10). Like the
  // ground cover, the reach is the field's: kept across corridors and turns, so that the next
  // corridor's first metres, with only headland behind the robot, are served too. It is measured
  // while following the corridor, and also applied while entering one: the end plants' shoots at
  // the flanks stopped 2-7 of the zoo's 100 entries (BENCHMARK.md).
  const NavState state = navigator_->state();
  if ((state != NavState::in_row && state != NavState::entering) ||
      tracking.status == track::TrackStatus::lost)
    return;
  if (state == NavState::in_row)
    canopy_.update(cloud_base, parts_.pipeline->last_ground(),
                   {band.min_height, band.max_height, robot_top()}, tracking.centre_line_base,
                   config_.robot.base_to_front);
  canopy_.drop_canopy(points, tracking.centre_line_base, config_.robot.width / 2.0);
}

double NavStack::robot_top() const {
  const auto& band = config_.stack.obstacles;
  if (band.robot_top > 0.0) return band.robot_top;
  return parts_.pipeline->T_base_lidar().translation().z() + band.sensor_top;
}

NavOutput NavStack::navigate_frame(double stamp, const core::Pose2& T, FrameReport& report) {
  NavInput in;
  in.stamp = stamp;
  in.T_odom_base = T;
  in.twist = twist();
  in.observation = report.observation;
  in.tracking = *report.tracking;
  in.end_of_row = report.end_of_row;
  in.points_base = parts_.pipeline->last_points();
  if (report.place) in.place = report.place->place;
  // A 3D sweep: obstacles by height above the ground, not every point of the detection band.
  const auto& cloud = parts_.pipeline->last_cloud_base();
  in.sweep_3d = !cloud.points.empty();
  std::vector<Eigen::Vector2f> tall;
  if (in.sweep_3d) {
    const ObstacleBandConfig band = obstacle_band(cloud);
    tall = obstacle_points(cloud, parts_.pipeline->last_ground(), band, robot_top());
    drop_row_canopy(cloud, band, *report.tracking, tall);
    in.obstacle_points_base = std::span<const Eigen::Vector2f>(tall);
  } else if (!config_.stack.planar_obstacles) {
    in.obstacle_points_base = std::span<const Eigen::Vector2f>();  // drives over them
  }
  in.robot = config_.robot;
  in.obstacle_distance = control::front_obstacle_distance(
      in.obstacle_points_base.value_or(in.points_base), config_.stack.front);
  NavOutput out = navigator_->step(in);
  if (out.control) {
    control::ControlInput c = *out.control;
    // The controllers integrate over the time since the previous frame (Malavazi 2018 2.3.5).
    const double dt = last_frame_stamp_ ? report.stamp - *last_frame_stamp_ : sweep_period_;
    c.dt = std::clamp(dt, 1e-3, config_.stack.max_frame_dt);
    c.obstacle_distance = in.obstacle_distance;
    out.cmd = parts_.controller->compute(c);
    if (!std::isfinite(out.cmd.v) || !std::isfinite(out.cmd.omega)) out.cmd = {};
  }
  return out;
}

void NavStack::apply(const NavOutput& out) {
  if (out.reset_tracking) {
    parts_.tracker->reset();
    parts_.controller->reset();
  }
  if (out.reset_end_of_row) end_of_row_->reset();
}

core::Twist2 NavStack::limit(const core::Twist2& cmd, double stamp) {
  const double dt =
      last_command_stamp_ ? stamp - *last_command_stamp_ : config_.stack.command_period;
  // A second command at the same instant (a frame's command right after the odometry's, or a
  // ROS timer and a frame on one stamp) may not change the first: apply_limits takes dt 0 as
  // "no acceleration limit", which let the command jump 0.1 -> 0.8 m/s at once (issue 15).
  if (!(dt > 0.0)) return sent_cmd_;
  sent_cmd_ = control::apply_limits(cmd, sent_cmd_, dt, config_.limits);
  return sent_cmd_;
}

NavCommand NavStack::command(double stamp) {
  NavCommand c;
  c.stamp = stamp;
  if (!std::isfinite(stamp) || (last_command_stamp_ && stamp < *last_command_stamp_)) {
    ++stats_.late_commands;  // answered with the last command, nothing advances
    c.cmd = sent_cmd_;
    c.state = navigator_->state();
    c.stop_reason = navigator_->stop_reason();
    return c;
  }
  const std::optional<core::Pose2> T = T_odom_base(stamp);
  NavOutput out;
  if (pending_) {
    const auto t0 = Clock::now();
    std::unique_ptr<Pending> frame = std::move(pending_);
    FrameReport report = process_frame(*frame, T);
    ++stats_.frames;
    if (!held_ && config_.stack.mode == StackMode::navigate && report.tracking && T && finite(*T))
      out = navigate_frame(stamp, *T, report);
    else
      out = navigator_->hold(stamp, T.value_or(core::Pose2()), nav_cmd_);
    watch_hold(report, out, stamp);
    last_frame_stamp_ = report.stamp;
    report.latency = std::chrono::duration<double>(Clock::now() - t0).count();
    if (report.place)
      if (auto k = validated_key(*place_, *report.place)) c.key_locations.push_back(*k);
    c.frame = std::move(report);
  } else {
    out = navigator_->hold(stamp, T.value_or(core::Pose2()), nav_cmd_);
  }
  if (held_ || config_.stack.mode != StackMode::navigate) out.cmd = {};
  if (config_.stack.mode == StackMode::navigate) {
    if (!held_) driven_ = true;
    if (!held_ && resume_refused_) {  // set_held(false) after a carry or a change of corridor
      safe_stop(out, StopReason::moved_while_held, stamp,
                "resumed after the hold: " + *resume_refused_);
      resume_refused_.reset();
    }
    apply(out);
    watch_budget(out, stamp, T);
    if (!terminal(out.state)) watch_odometry(out, stamp, T);
    watch_inputs(c, out, stamp);
  }
  if (!T || terminal(out.state)) out.cmd = {};  // never drive without a pose
  nav_cmd_ = out.cmd;
  c.cmd = limit(out.cmd, stamp);
  // Stale inputs or a stop: zero at once, not ramped down by the acceleration limit (the
  // robot's own drive brakes; a ramp would keep moving for max_speed / max_accel seconds).
  if (held_ || c.health != InputHealth::ok || terminal(out.state)) c.cmd = sent_cmd_ = {};
  last_command_stamp_ = stamp;
  c.state = out.state;
  c.stop_reason = out.stop_reason;
  c.corridor = out.corridor;
  c.served = out.served;
  c.events = std::move(out.events);
  c.row_end_points = std::move(out.row_end_points);
  if (place_) c.place = place_->place();
  return c;
}

}  // namespace rownav::navigate
