#pragma once
/// @file detector_input.hpp One preprocessed frame as every row detector reads it. In the core's
/// common types so that preprocess/ makes it and detect/ reads it without preprocess including
/// the detectors' interface (issue 14).
#include <Eigen/Core>
#include <vector>

#include "rownav/core/point_cloud.hpp"

namespace rownav::core {

/// One frame, already in the robot (base) frame: x forward, y left, z up, metres.
struct DetectorInput {
  double stamp = 0.0;                   ///< [s]
  std::vector<Eigen::Vector2f> points;  ///< 2D points: a scan, or a 3D cloud projected to 2D
  const PointCloud* cloud = nullptr;    ///< the 3D cloud (base frame) when the sensor is 3D
  /// [m] height above the estimated ground of each cloud point (same order as cloud->points),
  /// when the preprocessing estimated it; null: base z is the height (flat ground at z = 0)
  const std::vector<float>* heights = nullptr;
  /// The points are one planar scan (a 2D scanner at its own height), not a projection of a cloud
  /// or a synthetic scene: what the beams meet first occludes what lies behind (issue 11).
  bool planar_scan = false;
};

}  // namespace rownav::core
