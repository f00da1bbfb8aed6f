#pragma once
/// @file pose2.hpp Planar rigid transform (SE(2)); names follow frames: T_odom_base maps base -> odom.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rownav/core/angle.hpp"

namespace rownav::core {

/// A planar pose / rigid transform. `T_a_b` expresses frame b in frame a:
/// p_a = T_a_b * p_b. x forward, y left, theta counter-clockwise (REP 103).
struct Pose2 {
  double x = 0.0;      ///< [m]
  double y = 0.0;      ///< [m]
  double theta = 0.0;  ///< [rad] heading, wrapped to (-pi, pi]

  Pose2() = default;
  Pose2(double x_, double y_, double theta_) : x(x_), y(y_), theta(wrap_angle(theta_)) {}

  Eigen::Vector2d translation() const { return {x, y}; }
  Eigen::Matrix2d rotation() const { return Eigen::Rotation2Dd(theta).toRotationMatrix(); }

  /// Composition: (T_a_b * T_b_c) = T_a_c.
  Pose2 operator*(const Pose2& o) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * o.x - s * o.y, y + s * o.x + c * o.y, theta + o.theta};
  }
  /// Transforms a point of frame b into frame a.
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  /// T_b_a from T_a_b.
  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, -theta};
  }
  /// 3D isometry with z = 0, roll = pitch = 0.
  Eigen::Isometry3d to_isometry() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    return T;
  }
};

/// Linear interpolation of position and shortest-arc interpolation of heading, s in [0, 1].
inline Pose2 interpolate(const Pose2& a, const Pose2& b, double s) {
  return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.theta + s * angle_diff(b.theta, a.theta)};
}

/// A pose with a timestamp [s].
struct StampedPose2 {
  double stamp = 0.0;  ///< [s]
  Pose2 pose;
};

}  // namespace rownav::core
