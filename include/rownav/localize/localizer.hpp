#pragma once
/// @file localizer.hpp Odometry-frame localisation: wheel odometry + IMU (+ optional GNSS) fused
/// by an EKF, queried as T_odom_base at any stamp (LiDAR frames are interpolated).
///
/// CONTRACT shared by track/, navigate/ and the closed-loop runner. The implementation may add
/// fields and methods but must keep these signatures.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::localize {

/// Drive model used to turn wheel / track speeds into a body twist.
enum class DriveModel : std::uint8_t { differential, skid_steer, ackermann };

/// A pose estimate in the odom frame.
struct PoseEstimate {
  double stamp = 0.0;          ///< [s]
  core::Pose2 T_odom_base;     ///< base pose in the odom frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< of (x, y, theta) [m^2, rad^2]
  core::Twist2 twist;          ///< body velocity estimate
  bool valid = false;          ///< false before the first sample
};

}  // namespace rownav::localize

template <>
struct rownav::core::EnumNames<rownav::localize::DriveModel> {
  using E = rownav::localize::DriveModel;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::differential, "differential"},
       {E::skid_steer, "skid_steer"},
       {E::ackermann, "ackermann"}}};
};
