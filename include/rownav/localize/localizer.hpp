#pragma once
/// @file localizer.hpp Odometry-frame localisation: wheel odometry + IMU (+ optional GNSS) fused
/// by an EKF, queried as T_odom_base at any stamp (LiDAR frames are interpolated).
///
/// CONTRACT shared by track/, navigate/ and the closed-loop runner. The implementation may add
/// fields and methods but must keep these signatures.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/localize/drive_model.hpp"  // DriveModel (contract)
#include "rownav/localize/pose_ekf.hpp"
#include "rownav/localize/wheel_odometry.hpp"

namespace rownav::localize {

/// A pose estimate in the odom frame.
struct PoseEstimate {
  double stamp = 0.0;                                    ///< [s]
  core::Pose2 T_odom_base;                               ///< base pose in the odom frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< of (x, y, theta) [m^2, rad^2]
  core::Twist2 twist;                                    ///< body velocity estimate
  bool valid = false;                                    ///< false before the first sample
};

/// Everything the Localizer needs.
struct LocalizerConfig {
  WheelOdometryConfig odometry;    ///< wheel / track odometry (nominal kinematics)
  PoseEkfConfig ekf;               ///< fusion filter
  bool use_imu = true;             ///< fuse the gyro yaw rate (Lan 2021 sec. 2.1)
  bool use_gnss = true;            ///< fuse valid GNSS fixes when any arrive (Lan 2021 sec. 2.1)
  double history = 3.0;            ///< [s] poses kept for interpolation
  double max_extrapolation = 0.2;  ///< [s] T_odom_base extrapolates this far past the newest
  /// [m] GNSS fixes are used once the robot has moved this far since the first valid fix: the
  /// travelled chord fixes the ENU -> odom rotation, the current fix the offset (rownav)
  double gnss_align_distance = 5.0;
  /// [-] after this many consecutive gated fixes the ENU -> odom alignment is redone (an
  /// overconfident filter must not lock GNSS out for ever) (rownav)
  int gnss_realign_after = 10;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("odometry", s.odometry);
    v("ekf", s.ekf);
    v("use_imu", s.use_imu);
    v("use_gnss", s.use_gnss);
    v("history", s.history);
    v("max_extrapolation", s.max_extrapolation);
    v("gnss_align_distance", s.gnss_align_distance);
    v("gnss_realign_after", s.gnss_realign_after);
  }
  void validate() const;
};

/// Samples the Localizer did not use, for status reporting.
struct LocalizerStats {
  int encoder_time_rejected = 0;  ///< encoder stamps not after the previous one
  int encoder_jumps = 0;          ///< implausible tick jumps (re-anchored)
  int time_rejected = 0;          ///< measurements older than the filter time
  int outliers = 0;               ///< non-finite samples and gated GNSS fixes
  int gnss_invalid = 0;           ///< fixes flagged invalid (outage)
  int gnss_used = 0;              ///< fixes fused
};

/// Wheel odometry + IMU (+ GNSS) fused by PoseEkf; keeps a short pose history so LiDAR frames
/// can be placed at their own stamps. Never throws on data; works without IMU / GNSS.
class Localizer {
 public:
  /// Validates `config` (throws std::invalid_argument naming the field).
  explicit Localizer(const LocalizerConfig& config = {});
  void add_encoders(const core::WheelEncoderSample& s);
  void add_imu(const core::ImuSample& s);
  /// position_enu is used as odom-frame position once aligned (see gnss_align_distance).
  /// Invalid fixes (outage) are counted and ignored; outliers are gated (Mahalanobis).
  void add_gnss(const core::GnssFix& s);
  /// Newest estimate (valid = false before the first sample).
  PoseEstimate latest() const;
  /// T_odom_base at `stamp`, interpolated between stored estimates (extrapolated by the last
  /// twist up to max_extrapolation past the newest); nullopt when outside the history.
  std::optional<core::Pose2> T_odom_base(double stamp) const;
  /// Estimate at `stamp` (pose interpolated, covariance / twist of the earlier neighbour).
  std::optional<PoseEstimate> estimate_at(double stamp) const;
  /// [-] the odometry's current correction factor alpha (Bertoglio 2023 eq. (2)).
  double odometry_alpha() const { return odometry_.config().alpha; }
  /// Replaces alpha from the next encoder sample on (an online estimate); poses already
  /// integrated stay as they are.
  void set_odometry_alpha(double alpha) { odometry_.set_alpha(alpha); }
  /// GNSS fixes are being fused (the pose's distance is no longer the odometry's alone).
  bool gnss_aligned() const { return T_odom_enu_.has_value(); }
  /// Restarts at a pose: clears history and GNSS alignment, keeps the gyro bias estimate.
  void reset(const core::Pose2& T_odom_base = {});
  const LocalizerConfig& config() const { return config_; }
  LocalizerStats stats() const;
  /// [rad/s] current gyro z bias estimate.
  double gyro_bias() const { return ekf_.gyro_bias(); }
  /// Integrated wheel odometry alone (diagnostics).
  const core::Pose2& odometry_pose() const { return odometry_.pose(); }

 private:
  void record();
  std::optional<Eigen::Vector2d> gnss_to_odom(const core::GnssFix& s);

  LocalizerConfig config_;
  WheelOdometry odometry_;
  PoseEkf ekf_;
  std::deque<PoseEstimate> history_;
  core::Pose2 start_;
  LocalizerStats stats_;
  // GNSS alignment: first fix (ENU) and the odom position at that time, then T_odom_enu.
  std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> gnss_anchor_;
  std::optional<core::Pose2> T_odom_enu_;
  int gnss_gated_in_row_ = 0;
};

}  // namespace rownav::localize
