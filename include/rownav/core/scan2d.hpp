#pragma once
/// @file scan2d.hpp Planar laser scans, as sensor_msgs/LaserScan.
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

namespace rownav::core {

/// A 2D scan: beam i has bearing angle_min + i * angle_increment (counter-clockwise, 0 = forward).
/// A beam with no return holds +infinity; an invalid reading NaN.
struct Scan2D {
  double stamp = 0.0;  ///< [s] time of the first beam
  std::string frame_id = "lidar";
  double angle_min = 0.0;        ///< [rad]
  double angle_increment = 0.0;  ///< [rad]
  double time_increment = 0.0;   ///< [s] between beams
  double range_min = 0.0;        ///< [m]
  double range_max = 0.0;        ///< [m]
  std::vector<float> ranges;       ///< [m]
  std::vector<float> intensities;  ///< optional, same size as ranges when present

  double angle(std::size_t i) const { return angle_min + static_cast<double>(i) * angle_increment; }

  /// True when beam i holds a return inside [range_min, range_max].
  bool valid(std::size_t i) const {
    const float r = ranges[i];
    return std::isfinite(r) && r >= range_min && r <= range_max;
  }

  /// Valid returns as points in the scan frame.
  std::vector<Eigen::Vector2f> to_points() const {
    std::vector<Eigen::Vector2f> out;
    out.reserve(ranges.size());
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      if (!valid(i)) continue;
      const double a = angle(i);
      out.emplace_back(static_cast<float>(ranges[i] * std::cos(a)),
                       static_cast<float>(ranges[i] * std::sin(a)));
    }
    return out;
  }
};

}  // namespace rownav::core
