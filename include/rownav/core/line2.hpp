#pragma once
/// @file line2.hpp Infinite lines and segments in the plane.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "rownav/core/pose2.hpp"

namespace rownav::core {

/// An oriented infinite line through `point` along the unit vector `direction`.
/// Signed distances are positive on the left of the direction (y left, REP 103).
struct Line2 {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< unit vector

  Line2() = default;
  Line2(const Eigen::Vector2d& p, const Eigen::Vector2d& d) : point(p), direction(d.normalized()) {}

  /// Line through two distinct points, oriented from a to b.
  static Line2 through(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return {a, b - a}; }
  /// Line y = slope * x + intercept, oriented towards +x.
  static Line2 from_slope_intercept(double slope, double intercept) {
    return {Eigen::Vector2d(0.0, intercept), Eigen::Vector2d(1.0, slope)};
  }

  /// [rad] direction angle in (-pi, pi].
  double heading() const { return std::atan2(direction.y(), direction.x()); }
  /// Left normal (direction rotated by +90 deg).
  Eigen::Vector2d normal() const { return {-direction.y(), direction.x()}; }
  /// Signed distance of p, positive on the left.
  double signed_distance(const Eigen::Vector2d& p) const { return normal().dot(p - point); }
  /// Coordinate of p's projection along the direction, from `point`.
  double arc(const Eigen::Vector2d& p) const { return direction.dot(p - point); }
  Eigen::Vector2d project(const Eigen::Vector2d& p) const { return point + arc(p) * direction; }
  Eigen::Vector2d at(double s) const { return point + s * direction; }
  /// y at a given x, for lines that are not parallel to y (robot-frame row lines).
  double y_at(double x) const {
    return point.y() + (x - point.x()) * direction.y() / direction.x();
  }
  /// Same line expressed in frame a, given T_a_b and this line in frame b.
  Line2 transformed(const Pose2& T_a_b) const {
    return {T_a_b * point, T_a_b.rotation() * direction};
  }
};

/// A finite segment from a to b.
struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();

  double length() const { return (b - a).norm(); }
  Line2 line() const { return Line2::through(a, b); }
  /// Euclidean distance of p to the segment.
  double distance(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d d = b - a;
    const double l2 = d.squaredNorm();
    if (l2 <= 0.0) return (p - a).norm();
    const double s = std::clamp((p - a).dot(d) / l2, 0.0, 1.0);
    return (p - (a + s * d)).norm();
  }
};

}  // namespace rownav::core
