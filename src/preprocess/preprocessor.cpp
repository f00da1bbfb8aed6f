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
  const std::span<const core::PointXYZIRT> in(cloud_base.points);
  const std::size_t kept = crop_.crop(in, crop_pts_, out_.dropped_invalid);
  const std::span<const CroppedPoint> cropped(crop_pts_.data(), kept);
  out_.ground_ok = ground_.estimate(cropped);
  // The band and the voxel grid read the compact cropped points; the voxel grid reads the other
  // fields of the band's points from the cloud.
  const std::size_t band = height_band(cropped, ground_, config_.height, band_);
  voxel_.filter_indexed(in, std::span<const CroppedPoint>(band_.data(), band), out_.cloud.points);
  out_.points.clear();
  out_.heights.clear();
  if (config_.use_scan) {
    out_.scan.stamp = cloud_base.stamp;
    crop_buf_.clear();  // the virtual scan reads whole points
    for (const auto& c : cropped) crop_buf_.push_back(in[c.index]);
    scan_.project(crop_buf_, &ground_, out_.scan);
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
