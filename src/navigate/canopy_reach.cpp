// How far the followed rows' canopy reaches into the corridor (navigate/canopy_reach.hpp).
#include "rownav/navigate/canopy_reach.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::navigate {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The `q` quantile of `v` (a copy: the history keeps its order).
double quantile_of(std::deque<double> v, double q) {
  const auto k = static_cast<std::ptrdiff_t>(q * double(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

/// The `q` quantile of `v` (reordered), +inf when it holds fewer than `min_points` values.
double low_quantile(std::vector<float>& v, double q, int min_points) {
  if (static_cast<int>(v.size()) < min_points) return kInf;
  const auto k = static_cast<std::size_t>(q * double(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

CanopyReachEstimator::CanopyReachEstimator(const CanopyReachConfig& config) : config_(config) {
  config_.validate();
}

void CanopyReachEstimator::update(const core::PointCloud& cloud_base,
                                  const preprocess::GroundEstimator& ground, const HeightBand& band,
                                  const core::Line2& centre_base, double base_to_front) {
  if (!config_.enabled) return;
  if (!centre_base.point.allFinite() || !centre_base.direction.allFinite()) return reset();
  side_[0].clear(), side_[1].clear();
  const auto x0 = static_cast<float>(-config_.behind), x1 = static_cast<float>(base_to_front);
  const auto lo = static_cast<float>(band.min_height), hi = static_cast<float>(band.max_height);
  const auto top = static_cast<float>(band.top);
  for (const auto& p : cloud_base.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    if (p.x < x0 || p.x > x1 || p.z > top) continue;
    const float h = ground.height(p);
    if (!(h >= lo && h <= hi)) continue;
    const double u = centre_base.signed_distance({p.x, p.y});
    side_[u > 0.0 ? 1 : 0].push_back(static_cast<float>(std::abs(u)));
  }
  for (int s = 0; s < 2; ++s) {
    history_[s].push_back(low_quantile(side_[s], config_.quantile, config_.min_points));
    while (static_cast<int>(history_[s].size()) > config_.frames) history_[s].pop_front();
    reach_[s] = quantile_of(history_[s], config_.frame_quantile);
  }
}

double CanopyReachEstimator::reach(double side) const {
  return reach_[side > 0.0 ? 1 : 0];
}

void CanopyReachEstimator::drop_canopy(std::vector<Eigen::Vector2f>& points,
                                       const core::Line2& centre_base, double half_width) const {
  if (!config_.enabled || !centre_base.point.allFinite() || !centre_base.direction.allFinite())
    return;
  // Never deeper into the footprint than max_intrusion of its half width.
  const double core_half = half_width * (1.0 - config_.max_intrusion);
  const auto canopy = [&](const Eigen::Vector2f& p) {
    const double u = centre_base.signed_distance(p.cast<double>());
    const int s = u > 0.0 ? 1 : 0;
    const bool same_side = (p.y() > 0.0f) == (s == 1);
    return std::isfinite(reach_[s]) && same_side && std::abs(u) >= reach_[s] - config_.margin &&
           std::abs(p.y()) >= core_half;
  };
  points.erase(std::remove_if(points.begin(), points.end(), canopy), points.end());
}

void CanopyReachEstimator::reset() {
  for (int s = 0; s < 2; ++s) {
    history_[s].clear();
    reach_[s] = kInf;
  }
}

}  // namespace rownav::navigate
