#pragma once
/// @file scan_projection.hpp 3D cloud to a 2D virtual scan, as the ROS pointcloud_to_laserscan
/// node (Bertoglio 2023 sec. II-A): points within a height band, binned by bearing, nearest
/// horizontal range per bin, +inf in empty bins.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/preprocess/ground.hpp"

namespace rownav::preprocess {

/// Virtual scan parameters (pointcloud_to_laserscan's, angles in degrees).
struct ScanProjectionConfig {
  double min_height = 0.2;  ///< [m] above ground (or above z = 0 without a ground estimate)
  double max_height = 1.5;  ///< [m] trunks and the canopy's lower part (vine fruiting zone)
  double angle_min_deg = -135.0;      ///< [deg] first bin (1081 bins of 0.25 deg: a 270 deg
  double angle_max_deg = 135.0;       ///< [deg] last bin  planar LiDAR's layout)
  double angle_increment_deg = 0.25;  ///< [deg] bin width
  double range_min = 0.3;   ///< [m] horizontal range, closer points ignored (robot body)
  double range_max = 30.0;  ///< [m] farther points ignored

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("min_height", s.min_height);
    v("max_height", s.max_height);
    v("angle_min_deg", s.angle_min_deg);
    v("angle_max_deg", s.angle_max_deg);
    v("angle_increment_deg", s.angle_increment_deg);
    v("range_min", s.range_min);
    v("range_max", s.range_max);
  }
  void validate() const;
  /// Number of bins: round((angle_max - angle_min) / increment) + 1.
  std::size_t bins() const;
};

/// Projects clouds to scans. Stateless apart from the config; never throws after construction.
class ScanProjection {
 public:
  explicit ScanProjection(const ScanProjectionConfig& config = {});
  /// Fills `scan` (ranges resized, reused) from `cloud` (base frame). Heights are above
  /// `ground` when given, else raw z. Bin i covers [angle_min + i inc, angle_min + (i+1) inc).
  /// NaN / Inf points are skipped. scan.frame_id = "base", stamp untouched.
  void project(std::span<const core::PointXYZIRT> cloud, const GroundEstimator* ground,
               core::Scan2D& scan) const;
  /// Valid returns of `scan` as points at each bin's angle (as Scan2D::to_points), into `out`.
  static void to_points(const core::Scan2D& scan, std::vector<Eigen::Vector2f>& out);
  const ScanProjectionConfig& config() const { return config_; }

 private:
  ScanProjectionConfig config_;
};

}  // namespace rownav::preprocess
