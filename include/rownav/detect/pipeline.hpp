#pragma once
/// @file pipeline.hpp One LiDAR frame to a RowObservation: LiDAR frame -> base frame (the mount),
/// the preprocessing chain, then a row detector.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "rownav/core/data_filter.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/row_observation.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/detect/row_detector.hpp"
#include "rownav/detect/row_profile.hpp"
#include "rownav/preprocess/preprocessor.hpp"

namespace rownav::detect {

/// Planar part of a 3D mount: x, y and yaw of T_base_lidar (a 2D scanner is assumed level).
Eigen::Isometry2d planar_mount(const Eigen::Isometry3d& T_base_lidar);

/// Everything a DetectionPipeline is built from besides its detector: the `preprocess:` and
/// `row_profile:` sections of a config/detect/<crop>.yaml file.
struct PipelineConfig {
  PipelineConfig() = default;
  /// The preprocessing given, the row profile at its defaults.
  PipelineConfig(preprocess::PreprocessConfig p) : preprocess(std::move(p)) {}  // NOLINT: implicit
  preprocess::PreprocessConfig preprocess;  ///< the chain before the detector
  /// after the detector: every row's centre line and canopy half width from the 3D cloud
  /// (issue 10, detect/row_profile.hpp)
  RowProfileConfig row_profile;
  void validate() const {
    core::validate_nested(preprocess, "preprocess");
    core::validate_nested(row_profile, "row_profile");
  }
};

/// Preprocessing + detection of one frame. Not thread-safe (buffers, detector state).
class DetectionPipeline {
 public:
  /// Throws std::invalid_argument for an invalid PipelineConfig or a null detector.
  DetectionPipeline(const PipelineConfig& config, std::unique_ptr<RowDetector> detector,
                    const Eigen::Isometry3d& T_base_lidar = Eigen::Isometry3d::Identity());

  /// A 3D sweep in the LiDAR frame. Never throws.
  core::RowObservation process(const core::PointCloud& cloud_lidar);
  /// A 3D sweep levelled first: `up_base` is the gravity "up" direction in the base frame (from
  /// the accelerometer, see localize/gravity_attitude.hpp). The base frame tilts with the
  /// terrain, so a vertical row seen at height h appears shifted sideways by h sin(roll): at
  /// 3 deg of roll, 5 cm for a 1 m canopy. The cloud is rotated about the base origin (on the
  /// ground) so that up_base becomes +z, and the rows are found where they meet the ground.
  /// A non-finite, zero or downward up_base is ignored (not levelled); how far a trusted tilt
  /// may go is the caller's decision (NavStack: StackConfig::max_level_tilt_deg). Never throws.
  core::RowObservation process(const core::PointCloud& cloud_lidar, const Eigen::Vector3d& up_base);
  /// A planar scan in the LiDAR frame; the mount is applied in the plane (x, y, yaw). Never
  /// throws.
  core::RowObservation process(const core::Scan2D& scan_lidar);
  /// 2D points already in the base frame (x forward, y left, metres). Never throws.
  core::RowObservation process_points(std::span<const Eigen::Vector2f> points_base, double stamp);

  /// Data-filter boxes for the next frames' planar points (Malavazi 2018 sec. 2.3.1; from the
  /// tracker); nullopt: no filter. last_points() stays the unfiltered scan (end of row,
  /// obstacles).
  void set_data_filter(std::optional<core::DataFilterBoxes> boxes) { filter_ = std::move(boxes); }

  const RowDetector& detector() const { return *detector_; }
  /// The preprocessing chain's configuration (e.g. its voxel edge: the spacing of last_points()).
  const preprocess::PreprocessConfig& preprocess_config() const { return preprocessor_.config(); }
  const Eigen::Isometry3d& T_base_lidar() const { return T_base_lidar_; }
  /// Points handed to the detector in the last frame (base frame, after preprocessing).
  const std::vector<Eigen::Vector2f>& last_points() const { return last_points_; }
  /// The last 3D frame in the base frame before preprocessing (raw heights, NaN possible); empty
  /// after a planar scan. End-of-row tests count points in height bands of it.
  const core::PointCloud& last_cloud_base() const { return cloud_base_; }
  /// The sensor's origin in the base frame of the last frame: the mount's translation, turned
  /// by the gravity levelling when the frame was levelled (the point its rays start from).
  const Eigen::Vector3d& last_sensor_base() const { return sensor_base_; }
  /// The ground estimated on last_cloud_base() (heights above the local ground).
  const preprocess::GroundEstimator& last_ground() const { return preprocessor_.ground(); }

 private:
  core::RowObservation detect(double stamp, bool planar);
  core::RowObservation transform_and_detect(const core::PointCloud& cloud_lidar,
                                            const Eigen::Isometry3d& T_base_lidar);

  preprocess::Preprocessor preprocessor_;
  std::unique_ptr<RowDetector> detector_;
  RowProfile profile_;  // every row's centre and half width (issue 10)
  Eigen::Isometry3d T_base_lidar_;
  core::PointCloud cloud_base_;
  Eigen::Vector3d sensor_base_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2f> points_base_, last_points_;
  std::optional<core::DataFilterBoxes> filter_;
};

}  // namespace rownav::detect
