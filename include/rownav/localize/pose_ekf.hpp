#pragma once
/// @file pose_ekf.hpp Planar pose EKF fusing wheel odometry, IMU yaw rate and (optionally) GNSS
/// positions (Lan 2021, 001_b5f4b55a1b95775a.txt sec. 2.1: EKF fusion of odometry, IMU and GNSS
/// with constant-velocity and constant-turn motion models).
///
/// State [x, y, theta, v, omega, b_g]: odom-frame pose, body speed and yaw rate, and the gyro
/// z bias (rownav: a MEMS turn-on bias of a few mrad/s integrates to degrees of heading per
/// minute; it is observable while standing still and from the odometry yaw rate).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::localize {

/// Process model of the prediction step (Lan 2021 sec. 2.1).
/// constant_velocity: first-order (straight chord) step, eq. (1)-(3) written for a heading state.
/// constant_turn: exact arc at constant speed and yaw rate, eq. (9)-(14).
enum class MotionModel : std::uint8_t { constant_velocity, constant_turn };

/// EKF noise parameters and options.
struct PoseEkfConfig {
  MotionModel motion_model = MotionModel::constant_turn;  ///< prediction model
  double accel_noise = 1.0;      ///< [m/s^2] white acceleration driving v (robot max_accel)
  double yaw_accel_noise = 2.0;  ///< [rad/s^2] white yaw acceleration driving omega
  double position_noise = 0.05;  ///< [m/sqrt(s)] position diffusion: odometry scale / slip errors
  /// [rad/s/sqrt(s)] gyro bias random walk (MEMS datasheet; simulator default 2e-5)
  double gyro_bias_random_walk = 2.0e-5;
  double initial_gyro_bias_std = 0.01;  ///< [rad/s] prior std of the gyro turn-on bias
  double odom_speed_std = 0.05;         ///< [m/s] odometry speed noise, plus the relative term
  double odom_speed_rel_std = 0.05;     ///< [-] odometry speed noise per m/s (slip)
  double odom_omega_std = 0.05;         ///< [rad/s] odometry yaw-rate noise, plus relative term
  /// [-] odometry yaw-rate noise per rad/s: skid-steer ICR errors reach tens of percent
  /// (Bertoglio 2023 eq. (2) parameters differ from the ideal ones)
  double odom_omega_rel_std = 0.5;
  /// [m/s, rad/s] noise of a zero twist when no wheel moved (zero-velocity update)
  double stationary_std = 0.001;
  double gyro_std = 0.003;     ///< [rad/s] gyro white noise per sample (2e-4 /sqrt(Hz) at 100 Hz)
  double gnss_gate = 13.8;     ///< [-] Mahalanobis^2 gate on GNSS fixes (chi^2, 2 dof, 99.9 %)
  double min_gnss_std = 0.02;  ///< [m] floor of a fix's reported horizontal std
  /// [s] a measurement up to this much older than the filter time (sensor streams interleave
  /// with different latencies) is applied at the filter time; older ones are ignored (rownav)
  double late_tolerance = 0.05;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("motion_model", s.motion_model);
    v("accel_noise", s.accel_noise);
    v("yaw_accel_noise", s.yaw_accel_noise);
    v("position_noise", s.position_noise);
    v("gyro_bias_random_walk", s.gyro_bias_random_walk);
    v("initial_gyro_bias_std", s.initial_gyro_bias_std);
    v("odom_speed_std", s.odom_speed_std);
    v("odom_speed_rel_std", s.odom_speed_rel_std);
    v("odom_omega_std", s.odom_omega_std);
    v("odom_omega_rel_std", s.odom_omega_rel_std);
    v("stationary_std", s.stationary_std);
    v("gyro_std", s.gyro_std);
    v("gnss_gate", s.gnss_gate);
    v("min_gnss_std", s.min_gnss_std);
    v("late_tolerance", s.late_tolerance);
  }
  void validate() const;
};

/// The EKF. Measurements are applied at their stamps after predicting to them; a stamp more than
/// late_tolerance before the filter time is ignored (counted). Never throws on data; non-finite
/// inputs are dropped.
class PoseEkf {
 public:
  using State = Eigen::Matrix<double, 6, 1>;
  using Cov = Eigen::Matrix<double, 6, 6>;

  /// Validates `config` (throws std::invalid_argument naming the field).
  explicit PoseEkf(const PoseEkfConfig& config = {});

  /// Starts (or restarts) the filter at `stamp` with a pose; speed / yaw rate zero, the gyro
  /// bias estimate is kept.
  void reset(double stamp, const core::Pose2& T_odom_base = {});
  /// Odometry twist (v, omega); `stationary`: no wheel moved (zero-velocity update).
  bool update_odometry(double stamp, const core::Twist2& twist, bool stationary);
  /// Gyro yaw rate [rad/s] (includes the bias).
  bool update_gyro(double stamp, double yaw_rate);
  /// Odom-frame position with its 1-sigma [m]; false when gated out or ignored.
  bool update_position(double stamp, const Eigen::Vector2d& position, double std);

  bool initialized() const { return initialized_; }
  double stamp() const { return stamp_; }
  const State& state() const { return x_; }
  const Cov& covariance() const { return P_; }
  core::Pose2 pose() const { return {x_(0), x_(1), x_(2)}; }
  core::Twist2 twist() const { return {x_(3), 0.0, x_(4)}; }
  double gyro_bias() const { return x_(5); }
  /// Measurements ignored because their stamp was before the filter time.
  int rejected_time() const { return rejected_time_; }
  /// Measurements dropped as non-finite or rejected by the gate.
  int rejected_outliers() const { return rejected_outliers_; }
  const PoseEkfConfig& config() const { return config_; }

 private:
  bool predict_to(double stamp);
  void predict(double dt);
  template <int M>
  void correct(const Eigen::Matrix<double, M, 1>& innovation, const Eigen::Matrix<double, M, 6>& H,
               const Eigen::Matrix<double, M, M>& R, bool update_pose, bool update_bias);

  PoseEkfConfig config_;
  State x_ = State::Zero();
  Cov P_ = Cov::Zero();
  double stamp_ = 0.0;
  bool initialized_ = false;
  int rejected_time_ = 0;
  int rejected_outliers_ = 0;
};

}  // namespace rownav::localize

template <>
struct rownav::core::EnumNames<rownav::localize::MotionModel> {
  using E = rownav::localize::MotionModel;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::constant_velocity, "constant_velocity"}, {E::constant_turn, "constant_turn"}}};
};
