#include "rownav/detect/pipeline.hpp"

#include <cmath>
#include <stdexcept>

namespace rownav::detect {

Eigen::Isometry2d planar_mount(const Eigen::Isometry3d& T_base_lidar) {
  const Eigen::Matrix3d R = T_base_lidar.linear();
  Eigen::Isometry2d T = Eigen::Isometry2d::Identity();
  T.linear() = Eigen::Rotation2Dd(std::atan2(R(1, 0), R(0, 0))).toRotationMatrix();
  T.translation() = T_base_lidar.translation().head<2>();
  return T;
}

DetectionPipeline::DetectionPipeline(const PipelineConfig& config,
                                     std::unique_ptr<RowDetector> detector,
                                     const Eigen::Isometry3d& T_base_lidar)
    : preprocessor_(config.preprocess),
      detector_(std::move(detector)),
      profile_(config.row_profile),
      T_base_lidar_(T_base_lidar) {
  if (!detector_) throw std::invalid_argument("DetectionPipeline: no detector");
}

core::RowObservation DetectionPipeline::process(const core::PointCloud& cloud_lidar) {
  return transform_and_detect(cloud_lidar, T_base_lidar_);
}

core::RowObservation DetectionPipeline::process(const core::PointCloud& cloud_lidar,
                                                const Eigen::Vector3d& up_base) {
  const double norm = up_base.norm();
  if (!up_base.allFinite() || norm <= 0.0 || up_base.z() <= 0.0)
    return transform_and_detect(cloud_lidar, T_base_lidar_);
  // R rotates the measured up onto +z about the base origin (no yaw change).
  Eigen::Isometry3d level = Eigen::Isometry3d::Identity();
  level.linear() = Eigen::Quaterniond::FromTwoVectors(up_base / norm, Eigen::Vector3d::UnitZ())
                       .toRotationMatrix();
  return transform_and_detect(cloud_lidar, level * T_base_lidar_);
}

core::RowObservation DetectionPipeline::transform_and_detect(
    const core::PointCloud& cloud_lidar, const Eigen::Isometry3d& T_base_lidar) {
  cloud_base_.stamp = cloud_lidar.stamp;
  cloud_base_.frame_id = "base";
  sensor_base_ = T_base_lidar.translation();
  cloud_base_.has_intensity = cloud_lidar.has_intensity;
  cloud_base_.has_ring = cloud_lidar.has_ring;
  cloud_base_.has_time = cloud_lidar.has_time;
  cloud_base_.points.resize(cloud_lidar.points.size());
  const Eigen::Isometry3f T = T_base_lidar.cast<float>();
  for (std::size_t i = 0; i < cloud_lidar.points.size(); ++i) {
    auto q = cloud_lidar.points[i];
    const Eigen::Vector3f p = T * Eigen::Vector3f(q.x, q.y, q.z);  // NaN stays NaN: dropped later
    q.x = p.x();
    q.y = p.y();
    q.z = p.z();
    cloud_base_.points[i] = q;
  }
  preprocessor_.run(cloud_base_);
  return detect(cloud_lidar.stamp, false);
}

core::RowObservation DetectionPipeline::process(const core::Scan2D& scan_lidar) {
  const Eigen::Isometry2f T = planar_mount(T_base_lidar_).cast<float>();
  sensor_base_ = T_base_lidar_.translation();
  cloud_base_.points.clear();
  cloud_base_.stamp = scan_lidar.stamp;
  points_base_.clear();
  for (std::size_t i = 0; i < scan_lidar.ranges.size(); ++i) {
    if (!scan_lidar.valid(i)) continue;
    const double a = scan_lidar.angle(i);
    const float r = scan_lidar.ranges[i];
    points_base_.push_back(T * Eigen::Vector2f(r * static_cast<float>(std::cos(a)),
                                               r * static_cast<float>(std::sin(a))));
  }
  preprocessor_.run(std::span<const Eigen::Vector2f>(points_base_));
  return detect(scan_lidar.stamp, true);
}

core::RowObservation DetectionPipeline::process_points(std::span<const Eigen::Vector2f> points_base,
                                                       double stamp) {
  cloud_base_.points.clear();
  cloud_base_.stamp = stamp;
  preprocessor_.run(points_base);
  return detect(stamp, true);
}

core::RowObservation DetectionPipeline::detect(double stamp, bool planar) {
  try {
    DetectorInput input = preprocessor_.input(stamp);
    input.planar_scan = planar && input.cloud == nullptr;
    last_points_ = input.points;
    if (filter_ && input.cloud == nullptr)
      input.points = core::filter_points(input.points, *filter_);
    core::RowObservation obs = detector_->detect(input);
    // Centre lines under the crowns, canopy half widths (issue 10); 2D input: no heights.
    if (input.cloud != nullptr) profile_.apply(*input.cloud, obs);
    return obs;
  } catch (...) {  // out of memory only: detectors do not throw; report an empty frame
    core::RowObservation none;
    none.stamp = stamp;
    return none;
  }
}

}  // namespace rownav::detect
