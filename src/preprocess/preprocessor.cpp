// The preprocessing chain (see preprocessor.hpp for the order of the steps).
#include "rownav/preprocess/preprocessor.hpp"

namespace rownav::preprocess {

void PreprocessConfig::validate() const {
  core::validate_nested(crop, "crop");
  core::validate_nested(ground, "ground");
  core::validate_nested(height, "height");
  core::validate_nested(voxel, "voxel");
  core::validate_nested(radius_outlier, "radius_outlier");
  core::validate_nested(statistical_outlier, "statistical_outlier");
  core::validate_nested(scan, "scan");
}

Preprocessor::Preprocessor(const PreprocessConfig& config)
    : config_((config.validate(), config)),
      crop_(config.crop),
      ground_(config.ground),
      voxel_(config.voxel),
      radius_(config.radius_outlier),
      statistical_(config.statistical_outlier),
      scan_(config.scan) {
  out_.cloud.frame_id = "base";
}

const Preprocessed& Preprocessor::run(const core::PointCloud& cloud_base) {
  last_was_3d_ = true;
  out_.cloud.stamp = cloud_base.stamp;
  out_.cloud.has_intensity = cloud_base.has_intensity;
  out_.cloud.has_ring = cloud_base.has_ring;
  out_.cloud.has_time = cloud_base.has_time;
  crop_3d(cloud_base.points);
  out_.ground_ok = ground_.estimate(cropped_);
  // Height band fused into the voxel pass (no copy of the band).
  const auto lo = static_cast<float>(config_.height.min_height);
  const auto hi = static_cast<float>(config_.height.max_height);
  voxel_.filter_if(cropped_, out_.cloud.points, [&](const core::PointXYZIRT& p) {
    const float h = ground_.height(p);
    return (h >= lo) & (h <= hi);
  });
  out_.points.clear();
  out_.heights.clear();
  if (config_.use_scan) {
    out_.scan.stamp = cloud_base.stamp;
    scan_.project(cropped_, &ground_, out_.scan);
    ScanProjection::to_points(out_.scan, tmp2_);
    voxel_.filter(tmp2_, out_.points);
    filter_points_2d();
    return out_;
  }
  if (config_.radius_outlier.enabled) {
    radius_.filter(out_.cloud.points, tmp3_);
    out_.cloud.points.swap(tmp3_);
  }
  if (config_.statistical_outlier.enabled) {
    statistical_.filter(out_.cloud.points, tmp3_);
    out_.cloud.points.swap(tmp3_);
  }
  for (const auto& p : out_.cloud.points) {
    out_.points.emplace_back(p.x, p.y);
    out_.heights.push_back(ground_.height(p));  // trunk bands on sloped / rough ground
  }
  return out_;
}

void Preprocessor::crop_3d(std::span<const core::PointXYZIRT> in) {
  // Into a buffer that only grows (no per-frame initialisation). Branches, not a branch-free
  // compaction: a column's returns share the outcome, and writing every point costs more.
  if (crop_buf_.size() < in.size()) crop_buf_.resize(in.size());
  std::size_t kept = 0, invalid = 0;
  for (const auto& p : in) {
    if (!p.finite()) {
      ++invalid;
      continue;
    }
    if (crop_.contains(p.x, p.y, p.z)) crop_buf_[kept++] = p;
  }
  cropped_ = std::span<const core::PointXYZIRT>(crop_buf_.data(), kept);
  out_.dropped_invalid = invalid;
}

void Preprocessor::filter_points_2d() {
  if (config_.radius_outlier.enabled) {
    radius_.filter(out_.points, tmp2_);
    out_.points.swap(tmp2_);
  }
  if (config_.statistical_outlier.enabled) {
    statistical_.filter(out_.points, tmp2_);
    out_.points.swap(tmp2_);
  }
}

const Preprocessed& Preprocessor::run(std::span<const Eigen::Vector2f> points_base) {
  last_was_3d_ = false;
  out_.cloud.points.clear();
  out_.scan.ranges.clear();
  out_.dropped_invalid = 0;
  out_.ground_ok = true;
  tmp2_.clear();
  for (const auto& p : points_base) {
    if (!p.allFinite()) {
      ++out_.dropped_invalid;
      continue;
    }
    if (crop_.contains(p.x(), p.y())) tmp2_.push_back(p);
  }
  voxel_.filter(tmp2_, out_.points);
  filter_points_2d();
  return out_;
}

core::DetectorInput Preprocessor::input(double stamp) const {
  core::DetectorInput in;
  in.stamp = stamp;
  in.points = out_.points;
  in.cloud = last_was_3d_ ? &out_.cloud : nullptr;
  in.heights = last_was_3d_ ? &out_.heights : nullptr;
  return in;
}

}  // namespace rownav::preprocess
