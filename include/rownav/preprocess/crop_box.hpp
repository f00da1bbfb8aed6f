#pragma once
/// @file crop_box.hpp Axis-aligned box in the base frame plus a horizontal range crop around the
/// sensor origin (Nehme 2021 sec. 4 crops y to [-4, 4] m; Bertoglio 2023 sec. II-A keeps a circle
/// around the sensor).
#include <Eigen/Core>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/cropped_point.hpp"

namespace rownav::preprocess {

/// Crop box and range crop. Bounds are inclusive.
struct CropBoxConfig {
  double x_min = -1.0;  ///< [m] base frame, behind the robot
  double x_max = 10.0;  ///< [m] ahead (Nehme 2021 fig. 3 / Bertoglio: ~10 m of rows are used)
  double y_min = -4.0;  ///< [m] right (Nehme 2021 sec. 4: y in [-4, 4])
  double y_max = 4.0;   ///< [m] left (Nehme 2021 sec. 4)
  double z_min = -3.0;  ///< [m] below the base origin (3D clouds only)
  double z_max = 5.0;   ///< [m] above the base origin (3D clouds only)
  double range_min = 0.0;   ///< [m] horizontal distance from the sensor origin; closer = robot body
  double range_max = 30.0;  ///< [m] farther points dropped (Bertoglio 2023 sec. II-A radius filter)
  Eigen::Vector2d sensor_xy = Eigen::Vector2d::Zero();  ///< [m] sensor origin in the base frame

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("x_min", s.x_min);
    v("x_max", s.x_max);
    v("y_min", s.y_min);
    v("y_max", s.y_max);
    v("z_min", s.z_min);
    v("z_max", s.z_max);
    v("range_min", s.range_min);
    v("range_max", s.range_max);
    v("sensor_xy", s.sensor_xy);
  }
  void validate() const;
};

/// Point-in-crop test with precomputed bounds (float, squared ranges).
class CropBox {
 public:
  explicit CropBox(const CropBoxConfig& config = {});
  /// True when (x, y) lies in the box's xy bounds and the range annulus.
  bool contains(float x, float y) const {
    if (x < x_min_ || x > x_max_ || y < y_min_ || y > y_max_) return false;
    const float dx = x - sx_, dy = y - sy_;
    const float r2 = dx * dx + dy * dy;
    return r2 >= r2_min_ && r2 <= r2_max_;
  }
  /// True when the 3D point lies in the box (z included) and the range annulus.
  bool contains(float x, float y, float z) const {
    return z >= z_min_ && z <= z_max_ && contains(x, y);
  }
  /// contains(x, y, z) without branches (for compaction loops); false for NaN coordinates.
  bool contains_branchless(float x, float y, float z) const {
    const float dx = x - sx_, dy = y - sy_;
    const float r2 = dx * dx + dy * dy;
    return (z >= z_min_) & (z <= z_max_) & (x >= x_min_) & (x <= x_max_) & (y >= y_min_) &
           (y <= y_max_) & (r2 >= r2_min_) & (r2 <= r2_max_);
  }
  /// The points of `in` for which contains(x, y, z) holds, in order, into out[0, returned
  /// count) (`out` is only grown, never shrunk or initialised); `invalid` receives the number of
  /// NaN / Inf points. One pass; the range test is skipped when the box lies inside the annulus.
  std::size_t crop(std::span<const core::PointXYZIRT> in, std::vector<CroppedPoint>& out,
                   std::size_t& invalid) const;
  const CropBoxConfig& config() const { return config_; }

 private:
  /// contains(x, y, z), false for NaN / Inf, without the range test when it cannot fail.
  bool keeps(float x, float y, float z) const {
    const bool in_box =
        z >= z_min_ && z <= z_max_ && x >= x_min_ && x <= x_max_ && y >= y_min_ && y <= y_max_;
    return in_box && (!ring_test_ || contains(x, y));
  }

  CropBoxConfig config_;
  float x_min_, x_max_, y_min_, y_max_, z_min_, z_max_, sx_, sy_, r2_min_, r2_max_;
  bool ring_test_ = true;  // false: every point of the box lies in the range annulus
};

}  // namespace rownav::preprocess
