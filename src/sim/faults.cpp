// The simulator's fault injector (sim/faults.hpp, issue 13).
#include "rownav/sim/faults.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rownav/core/angle.hpp"

namespace rownav::sim {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

double uniform(std::mt19937_64& rng) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); }

/// Keeps each point (and its label) with probability 1 - fraction.
void lose(core::PointCloud& c, std::vector<SurfaceClass>& labels, double fraction,
          std::mt19937_64& rng) {
  const bool labelled = labels.size() == c.points.size();
  std::size_t m = 0;
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    if (uniform(rng) < fraction) continue;
    c.points[m] = c.points[i];
    if (labelled) labels[m] = labels[i];
    ++m;
  }
  c.points.resize(m);
  if (labelled) labels.resize(m);
}

void lose(core::Scan2D& s, std::vector<SurfaceClass>& labels, double fraction,
          std::mt19937_64& rng) {
  for (std::size_t i = 0; i < s.ranges.size(); ++i)
    if (uniform(rng) < fraction) {
      s.ranges[i] = kInf;  // no return
      if (i < labels.size()) labels[i] = SurfaceClass::other;
    }
}

/// NaN, or +-Inf with probability inf_share.
float poison_value(double inf_share, std::mt19937_64& rng) {
  if (uniform(rng) >= inf_share) return kNaN;
  return uniform(rng) < 0.5 ? kInf : -kInf;
}

void poison(core::PointCloud& c, const CloudNanFault& f, std::mt19937_64& rng) {
  for (auto& p : c.points) {
    if (uniform(rng) >= f.fraction) continue;
    const float v = poison_value(f.inf_share, rng);
    // A corrupted buffer spoils whole points or single coordinates: both happen.
    const double which = uniform(rng);
    if (which < 0.25) p.x = v;
    else if (which < 0.5) p.y = v;
    else if (which < 0.75) p.z = v;
    else p.x = p.y = p.z = v;
  }
}

void poison(core::Scan2D& s, const CloudNanFault& f, std::mt19937_64& rng) {
  for (auto& r : s.ranges)
    if (uniform(rng) < f.fraction) r = poison_value(f.inf_share, rng);
}

double& stamp_of(std::variant<core::PointCloud, core::Scan2D>& d) {
  return std::visit([](auto& x) -> double& { return x.stamp; }, d);
}

}  // namespace

FaultInjector::FaultInjector(const FaultsConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
}

void FaultInjector::begin_step(double t, const core::Pose2& robot, SimSink& out) {
  out_ = &out;
  now_ = t;
  while (!held_.empty() && held_.front().release <= t + 1e-9) {
    forward(held_.front());
    held_.pop_front();
  }
  const PersonFault& p = config_.person;
  if (p.enabled && !person_ && t >= p.start) {
    // Sets off beside the robot's line, `ahead` in front of where the robot is now.
    const Eigen::Vector2d fwd(std::cos(robot.theta), std::sin(robot.theta)), left(-fwd.y(), fwd.x());
    PersonPath path;
    path.centre = robot.translation() + p.ahead * fwd;
    path.from = path.centre + p.side * left;
    path.dir = p.side >= 0.0 ? Eigen::Vector2d(-left) : left;
    path.yaw = robot.theta;
    person_ = path;
  }
}

std::optional<ObstacleBox> FaultInjector::person_at(double t) const {
  if (!person_) return std::nullopt;
  const PersonFault& p = config_.person;
  const double in = std::abs(p.side);  // walked to reach the robot's line
  const double walk_in = (t - p.start) * p.speed;
  // Walks in, stands on the line until start + duration, walks on as far again and stays.
  double s = std::min(walk_in, in);
  if (t > p.end()) s = std::max(s, std::min(in + (t - p.end()) * p.speed, 2.0 * in));
  ObstacleBox box;
  box.yaw = person_->yaw;
  box.size = p.size;
  const Eigen::Vector2d xy = person_->from + std::max(0.0, s) * person_->dir;
  box.base = Eigen::Vector3d(xy.x(), xy.y(), 0.0);
  return box;
}

void FaultInjector::on_cloud(const core::PointCloud& c, const std::vector<SurfaceClass>& labels) {
  lidar_frame(Frame{c, labels, now_});
}

void FaultInjector::on_scan(const core::Scan2D& s, const std::vector<SurfaceClass>& labels) {
  lidar_frame(Frame{s, labels, now_});
}

void FaultInjector::lidar_frame(Frame f) {
  const double t = now_;
  if (config_.lidar_dropout.active(t)) return;
  const LidarRateFault& rate = config_.lidar_rate;
  if (rate.active(t)) {
    if (rate_count_++ % rate.keep_every != 0) return;  // a slow LiDAR: this frame never comes
    f.release = t + rate.jitter * uniform(rng_);
  } else {
    rate_count_ = 0;
  }
  corrupt(f);
  restamp(f);
  repeat(std::move(f));
}

void FaultInjector::corrupt(Frame& f) {
  const double t = now_;
  if (config_.point_loss.active(t))
    std::visit([&](auto& d) { lose(d, f.labels, config_.point_loss.fraction, rng_); }, f.data);
  if (config_.cloud_nan.active(t))
    std::visit([&](auto& d) { poison(d, config_.cloud_nan, rng_); }, f.data);
}

void FaultInjector::restamp(Frame& f) {
  const double t = now_;
  double& stamp = stamp_of(f.data);
  if (config_.lidar_time_backwards.active(t)) stamp -= config_.lidar_time_backwards.offset;
  if (config_.lidar_stamp_stall.active(t)) {
    if (!stall_stamp_) stall_stamp_ = stamp;
    stamp = *stall_stamp_;
  } else {
    stall_stamp_.reset();
  }
}

void FaultInjector::repeat(Frame f) {
  const FrameRepeatFault& r = config_.frame_repeat;
  if (!r.active(now_)) {
    if (swapped_) deliver(std::move(*swapped_)), swapped_.reset();
    return deliver(std::move(f));
  }
  if (r.mode == RepeatMode::duplicate) {
    deliver(f);
    return deliver(std::move(f));
  }
  if (!swapped_) return void(swapped_ = std::move(f));  // held until the next one is out
  deliver(std::move(f));
  deliver(std::move(*swapped_));
  swapped_.reset();
}

void FaultInjector::deliver(Frame f) {
  // Frames leave in order: none overtakes one held back before it.
  f.release = std::max(f.release, last_release_);
  last_release_ = f.release;
  if (f.release <= now_ + 1e-9 && held_.empty()) return forward(f);
  held_.push_back(std::move(f));
}

void FaultInjector::forward(const Frame& f) {
  if (!out_) return;
  if (const auto* c = std::get_if<core::PointCloud>(&f.data)) return out_->on_cloud(*c, f.labels);
  out_->on_scan(std::get<core::Scan2D>(f.data), f.labels);
}

void FaultInjector::on_encoders(const core::WheelEncoderSample& s) {
  const double t = now_;
  if (!last_true_) left_ = double(s.left_ticks), right_ = double(s.right_ticks);
  const double dl = last_true_ ? double(s.left_ticks - last_true_->left_ticks) : 0.0;
  const double dr = last_true_ ? double(s.right_ticks - last_true_->right_ticks) : 0.0;
  last_true_ = s;
  const EncoderFault& e = config_.encoder;
  double factor = config_.odometry_slip.active(t) ? config_.odometry_slip.factor : 1.0;
  if (e.active(t) && e.mode == EncoderFaultMode::freeze) factor = 0.0;
  left_ += factor * dl, right_ += factor * dr;
  core::WheelEncoderSample out = s;
  const double q = e.active(t) && e.mode == EncoderFaultMode::coarse ? e.coarse_ticks : 1.0;
  out.left_ticks = static_cast<std::int64_t>(std::floor(left_ / q) * q);
  out.right_ticks = static_cast<std::int64_t>(std::floor(right_ / q) * q);
  if (out_) out_->on_encoders(out);
}

void FaultInjector::on_imu(const core::ImuSample& s) {
  core::ImuSample out = s;
  if (config_.gyro_bias.active(now_))
    out.angular_velocity.z() += core::deg2rad(config_.gyro_bias.bias_deg_s);
  if (out_) out_->on_imu(out);
}

void FaultInjector::on_gnss(const core::GnssFix& s) {
  core::GnssFix out = s;
  if (out.valid && config_.gnss_jump.active(now_))
    out.position_enu.head<2>() += config_.gnss_jump.offset;
  if (out_) out_->on_gnss(out);
}

void FaultInjector::on_ground_truth(const GroundTruth& g) {
  if (out_) out_->on_ground_truth(g);
}

void FaultsConfig::validate() const {
  core::validate_nested(lidar_dropout, "lidar_dropout");
  core::validate_nested(lidar_rate, "lidar_rate");
  core::validate_nested(cloud_nan, "cloud_nan");
  core::validate_nested(point_loss, "point_loss");
  core::validate_nested(frame_repeat, "frame_repeat");
  core::validate_nested(lidar_time_backwards, "lidar_time_backwards");
  core::validate_nested(lidar_stamp_stall, "lidar_stamp_stall");
  core::validate_nested(odometry_slip, "odometry_slip");
  core::validate_nested(encoder, "encoder");
  core::validate_nested(gyro_bias, "gyro_bias");
  core::validate_nested(gnss_jump, "gnss_jump");
  core::validate_nested(person, "person");
}

bool FaultsConfig::any() const {
  return lidar_dropout.enabled || lidar_rate.enabled || cloud_nan.enabled || point_loss.enabled ||
         frame_repeat.enabled || lidar_time_backwards.enabled || lidar_stamp_stall.enabled ||
         odometry_slip.enabled || encoder.enabled || gyro_bias.enabled || gnss_jump.enabled ||
         person.enabled;
}

}  // namespace rownav::sim
