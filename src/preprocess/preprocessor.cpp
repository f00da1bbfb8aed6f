// Minimal chain (crop, flat-ground height band); the full chain replaces it.
#include "rownav/preprocess/preprocessor.hpp"

namespace rownav::preprocess {

void PreprocessConfig::validate() const {
  core::check(x_min < x_max, "x_max", "must be > x_min");
  core::check(y_min < y_max, "y_max", "must be > y_min");
  core::check(min_height < max_height, "max_height", "must be > min_height");
  core::check_non_negative(voxel_size, "voxel_size");
}

Preprocessor::Preprocessor(const PreprocessConfig& config) : config_(config) {
  config_.validate();
}

const Preprocessed& Preprocessor::run(const core::PointCloud& cloud_base) {
  last_was_3d_ = true;
  out_.cloud.points.clear();
  out_.cloud.stamp = cloud_base.stamp;
  out_.cloud.frame_id = "base";
  out_.points.clear();
  out_.dropped_invalid = 0;
  for (const auto& p : cloud_base.points) {
    if (!p.finite()) {
      ++out_.dropped_invalid;
      continue;
    }
    if (p.x < config_.x_min || p.x > config_.x_max || p.y < config_.y_min || p.y > config_.y_max ||
        p.z < config_.min_height || p.z > config_.max_height)
      continue;
    out_.cloud.points.push_back(p);
    out_.points.emplace_back(p.x, p.y);
  }
  return out_;
}

const Preprocessed& Preprocessor::run(std::span<const Eigen::Vector2f> points_base) {
  last_was_3d_ = false;
  out_.cloud.points.clear();
  out_.points.clear();
  out_.dropped_invalid = 0;
  for (const auto& p : points_base) {
    if (!p.allFinite()) {
      ++out_.dropped_invalid;
      continue;
    }
    if (p.x() < config_.x_min || p.x() > config_.x_max || p.y() < config_.y_min ||
        p.y() > config_.y_max)
      continue;
    out_.points.push_back(p);
  }
  return out_;
}

detect::DetectorInput Preprocessor::input(double stamp) const {
  detect::DetectorInput in;
  in.stamp = stamp;
  in.points = out_.points;
  in.cloud = last_was_3d_ ? &out_.cloud : nullptr;
  return in;
}

}  // namespace rownav::preprocess
