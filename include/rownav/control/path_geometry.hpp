#pragma once
/// @file path_geometry.hpp Geometry of ControlInput::path_base shared by the controllers.
#include <Eigen/Core>
#include <cmath>

#include "rownav/control/controller.hpp"

namespace rownav::control {

/// True when the input's path and errors are finite and the path direction is non-zero.
inline bool input_finite(const ControlInput& in) {
  return std::isfinite(in.lateral_error) && std::isfinite(in.heading_error) &&
         in.path_base.point.allFinite() && in.path_base.direction.allFinite() &&
         in.path_base.direction.squaredNorm() > 0.0 && std::isfinite(in.speed_ref);
}

/// The point `lookahead` [m] ahead along the path of the base origin's projection on it (base
/// frame): the target of pure pursuit and of Bertoglio 2023 sec. II-B ("the point ... 1 m in
/// front of the robot").
inline Eigen::Vector2d lookahead_point(const core::Line2& path_base, double lookahead) {
  const Eigen::Vector2d d = path_base.direction.normalized();
  const Eigen::Vector2d foot = path_base.point + d * d.dot(-path_base.point);
  return foot + lookahead * d;
}

}  // namespace rownav::control
