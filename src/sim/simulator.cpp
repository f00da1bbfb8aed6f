#include "rownav/sim/simulator.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::sim {

namespace {

Eigen::Isometry3d lerp(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond(a.linear()).slerp(s, Eigen::Quaterniond(b.linear())).toRotationMatrix();
  T.translation() = (1.0 - s) * a.translation() + s * b.translation();
  return T;
}

}  // namespace

void SimConfig::validate() const {
  core::validate_nested(lidar, "lidar");
  core::validate_nested(encoders, "encoders");
  core::validate_nested(imu, "imu");
  core::validate_nested(gnss, "gnss");
  core::check_range(physics_rate_hz, 10.0, 10000.0, "physics_rate_hz");
  core::check_range(ground_truth_rate_hz, 0.1, physics_rate_hz, "ground_truth_rate_hz");
  core::check_positive(truth_reach, "truth_reach");
  core::validate_nested(faults, "faults");
  core::validate_nested(ground_contact, "ground_contact");
}

Simulator::Simulator(const Field& field, const RobotConfig& robot, const SimConfig& config,
                     const core::Pose2& start)
    : field_(field),
      config_(config),
      dt_(1.0 / config.physics_rate_hz),
      robot_(robot, config.seed * 7919 + 1, start),
      caster_(field.mesh),
      lidar_(config.lidar, config.seed * 7919 + 2),
      truth_(field),
      crush_(field),
      encoders_(config.encoders, config.seed * 7919 + 3),
      imu_(config.imu, config.seed * 7919 + 4),
      gnss_(config.gnss, config.seed * 7919 + 5),
      faults_(config.faults, config.seed * 7919 + 6 + config.faults.seed * 104729) {
  config_.validate();
  // Proprioception and truth sample n (n >= 1) is due at n / rate: the state at t = 0 is the
  // start pose, not a measurement, and starting at n = 0 emitted an extra sample at the first
  // step (t = dt), so the first interval was dt instead of 1 / rate (50 Hz encoders: 0.01,
  // 0.02, 0.04, ...; 101 samples in 2 s). A sweep n still starts at n / rate (n >= 0).
  n_encoders_ = n_imu_ = n_gnss_ = n_truth_ = 1;
  history_.emplace_back(0.0, pose3d(start));
  update_truth();
}

Eigen::Isometry3d Simulator::pose3d(const core::Pose2& T_world_base) const {
  return rest_on_ground(field_.terrain, robot_.config(), T_world_base, config_.ground_contact);
}

Eigen::Isometry3d Simulator::pose_at(double t) const {
  // The history holds every physics step since before the current sweep began.
  if (t <= history_.front().first) return history_.front().second;
  for (std::size_t i = 1; i < history_.size(); ++i) {
    const auto& [t1, T1] = history_[i];
    if (t <= t1) {
      const auto& [t0, T0] = history_[i - 1];
      return lerp(T0, T1, (t - t0) / std::max(t1 - t0, 1e-9));
    }
  }
  return history_.back().second;
}

void Simulator::update_truth() {
  const RobotState& s = robot_.state();
  truth_now_ = truth_.at(s.pose, s.stamp, config_.truth_reach);
  // Roll / pitch of the base on the terrain (ZYX convention: R = Rz(yaw) Ry(pitch) Rx(roll)).
  const Eigen::Isometry3d& T = history_.back().second;
  const Eigen::Matrix3d& R = T.linear();
  truth_now_.z = T.translation().z();
  truth_now_.pitch = -std::asin(std::clamp(R(2, 0), -1.0, 1.0));
  truth_now_.roll = std::atan2(R(2, 1), R(2, 2));
  truth_now_.twist = s.twist;
  truth_now_.plants_crushed = crush_.total();
}

namespace {

// True when the next sample of a stream at `rate` is due at time t (sample n is due at n / rate).
bool due(std::int64_t& n, double rate, double t) {
  if (t + 1e-9 < static_cast<double>(n) / rate) return false;
  ++n;
  return true;
}

}  // namespace

void Simulator::step(const core::Twist2& cmd, SimSink& sink) {
  // Step to (n + 1) dt rather than adding dt, so stamps stay on the grid instead of drifting.
  ++n_steps_;
  robot_.step(cmd, static_cast<double>(n_steps_) * dt_ - robot_.state().stamp);
  step_carry();
  const double t = time();
  history_.emplace_back(t, pose3d(robot_.state().pose));
  const double keep = 2.0 / config_.lidar.rate_hz + 0.1;
  while (history_.size() > 2 && history_[1].first < t - keep) history_.pop_front();
  crush_.update(robot_.footprint_world());
  update_truth();
  // Without faults the samples go straight to the sink (bit-identical to a run before faults).
  SimSink* out = &sink;
  if (config_.faults.any()) {
    faults_.begin_step(t, robot_.state().pose, sink);
    out = &faults_;
    update_person(t);
  }
  emit_proprioception(*out);
  emit_lidar(*out);
  if (due(n_truth_, config_.ground_truth_rate_hz, t)) out->on_ground_truth(truth_now_);
  last_twist_ = robot_.state().twist;
}

void Simulator::carry(const core::Pose2& delta_base, double speed, double yaw_rate) {
  const core::Pose2& T = robot_.state().pose;
  Carry c;
  c.remaining = T.rotation() * Eigen::Vector2d(delta_base.x, delta_base.y);
  c.turn = delta_base.theta;
  c.speed = std::isfinite(speed) ? speed : 0.0;
  c.yaw_rate = std::isfinite(yaw_rate) ? yaw_rate : 0.0;
  carry_ = c;
}

void Simulator::step_carry() {
  if (!carry_) return;
  Carry& c = *carry_;
  // The share of what is left that this step moves: the slower of the line and the turn.
  const double run = c.remaining.norm(), turn = std::abs(c.turn);
  double share = 1.0;
  if (run > 0.0 && c.speed > 0.0) share = std::min(share, c.speed * dt_ / run);
  if (turn > 0.0 && c.yaw_rate > 0.0) share = std::min(share, c.yaw_rate * dt_ / turn);
  const core::Pose2& T = robot_.state().pose;
  const Eigen::Vector2d move = share * c.remaining;
  robot_.place({T.x + move.x(), T.y + move.y(), T.theta + share * c.turn});
  c.remaining -= move;
  c.turn -= share * c.turn;
  if (share >= 1.0) carry_.reset();
}

std::optional<ObstacleBox> Simulator::person_at(double t) const {
  auto box = faults_.person_at(t);
  if (box) box->base.z() = field_.terrain.height(box->base.x(), box->base.y());
  return box;
}

void Simulator::update_person(double t) {
  const auto box = person_at(t);
  if (!box) return;
  // A person is not a plant: touching one is a collision, measured as a clearance.
  truth_now_.obstacle_clearance = clearance(robot_.footprint_world(), footprint(*box));
}

void Simulator::emit_proprioception(SimSink& sink) {
  const double t = time();
  const RobotState& s = robot_.state();
  if (due(n_encoders_, config_.encoders.rate_hz, t)) {
    core::WheelEncoderSample e = encoders_.sample(s);
    if (robot_.config().drive != DriveKind::ackermann) e.steering_angle = 0.0;  // no such sensor
    sink.on_encoders(e);
  }
  if (due(n_imu_, config_.imu.rate_hz, t))
    sink.on_imu(imu_.sample(s, truth_now_.roll, truth_now_.pitch));
  if (config_.gnss.enabled && due(n_gnss_, config_.gnss.rate_hz, t)) {
    const Eigen::Vector3d p(s.pose.x, s.pose.y, truth_now_.z);
    sink.on_gnss(gnss_.sample(t, p, truth_now_.place));
  }
}

void Simulator::emit_lidar(SimSink& sink) {
  // Sweep n starts at n / rate and is complete (emitted) one period later.
  const double rate = config_.lidar.rate_hz;
  const double start = static_cast<double>(n_sweeps_) / rate;
  if (time() + 1e-9 < static_cast<double>(n_sweeps_ + 1) / rate) return;
  ++n_sweeps_;
  const PoseAt pose = [this](double t) { return pose_at(t); };
  std::vector<SurfaceClass> labels;
  // The person where it is halfway through the sweep (it moves ~5 cm in half a 10 Hz sweep).
  std::vector<ObstacleBox> boxes;
  if (const auto box = person_at(start + 0.5 / rate)) boxes.push_back(*box);
  lidar_.set_obstacles(std::move(boxes));
  if (config_.lidar.kind == LidarKind::spinning) {
    sink.on_cloud(lidar_.sweep(caster_, pose, start, &labels), labels);
  } else {
    sink.on_scan(lidar_.scan(caster_, pose, start, &labels), labels);
  }
}

}  // namespace rownav::sim
