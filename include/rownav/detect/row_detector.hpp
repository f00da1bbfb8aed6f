#pragma once
/// @file row_detector.hpp The interface every row detector implements.
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::detect {

/// One frame, already in the robot (base) frame: x forward, y left, z up, metres.
struct DetectorInput {
  double stamp = 0.0;                    ///< [s]
  std::vector<Eigen::Vector2f> points;   ///< 2D points: a scan, or a 3D cloud projected to 2D
  const core::PointCloud* cloud = nullptr;  ///< the 3D cloud (base frame) when the sensor is 3D
  /// [m] height above the estimated ground of each cloud point (same order as cloud->points),
  /// when the preprocessing estimated it; null: base z is the height (flat ground at z = 0)
  const std::vector<float>* heights = nullptr;
  /// The points are one planar scan (a 2D scanner at its own height), not a projection of a cloud
  /// or a synthetic scene: what the beams meet first occludes what lies behind (issue 11).
  bool planar_scan = false;
};

/// A per-frame row detector. detect() never throws: bad input gives status no_rows / degraded.
/// Detectors may keep state between frames (none of the current ones needs it), so detect() is
/// not const; one instance per thread.
class RowDetector {
 public:
  virtual ~RowDetector() = default;
  /// Short name, as on the command line (hough_skew, parallel_lines, pearl, ...).
  virtual std::string_view name() const = 0;
  virtual core::RowObservation detect(const DetectorInput& input) = 0;
};

}  // namespace rownav::detect
