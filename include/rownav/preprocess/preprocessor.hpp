#pragma once
/// @file preprocessor.hpp The configurable chain that turns one LiDAR frame (base frame) into the
/// keypoints a row detector consumes: crop, ground-relative height band, voxel grid, outlier
/// removal and, for 3D clouds, the 2D points (projection or virtual scan).
#include <Eigen/Core>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/detect/row_detector.hpp"

namespace rownav::preprocess {

/// Every step of the chain; each sub-config documents its own defaults.
struct PreprocessConfig {
  double x_min = -1.0;       ///< [m] crop box, base frame (Nehme 2021 sec. 4 crops y to [-4, 4])
  double x_max = 10.0;       ///< [m]
  double y_min = -4.0;       ///< [m]
  double y_max = 4.0;        ///< [m]
  double min_height = 0.2;   ///< [m] keep points at least this far above the ground
  double max_height = 3.0;   ///< [m] and at most this far
  double voxel_size = 0.0;   ///< [m] voxel-grid edge; 0 = no downsampling (Nehme 2021: 0.15)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("x_min", s.x_min);
    v("x_max", s.x_max);
    v("y_min", s.y_min);
    v("y_max", s.y_max);
    v("min_height", s.min_height);
    v("max_height", s.max_height);
    v("voxel_size", s.voxel_size);
  }
  void validate() const;
};

/// Result of one frame; buffers are reused between frames.
struct Preprocessed {
  core::PointCloud cloud;               ///< kept 3D points (base frame), empty for 2D input
  std::vector<Eigen::Vector2f> points;  ///< kept points in the plane (x, y)
  std::size_t dropped_invalid = 0;      ///< NaN / Inf points removed
};

/// Runs the chain. Never throws on frame content; holds buffers, so one instance per thread.
class Preprocessor {
 public:
  explicit Preprocessor(const PreprocessConfig& config = {});
  /// A 3D cloud in the base frame.
  const Preprocessed& run(const core::PointCloud& cloud_base);
  /// 2D points in the base frame (a scan already converted): crop and 2D filters only.
  const Preprocessed& run(std::span<const Eigen::Vector2f> points_base);
  /// The detector input for the last run (points, and the cloud for 3D frames).
  detect::DetectorInput input(double stamp) const;
  const PreprocessConfig& config() const { return config_; }

 private:
  PreprocessConfig config_;
  Preprocessed out_;
  bool last_was_3d_ = false;
};

}  // namespace rownav::preprocess
