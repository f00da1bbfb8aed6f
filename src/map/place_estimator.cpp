/// @file place_estimator.cpp The map stage of Emmi 2021 Fig. 2a.
#include "rownav/map/place_estimator.hpp"

#include <cmath>

namespace rownav::map {

namespace {

bool finite_pose(const core::Pose2& T) {
  return std::isfinite(T.x) && std::isfinite(T.y) && std::isfinite(T.theta);
}

/// [m] forward travel from a to b along a's heading (negative when reversing).
double forward_travel(const core::Pose2& a, const core::Pose2& b) {
  return (b.translation() - a.translation()).dot(Eigen::Vector2d(std::cos(a.theta), std::sin(a.theta)));
}

}  // namespace

void PlaceEstimatorConfig::validate() const {
  core::check_positive(key_history, "key_history");
  core::validate_nested(clusters, "clusters");
  core::validate_nested(key_locations, "key_locations");
  core::validate_nested(indices, "indices");
  core::validate_nested(hmm, "hmm");
  core::validate_nested(transitions, "transitions");
  core::validate_nested(map, "map");
}

PlaceEstimator::PlaceEstimator(const PlaceEstimatorConfig& config)
    : config_((config.validate(), config)),
      clusters_(config.clusters),
      keys_(config.key_locations),
      hmm_(config.hmm),
      map_(config.map) {
  reset();
}

void PlaceEstimator::reset() {
  clusters_.reset();
  keys_.reset();
  hmm_.reset(config_.initial_place);
  map_ = TopologicalMap(config_.map);
  valid_keys_.clear();
  place_ = config_.initial_place;
  last_pose_.reset();
}

bool PlaceEstimator::set_lane_width(double lane_width) {
  if (!keys_.set_lane_width(lane_width)) return false;
  config_.key_locations.lane_width = lane_width;
  return true;
}

PlaceEstimate PlaceEstimator::update(const std::vector<Eigen::Vector3f>& points_base,
                                     const std::vector<PointLabel>& labels,
                                     const core::Pose2& T_odom_base, double stamp) {
  PlaceEstimate out;
  out.stamp = stamp;
  out.place = place_;
  if (!finite_pose(T_odom_base) || points_base.size() != labels.size()) {
    out.status = EstimateStatus::invalid_input;
    out.probabilities = hmm_.posterior();
    return out;
  }
  if (!map_.started()) map_.start(T_odom_base);
  const core::Pose2 T_local_base = map_.T_odom_local().inverse() * T_odom_base;
  clusters_.add(points_base, labels, T_local_base);
  const auto& rows = clusters_.update(T_local_base);
  for (const auto& k : keys_.update(rows, T_local_base)) valid_keys_.push_back(k);
  const auto history = static_cast<std::size_t>(config_.key_history);
  if (valid_keys_.size() > history)
    valid_keys_.erase(valid_keys_.begin(),
                      valid_keys_.end() - static_cast<std::ptrdiff_t>(history));
  const PlaceIndices idx = compute_place_indices(rows, T_local_base, keys_.half_width(),
                                                 valid_keys_, config_.key_locations,
                                                 config_.indices);
  const double forward = last_pose_ ? forward_travel(*last_pose_, T_odom_base) : 0.0;
  last_pose_ = T_odom_base;
  const PlaceHmmResult hmm = hmm_.update(forward, &idx.c_index);
  out.instantaneous = idx.instantaneous;
  out.c_index = idx.c_index;
  out.filtered = hmm.place;
  out.probabilities = hmm.posterior;
  out.confidence = hmm.confidence;
  out.rows = static_cast<int>(rows.size());
  validate_transition(out, T_odom_base, T_local_base, stamp);
  out.status = rows.empty()                      ? EstimateStatus::no_crop
               : hmm.place == Place::unknown ? EstimateStatus::uncertain
                                             : EstimateStatus::ok;
  return out;
}

void PlaceEstimator::validate_transition(PlaceEstimate& out, const core::Pose2& T_odom_base,
                                         const core::Pose2& T_local_base, double stamp) {
  const auto& entry = keys_.last(KeyType::entry);
  const auto& exit = keys_.last(KeyType::exit);
  if (entry) out.entry = map_.local_to_field(*entry);
  if (exit) out.exit = map_.local_to_field(*exit);
  const TransitionDecision d = evaluate_transition(place_, out.filtered, entry, exit,
                                                   T_local_base, config_.transitions);
  out.reason = d.reason;
  if (!d.transition) return;
  const bool to_rows = d.next == Place::lane || d.next == Place::alley;
  const auto& key = to_rows ? entry : exit;
  KeyLocation k = key ? *key : KeyLocation{};
  if (!key) k.p = T_local_base.translation();  // relocated: no key location, the robot's place
  map_.add_transition(place_, d.next, k, T_odom_base, stamp);
  // Emmi 2021: the new F_l flushes the stored perception and resets d.
  clusters_.reset();
  keys_.reset();
  valid_keys_.clear();
  place_ = d.next;
  out.place = place_;
  out.transition = true;
}

}  // namespace rownav::map
