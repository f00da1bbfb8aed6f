#include "rownav/localize/pose_ekf.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "rownav/core/angle.hpp"

namespace rownav::localize {
namespace {

constexpr int kX = 0, kY = 1, kTh = 2, kV = 3, kW = 4, kB = 5;

double sq(double x) {
  return x * x;
}

}  // namespace

void PoseEkfConfig::validate() const {
  core::check_positive(accel_noise, "accel_noise");
  core::check_positive(yaw_accel_noise, "yaw_accel_noise");
  core::check_non_negative(position_noise, "position_noise");
  core::check_non_negative(gyro_bias_random_walk, "gyro_bias_random_walk");
  core::check_non_negative(initial_gyro_bias_std, "initial_gyro_bias_std");
  core::check_positive(odom_speed_std, "odom_speed_std");
  core::check_non_negative(odom_speed_rel_std, "odom_speed_rel_std");
  core::check_positive(odom_omega_std, "odom_omega_std");
  core::check_non_negative(odom_omega_rel_std, "odom_omega_rel_std");
  core::check_positive(stationary_std, "stationary_std");
  core::check_positive(gyro_std, "gyro_std");
  core::check_positive(gnss_gate, "gnss_gate");
  core::check_positive(min_gnss_std, "min_gnss_std");
  core::check_non_negative(late_tolerance, "late_tolerance");
}

PoseEkf::PoseEkf(const PoseEkfConfig& config) : config_(config) {
  config_.validate();
  P_(kB, kB) = sq(config_.initial_gyro_bias_std);
}

void PoseEkf::reset(double stamp, const core::Pose2& T) {
  const double bias = x_(kB), bias_var = P_(kB, kB);
  x_.setZero();
  P_.setZero();
  x_ << T.x, T.y, T.theta, 0.0, 0.0, bias;
  P_(kV, kV) = sq(config_.odom_speed_std);
  P_(kW, kW) = sq(config_.odom_omega_std);
  P_(kB, kB) = initialized_ ? bias_var : sq(config_.initial_gyro_bias_std);
  stamp_ = stamp;
  initialized_ = true;
}

void PoseEkf::predict(double dt) {
  const double th = x_(kTh), v = x_(kV), w = x_(kW);
  Cov F = Cov::Identity();
  F(kTh, kW) = dt;
  if (config_.motion_model == MotionModel::constant_turn && std::abs(w * dt) > 1e-6) {
    // Lan 2021 eq. (9)-(10): exact arc at constant speed and turn rate.
    const double th1 = th + w * dt, s0 = std::sin(th), c0 = std::cos(th);
    const double s1 = std::sin(th1), c1 = std::cos(th1);
    x_(kX) += v / w * (s1 - s0);
    x_(kY) += v / w * (c0 - c1);
    F(kX, kTh) = v / w * (c1 - c0);
    F(kX, kV) = (s1 - s0) / w;
    F(kX, kW) = v * c1 * dt / w - v * (s1 - s0) / (w * w);
    F(kY, kTh) = v / w * (s1 - s0);
    F(kY, kV) = (c0 - c1) / w;
    F(kY, kW) = v * s1 * dt / w - v * (c0 - c1) / (w * w);
  } else {
    // Lan 2021 eq. (1)-(3): first-order step along the current heading (also the w -> 0 limit of
    // the constant-turn model).
    const double c = std::cos(th), s = std::sin(th);
    x_(kX) += v * c * dt;
    x_(kY) += v * s * dt;
    F(kX, kTh) = -v * s * dt;
    F(kX, kV) = c * dt;
    F(kY, kTh) = v * c * dt;
    F(kY, kV) = s * dt;
  }
  x_(kTh) = core::wrap_angle(th + w * dt);
  Cov Q = Cov::Zero();
  Q(kX, kX) = Q(kY, kY) = sq(config_.position_noise) * dt;
  Q(kV, kV) = sq(config_.accel_noise) * dt;
  Q(kW, kW) = sq(config_.yaw_accel_noise) * dt;
  Q(kB, kB) = sq(config_.gyro_bias_random_walk) * dt;
  P_ = F * P_ * F.transpose() + Q;
}

bool PoseEkf::predict_to(double stamp) {
  if (!std::isfinite(stamp)) {
    ++rejected_outliers_;
    return false;
  }
  if (!initialized_) reset(stamp);
  const double dt = stamp - stamp_;
  if (dt < -config_.late_tolerance) {
    ++rejected_time_;
    return false;
  }
  if (dt > 0.0) {
    predict(dt);
    stamp_ = stamp;
  }
  return true;
}

template <int M>
void PoseEkf::correct(const Eigen::Matrix<double, M, 1>& y, const Eigen::Matrix<double, M, 6>& H,
                      const Eigen::Matrix<double, M, M>& R, bool update_pose,
                      bool update_bias) {
  const Eigen::Matrix<double, M, M> S = H * P_ * H.transpose() + R;
  Eigen::Matrix<double, 6, M> K = P_ * H.transpose() * S.inverse();
  // Velocity measurements (wheels, gyro) correct the velocity and bias states only: through
  // the cross-covariance the optimal gain would also shift x, y, theta, which made the pose
  // slide sideways while the robot rotated in place (closed-loop demo). The pose stays the
  // integral of the estimated velocities (a Schmidt / consider update; the Joseph form below
  // is valid for any gain).
  if (!update_pose) K.template topRows<3>().setZero();
  if (!update_bias) K.row(kB).setZero();
  x_ += K * y;
  x_(kTh) = core::wrap_angle(x_(kTh));
  // Joseph form keeps P symmetric positive semi-definite.
  const Cov I_KH = Cov::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
}

bool PoseEkf::update_odometry(double stamp, const core::Twist2& t, bool stationary) {
  if (!std::isfinite(t.v) || !std::isfinite(t.omega)) {
    ++rejected_outliers_;
    return false;
  }
  if (!predict_to(stamp)) return false;
  Eigen::Matrix<double, 2, 6> H = Eigen::Matrix<double, 2, 6>::Zero();
  H(0, kV) = 1.0;
  H(1, kW) = 1.0;
  const double sv = stationary
                        ? config_.stationary_std
                        : config_.odom_speed_std + config_.odom_speed_rel_std * std::abs(t.v);
  const double sw = stationary
                        ? config_.stationary_std
                        : config_.odom_omega_std + config_.odom_omega_rel_std * std::abs(t.omega);
  const Eigen::Vector2d y(t.v - x_(kV), t.omega - x_(kW));
  // A moving robot's wheel yaw rate carries the skid-steer ICR scale error (tens of percent):
  // it must not teach the gyro bias; a standing robot's zero twist is exact and does (rownav).
  correct<2>(y, H, Eigen::Vector2d(sq(sv), sq(sw)).asDiagonal().toDenseMatrix(), false,
             stationary);
  return true;
}

bool PoseEkf::update_gyro(double stamp, double yaw_rate) {
  if (!std::isfinite(yaw_rate)) {
    ++rejected_outliers_;
    return false;
  }
  if (!predict_to(stamp)) return false;
  Eigen::Matrix<double, 1, 6> H = Eigen::Matrix<double, 1, 6>::Zero();
  H(0, kW) = 1.0;
  H(0, kB) = 1.0;
  Eigen::Matrix<double, 1, 1> y, R;
  y(0) = yaw_rate - (x_(kW) + x_(kB));
  R(0) = sq(config_.gyro_std);
  correct<1>(y, H, R, false, true);
  return true;
}

bool PoseEkf::update_position(double stamp, const Eigen::Vector2d& p, double std) {
  if (!p.allFinite() || !std::isfinite(std)) {
    ++rejected_outliers_;
    return false;
  }
  if (!predict_to(stamp)) return false;
  Eigen::Matrix<double, 2, 6> H = Eigen::Matrix<double, 2, 6>::Zero();
  H(0, kX) = 1.0;
  H(1, kY) = 1.0;
  const double s = std::max(std, config_.min_gnss_std);
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * sq(s);
  const Eigen::Vector2d y = p - x_.head<2>();
  const Eigen::Matrix2d S = H * P_ * H.transpose() + R;
  if (y.dot(S.ldlt().solve(y)) > config_.gnss_gate) {  // robust: a multipath jump is gated out
    ++rejected_outliers_;
    return false;
  }
  correct<2>(y, H, R, true, true);
  return true;
}

}  // namespace rownav::localize
