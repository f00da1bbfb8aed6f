#pragma once
/// @file wheel_odometry.hpp Wheel / track odometry from cumulative encoder ticks: ideal
/// differential drive, skid-steer ICR model (Bertoglio 2023, 003_25dc0df51a1e5faf.txt sec. II-A,
/// eq. (1)-(2)) and car-like bicycle model with the measured steering angle.
#include <cstdint>
#include <optional>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/localize/drive_model.hpp"

namespace rownav::localize {

/// Kinematic parameters the odometry assumes (nominal values unless calibrated).
struct WheelOdometryConfig {
  DriveModel model = DriveModel::skid_steer;  ///< kinematic model
  double track_width = 0.55;    ///< [m] wheel / track centre distance (differential model)
  double wheel_radius = 0.165;  ///< [m] wheel (or sprocket) radius
  int ticks_per_rev = 2048;     ///< [ticks/rev] encoder resolution
  /// [m] ICR distance x_ICR of Bertoglio 2023 eq. (2); nominal (ideal) = track_width / 2
  double x_icr = 0.275;
  /// [-] correction factor alpha of Bertoglio 2023 eq. (2); nominal 1. Also scales the
  /// car-like model's speed (tyre inflation / rolling radius error).
  double alpha = 1.0;
  double wheelbase = 0.6;  ///< [m] car-like: rear to front axle (bicycle model)
  /// [m/s] a wheel moving faster than this between two samples is an encoder glitch: rejected
  double max_plausible_speed = 5.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("model", s.model);
    v("track_width", s.track_width);
    v("wheel_radius", s.wheel_radius);
    v("ticks_per_rev", s.ticks_per_rev);
    v("x_icr", s.x_icr);
    v("alpha", s.alpha);
    v("wheelbase", s.wheelbase);
    v("max_plausible_speed", s.max_plausible_speed);
  }
  void validate() const;
};

/// Pose increment of a constant body twist held for dt [s] (exact arc, SE(2) exponential).
core::Pose2 twist_increment(const core::Twist2& twist, double dt);

/// Turns a stream of cumulative encoder samples into body twists and an integrated pose.
/// Never throws on data.
class WheelOdometry {
 public:
  /// Validates `config` (throws std::invalid_argument naming the field).
  explicit WheelOdometry(const WheelOdometryConfig& config = {});

  /// Body twist over the interval since the previous accepted sample. nullopt for the first
  /// sample, for a stamp not after the previous one (ignored), and for an implausible tick jump
  /// or non-finite data (the odometry re-anchors on this sample without moving).
  std::optional<core::Twist2> add(const core::WheelEncoderSample& sample);

  /// Body twist for left / right wheel (track) ground speeds [m/s] and steering angle [rad].
  core::Twist2 twist_from_wheels(double v_left, double v_right, double steering) const;

  /// Integrated T_odom_base.
  const core::Pose2& pose() const { return pose_; }
  /// Sets the pose; the next sample only re-anchors the ticks.
  void reset(const core::Pose2& T_odom_base = {});
  /// Samples ignored because time did not advance.
  int rejected_time() const { return rejected_time_; }
  /// Samples rejected as implausible jumps (or non-finite).
  int rejected_jumps() const { return rejected_jumps_; }
  const WheelOdometryConfig& config() const { return config_; }
  /// Replaces the correction factor alpha (an online estimate); ignored outside the range
  /// validate() allows.
  void set_alpha(double alpha);

 private:
  WheelOdometryConfig config_;
  core::Pose2 pose_;
  std::optional<core::WheelEncoderSample> last_;
  int rejected_time_ = 0;
  int rejected_jumps_ = 0;
};

}  // namespace rownav::localize
