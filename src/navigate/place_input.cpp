/// @file place_input.cpp The map stage's per-frame input (navigate/place_input.hpp).
#include "rownav/navigate/place_input.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace rownav::navigate {

void PlaceConfig::validate() const {
  core::check(band_z_max > band_z_min, "band_z_max", "must exceed band_z_min");
  core::check_non_negative(row_margin, "row_margin");
  core::validate_nested(estimator, "estimator");
}

map::PointLabel geometric_label(const Eigen::Vector2f& p_base, const core::RowObservation& rows,
                                double row_margin) {
  const Eigen::Vector2d p = p_base.cast<double>();
  for (const auto& r : rows.rows) {
    // The row's centre line lies centre_shift beyond the fitted line, away from the robot.
    const double away = r.offset >= 0.0 ? 1.0 : -1.0;
    const double across = r.line.signed_distance(p) - away * r.centre_shift;
    if (std::abs(across) <= std::max(r.half_width, 0.0) + row_margin) return map::PointLabel::crop;
  }
  return map::PointLabel::ground;
}

std::optional<PlaceKey> validated_key(const map::PlaceEstimator& estimator,
                                      const map::PlaceEstimate& estimate) {
  const auto& transitions = estimator.map().transitions();
  if (!estimate.transition || transitions.empty()) return std::nullopt;
  const map::MapTransition& t = transitions.back();
  const core::Pose2& T_odom_field = estimator.map().T_odom_field();
  PlaceKey k{t.from, t.to, t.key, t.stamp};
  k.key.p = T_odom_field * t.key.p;
  k.key.v = Eigen::Rotation2Dd(T_odom_field.theta) * t.key.v;
  return k;
}

PlaceInput::PlaceInput(const PlaceConfig& config) : config_(config) { config_.validate(); }

void PlaceInput::collect(const core::PointCloud& cloud_base,
                         const preprocess::GroundEstimator& ground,
                         std::span<const map::PointLabel> labels,
                         const core::RowObservation& rows) {
  points_.clear();
  labels_.clear();
  given_ = labels.size() == cloud_base.points.size() && !labels.empty();
  for (std::size_t i = 0; i < cloud_base.points.size(); ++i) {
    const auto& q = cloud_base.points[i];
    if (!q.finite()) continue;
    const float h = ground.height(q);
    if (!(h >= config_.band_z_min && h <= config_.band_z_max)) continue;
    points_.emplace_back(q.x, q.y, q.z);
    labels_.push_back(given_ ? labels[i]
                             : geometric_label({q.x, q.y}, rows, config_.row_margin));
  }
}

void PlaceInput::collect(std::span<const Eigen::Vector2f> points_base,
                         const core::RowObservation& rows) {
  points_.clear();
  labels_.clear();
  given_ = false;
  for (const auto& p : points_base) {
    if (!p.allFinite()) continue;
    points_.emplace_back(p.x(), p.y(), 0.0f);
    labels_.push_back(geometric_label(p, rows, config_.row_margin));
  }
}

}  // namespace rownav::navigate
