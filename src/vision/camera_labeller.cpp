/// @file camera_labeller.cpp Laser points projected into the image, labelled by the box they hit.
#include "rownav/vision/camera_labeller.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::vision {

void CameraLabellerConfig::validate() const {
  core::check(!class_labels.empty(), "class_labels", "must not be empty");
  core::check(std::isfinite(ground_max_z), "ground_max_z", "must be finite");
  core::check_positive(min_depth, "min_depth");
  core::check_range(min_score, 0.0, 1.0, "min_score");
}

CameraLabeller::CameraLabeller(const CameraLabellerConfig& config) : config_(config) {
  config_.validate();
}

void CameraLabeller::set_detections(const core::CameraImage& image,
                                    std::vector<Detection> detections) {
  intrinsics_ = image.intrinsics;
  T_camera_base_ = image.T_base_camera.inverse();
  has_image_ = intrinsics_.width > 0 && intrinsics_.height > 0 && intrinsics_.fx > 0.0 &&
               intrinsics_.fy > 0.0 && T_camera_base_.matrix().allFinite();
  std::erase_if(detections, [&](const Detection& d) { return !(d.score >= config_.min_score); });
  std::stable_sort(detections.begin(), detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
  detections_ = std::move(detections);
}

void CameraLabeller::set_image(const core::CameraImage& image, ImageDetector& detector) {
  std::vector<Detection> boxes;
  detector.detect(image, boxes);
  set_detections(image, std::move(boxes));
}

map::PointLabel CameraLabeller::label_point(const Eigen::Vector3f& p_base) const {
  if (!p_base.allFinite()) return map::PointLabel::obstacle;
  if (p_base.z() <= config_.ground_max_z) return map::PointLabel::ground;
  if (!has_image_) return map::PointLabel::obstacle;
  const auto uv = intrinsics_.project(T_camera_base_ * p_base.cast<double>(), config_.min_depth);
  if (!uv) return map::PointLabel::obstacle;
  for (const Detection& d : detections_) {  // highest score first
    if (!d.contains(uv->x(), uv->y())) continue;
    if (d.class_id < 0 || d.class_id >= static_cast<int>(config_.class_labels.size()))
      return map::PointLabel::obstacle;
    return config_.class_labels[static_cast<std::size_t>(d.class_id)];
  }
  return map::PointLabel::obstacle;
}

void CameraLabeller::label(const std::vector<Eigen::Vector3f>& points_base,
                           std::vector<map::PointLabel>& labels) {
  labels.resize(points_base.size());
  for (std::size_t i = 0; i < points_base.size(); ++i) labels[i] = label_point(points_base[i]);
}

}  // namespace rownav::vision
