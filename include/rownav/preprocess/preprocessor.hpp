#pragma once
/// @file preprocessor.hpp The configurable chain that turns one LiDAR frame (base frame) into the
/// keypoints a row detector consumes: crop, ground-relative height band, voxel grid, outlier
/// removal and, for 3D clouds, the 2D points (projection or virtual scan).
///
/// 3D frame: drop NaN / Inf -> crop box + range -> ground estimate -> height band -> voxel grid
/// (Nehme 2021 sec. 4) -> cloud. The crop keeps compact (x, y, z, index) points that the ground,
/// the band and the voxel grid read; the cloud is not copied. Then either points =
/// (x, y) of the cloud, each point filtered by the enabled outlier filters in 3D; or (use_scan) a
/// virtual scan of the cropped cloud (Bertoglio 2023 sec. II-A), whose returns go through a 2D
/// voxel grid and the outlier filters.
/// 2D frame: drop NaN / Inf -> crop (x, y, range) -> 2D voxel grid -> outlier filters.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/core/detector_input.hpp"
#include "rownav/preprocess/crop_box.hpp"
#include "rownav/preprocess/ground.hpp"
#include "rownav/preprocess/height_band.hpp"
#include "rownav/preprocess/radius_outlier.hpp"
#include "rownav/preprocess/scan_projection.hpp"
#include "rownav/preprocess/statistical_outlier.hpp"
#include "rownav/preprocess/voxel_grid.hpp"

namespace rownav::preprocess {

/// Every step of the chain; each sub-config documents its own defaults (a vineyard seen by a
/// roof-mounted 3D LiDAR).
struct PreprocessConfig {
  CropBoxConfig crop;                           ///< box + range crop (base frame)
  GroundConfig ground;                          ///< ground estimate (3D only)
  HeightBandConfig height;                      ///< band above the ground (3D only)
  VoxelGridConfig voxel;                        ///< downsampling (3D, or 2D for 2D points)
  RadiusOutlierConfig radius_outlier;           ///< off by default
  StatisticalOutlierConfig statistical_outlier; ///< off by default
  ScanProjectionConfig scan;                    ///< virtual scan (3D with use_scan)
  bool use_scan = false;  ///< 3D: points from a virtual 2D scan instead of the cloud's (x, y)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("crop", s.crop);
    v("ground", s.ground);
    v("height", s.height);
    v("voxel", s.voxel);
    v("radius_outlier", s.radius_outlier);
    v("statistical_outlier", s.statistical_outlier);
    v("scan", s.scan);
    v("use_scan", s.use_scan);
  }
  void validate() const;
};

/// Result of one frame; buffers are reused between frames.
struct Preprocessed {
  core::PointCloud cloud;               ///< kept 3D points (base frame), empty for 2D input
  std::vector<float> heights;           ///< [m] each cloud point's height above the ground
  std::vector<Eigen::Vector2f> points;  ///< kept points in the plane (x, y)
  std::size_t dropped_invalid = 0;      ///< NaN / Inf points removed
  core::Scan2D scan;                    ///< the virtual scan (3D input with use_scan only)
  bool ground_ok = true;                ///< false: ground estimation failed, flat_z was used
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
  core::DetectorInput input(double stamp) const;
  const PreprocessConfig& config() const { return config_; }
  /// The ground estimate of the last 3D frame (height-above-ground function).
  const GroundEstimator& ground() const { return ground_; }

 private:
  void filter_points_2d();

  PreprocessConfig config_;
  CropBox crop_;
  GroundEstimator ground_;
  VoxelGrid voxel_;
  RadiusOutlier radius_;
  StatisticalOutlier statistical_;
  ScanProjection scan_;
  Preprocessed out_;
  bool last_was_3d_ = false;
  std::vector<CroppedPoint> crop_pts_, band_;       // only grow: the crop's output, the band
  std::vector<core::PointXYZIRT> crop_buf_, tmp3_;  // crop_buf_: cropped points for use_scan
  std::vector<Eigen::Vector2f> tmp2_;
};

}  // namespace rownav::preprocess
