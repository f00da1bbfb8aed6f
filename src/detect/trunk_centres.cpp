#include "rownav/detect/trunk_centres.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::detect {

void TrunkCentresConfig::validate() const {
  core::check(z_max > z_min, "z_max", "must be > z_min");
  core::check_positive(max_range, "max_range");
  core::check_positive(cluster_eps, "cluster_eps");
  core::check_positive(min_points, "min_points");
  core::check_positive(max_radius, "max_radius");
}

TrunkCentres::TrunkCentres(const TrunkCentresConfig& config) : config_(config) {
  config_.validate();
}

const std::vector<TrunkCentre>& TrunkCentres::find(const core::PointCloud& cloud,
                                                   std::span<const float> heights) {
  trunks_.clear();
  band_.clear();
  const bool use_heights = heights.size() == cloud.points.size();
  const float r2 = static_cast<float>(config_.max_range * config_.max_range);
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const auto& p = cloud.points[i];
    const float h = use_heights ? heights[i] : p.z;
    if (!(h >= config_.z_min && h <= config_.z_max) || !(p.x * p.x + p.y * p.y <= r2)) continue;
    band_.emplace_back(p.x, p.y);  // NaN fails both tests above: dropped
  }
  if (band_.empty()) return trunks_;
  const auto& label = dbscan_.run(band_, config_.cluster_eps, 1);
  const auto n = static_cast<std::size_t>(dbscan_.cluster_count());
  sum_.assign(n, Eigen::Vector2d::Zero());
  count_.assign(n, 0);
  for (std::size_t i = 0; i < band_.size(); ++i) {
    if (label[i] < 0) continue;
    sum_[static_cast<std::size_t>(label[i])] += band_[i].cast<double>();
    ++count_[static_cast<std::size_t>(label[i])];
  }
  std::vector<double> radius(n, 0.0);
  for (std::size_t i = 0; i < band_.size(); ++i) {
    if (label[i] < 0) continue;
    const auto k = static_cast<std::size_t>(label[i]);
    const double d = (band_[i].cast<double>() - sum_[k] / count_[k]).norm();
    radius[k] = std::max(radius[k], d);
  }
  for (std::size_t k = 0; k < n; ++k) {
    // A trunk is compact; wider clusters are low branches, bushes, walls or the ground.
    if (count_[k] < config_.min_points || radius[k] > config_.max_radius) continue;
    trunks_.push_back({sum_[k] / count_[k], count_[k]});
  }
  return trunks_;
}

}  // namespace rownav::detect
