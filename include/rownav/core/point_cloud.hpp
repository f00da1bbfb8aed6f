#pragma once
/// @file point_cloud.hpp LiDAR point clouds: XYZ + intensity + ring / column + per-point time.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace rownav::core {

/// One LiDAR return in the sensor frame (x forward, y left, z up).
struct PointXYZIRT {
  float x = 0.0f;          ///< [m]
  float y = 0.0f;          ///< [m]
  float z = 0.0f;          ///< [m]
  float intensity = 0.0f;  ///< [-] sensor-specific reflectivity / intensity
  std::uint16_t ring = 0;    ///< laser index (0 = lowest beam), where known
  std::uint16_t column = 0;  ///< azimuth column index, where known
  float time = 0.0f;         ///< [s] offset from the cloud stamp (motion during the sweep)

  bool finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};

/// A stamped LiDAR frame. `stamp` is the start of the sweep; point i was measured at
/// stamp + points[i].time.
struct PointCloud {
  double stamp = 0.0;             ///< [s]
  std::string frame_id = "lidar";
  std::vector<PointXYZIRT> points;
  bool has_intensity = false;  ///< intensity field is meaningful
  bool has_ring = false;       ///< ring / column fields are meaningful
  bool has_time = false;       ///< time field is meaningful

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }

  /// Removes NaN / Inf points in place (the brief: bad points are dropped, never propagated).
  /// Returns the number of points removed.
  std::size_t drop_invalid() {
    const auto before = points.size();
    std::erase_if(points, [](const PointXYZIRT& p) { return !p.finite(); });
    return before - points.size();
  }
};

}  // namespace rownav::core
