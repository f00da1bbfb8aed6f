#include "rownav/localize/localizer.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::localize {

void LocalizerConfig::validate() const {
  core::validate_nested(odometry, "odometry");
  core::validate_nested(ekf, "ekf");
  core::check_positive(history, "history");
  core::check_non_negative(max_extrapolation, "max_extrapolation");
  core::check_positive(gnss_align_distance, "gnss_align_distance");
  core::check_positive(gnss_realign_after, "gnss_realign_after");
}

Localizer::Localizer(const LocalizerConfig& config)
    : config_(config), odometry_(config.odometry), ekf_(config.ekf) {
  config_.validate();
}

void Localizer::record() {
  PoseEstimate e = latest();
  if (!history_.empty() && history_.back().stamp >= e.stamp)
    history_.back() = e;  // several sensors at one stamp: keep the last update
  else
    history_.push_back(e);
  while (history_.size() > 2 && history_.front().stamp < e.stamp - config_.history)
    history_.pop_front();
}

void Localizer::add_encoders(const core::WheelEncoderSample& s) {
  const auto twist = odometry_.add(s);
  if (!twist) {
    // The first sample starts the filter so a robot standing still still gets a pose.
    if (!ekf_.initialized() && std::isfinite(s.stamp)) {
      ekf_.reset(s.stamp, start_);
      record();
    }
    return;
  }
  // Exactly zero: no tick changed on either wheel, the robot stands still (zero-velocity update).
  const bool stationary = twist->v == 0.0 && twist->omega == 0.0;
  if (ekf_.update_odometry(s.stamp, *twist, stationary)) record();
}

void Localizer::add_imu(const core::ImuSample& s) {
  if (!config_.use_imu) return;
  if (ekf_.update_gyro(s.stamp, s.angular_velocity.z())) record();
}

std::optional<Eigen::Vector2d> Localizer::gnss_to_odom(const core::GnssFix& s) {
  const Eigen::Vector2d enu = s.position_enu.head<2>();
  if (!gnss_anchor_) {
    gnss_anchor_.emplace(enu, ekf_.pose().translation());
    return std::nullopt;
  }
  if (!T_odom_enu_) {
    const auto& [e0, o0] = *gnss_anchor_;
    const Eigen::Vector2d de = enu - e0, dodom = ekf_.pose().translation() - o0;
    if (de.norm() < config_.gnss_align_distance || dodom.norm() < 0.5 * de.norm())
      return std::nullopt;
    // The travelled chord fixes the rotation ENU -> odom; the current fix maps onto the current
    // pose, so the odometry's scale error since the first fix does not become a position jump.
    const double rot = std::atan2(dodom.y(), dodom.x()) - std::atan2(de.y(), de.x());
    const core::Pose2 R(0.0, 0.0, rot);
    const Eigen::Vector2d t = ekf_.pose().translation() - R * enu;
    T_odom_enu_ = core::Pose2(t.x(), t.y(), rot);
  }
  return *T_odom_enu_ * enu;
}

void Localizer::add_gnss(const core::GnssFix& s) {
  if (!config_.use_gnss || !ekf_.initialized()) return;
  if (!s.valid) {
    ++stats_.gnss_invalid;
    return;
  }
  if (!s.position_enu.allFinite() || !std::isfinite(s.horizontal_std) || !std::isfinite(s.stamp)) {
    ++stats_.outliers;
    return;
  }
  const auto p = gnss_to_odom(s);
  if (!p) return;
  const int outliers = ekf_.rejected_outliers();
  if (ekf_.update_position(s.stamp, *p, s.horizontal_std)) {
    ++stats_.gnss_used;
    gnss_gated_in_row_ = 0;
    record();
  } else if (ekf_.rejected_outliers() > outliers &&
             ++gnss_gated_in_row_ >= config_.gnss_realign_after) {
    gnss_anchor_.reset();  // consistently far from the estimate: align again
    T_odom_enu_.reset();
    gnss_gated_in_row_ = 0;
  }
}

PoseEstimate Localizer::latest() const {
  PoseEstimate e;
  e.valid = ekf_.initialized();
  e.stamp = ekf_.stamp();
  e.T_odom_base = ekf_.pose();
  e.covariance = ekf_.covariance().topLeftCorner<3, 3>();
  e.twist = ekf_.twist();
  return e;
}

std::optional<PoseEstimate> Localizer::estimate_at(double stamp) const {
  if (history_.empty() || !std::isfinite(stamp) || stamp < history_.front().stamp)
    return std::nullopt;
  const PoseEstimate& last = history_.back();
  if (stamp >= last.stamp) {
    if (stamp - last.stamp > config_.max_extrapolation) return std::nullopt;
    PoseEstimate e = last;
    e.T_odom_base = last.T_odom_base * twist_increment(last.twist, stamp - last.stamp);
    e.stamp = stamp;
    return e;
  }
  const auto it = std::upper_bound(history_.begin(), history_.end(), stamp,
                                   [](double t, const PoseEstimate& e) { return t < e.stamp; });
  const PoseEstimate& b = *it;
  const PoseEstimate& a = *std::prev(it);
  PoseEstimate e = a;
  e.stamp = stamp;
  e.T_odom_base =
      core::interpolate(a.T_odom_base, b.T_odom_base, (stamp - a.stamp) / (b.stamp - a.stamp));
  return e;
}

std::optional<core::Pose2> Localizer::T_odom_base(double stamp) const {
  const auto e = estimate_at(stamp);
  if (!e) return std::nullopt;
  return e->T_odom_base;
}

void Localizer::reset(const core::Pose2& T_odom_base) {
  start_ = T_odom_base;
  odometry_.reset(T_odom_base);
  if (ekf_.initialized()) ekf_.reset(ekf_.stamp(), T_odom_base);
  history_.clear();
  if (ekf_.initialized()) record();
  gnss_anchor_.reset();
  T_odom_enu_.reset();
  gnss_gated_in_row_ = 0;
}

LocalizerStats Localizer::stats() const {
  LocalizerStats s = stats_;
  s.encoder_time_rejected = odometry_.rejected_time();
  s.encoder_jumps = odometry_.rejected_jumps();
  s.time_rejected = ekf_.rejected_time();
  s.outliers += ekf_.rejected_outliers();
  return s;
}

}  // namespace rownav::localize
