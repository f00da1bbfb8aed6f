/// @file truth_labeller.cpp Ground-truth point labels with detector errors.
#include "rownav/sim/truth_labeller.hpp"

#include <algorithm>

namespace rownav::sim {

void TruthLabellerConfig::validate() const {
  core::check(!crop_classes.empty(), "crop_classes", "must not be empty");
  core::check_range(false_positive_rate, 0.0, 1.0, "false_positive_rate");
  core::check_range(false_negative_rate, 0.0, 1.0, "false_negative_rate");
  core::check(!use_target_region || (target_max.array() > target_min.array()).all(),
              "target_max", "must exceed target_min in x and y");
}

TruthLabeller::TruthLabeller(const TruthLabellerConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
}

void TruthLabeller::set_frame(const core::Pose2& T_world_base, std::vector<SurfaceClass> classes) {
  T_world_base_ = T_world_base;
  classes_ = std::move(classes);
}

map::PointLabel TruthLabeller::true_label(SurfaceClass c, const Eigen::Vector2d& world) const {
  const auto& crops = config_.crop_classes;
  if (std::find(crops.begin(), crops.end(), c) != crops.end()) {
    const bool inside = !config_.use_target_region ||
                        ((world.array() >= config_.target_min.array()).all() &&
                         (world.array() <= config_.target_max.array()).all());
    return inside ? map::PointLabel::crop : map::PointLabel::other_crop;
  }
  if (c == SurfaceClass::ground) return map::PointLabel::ground;
  if (c == SurfaceClass::weed) return map::PointLabel::weed;
  return map::PointLabel::obstacle;
}

void TruthLabeller::label(const std::vector<Eigen::Vector3f>& points_base,
                          std::vector<map::PointLabel>& labels) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  labels.resize(points_base.size());
  for (std::size_t i = 0; i < points_base.size(); ++i) {
    const SurfaceClass c = i < classes_.size() ? classes_[i] : SurfaceClass::obstacle;
    const Eigen::Vector2d w = T_world_base_ * points_base[i].head<2>().cast<double>();
    map::PointLabel l = true_label(c, w);
    const double draw = u(rng_);  // one draw a point: the stream does not depend on the labels
    if (l == map::PointLabel::crop && draw < config_.false_negative_rate)
      l = map::PointLabel::obstacle;
    else if (l != map::PointLabel::crop && draw < config_.false_positive_rate)
      l = map::PointLabel::crop;
    labels[i] = l;
  }
}

}  // namespace rownav::sim
