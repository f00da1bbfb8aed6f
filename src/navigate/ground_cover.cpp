// Height of the ground cover the robot drives through (navigate/ground_cover.hpp).
#include "rownav/navigate/ground_cover.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/core/statistics.hpp"

namespace rownav::navigate {

GroundCoverEstimator::GroundCoverEstimator(const GroundCoverConfig& config) : config_(config) {
  config_.validate();
}

void GroundCoverEstimator::update(const core::PointCloud& cloud_base,
                                  const preprocess::GroundEstimator& ground,
                                  const CoverRegion& region) {
  if (!config_.enabled) return;
  heights_.clear();
  const auto x0 = static_cast<float>(-config_.behind);
  const auto x1 = static_cast<float>(region.base_to_front);
  const auto half = static_cast<float>(region.half_width + config_.side);
  const auto lo = static_cast<float>(config_.floor), hi = static_cast<float>(config_.cap);
  for (const auto& p : cloud_base.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    if (p.x < x0 || p.x > x1 || std::abs(p.y) > half) continue;
    const float h = ground.height(p);
    if (h >= lo && h <= hi) heights_.push_back(h);
  }
  double top = 0.0;
  if (static_cast<int>(heights_.size()) >= config_.min_points) {
    const auto k = static_cast<std::size_t>(config_.quantile * double(heights_.size() - 1));
    std::nth_element(heights_.begin(), heights_.begin() + static_cast<std::ptrdiff_t>(k),
                     heights_.end());
    top = heights_[k];
  }
  history_.push_back(top);
  while (static_cast<int>(history_.size()) > config_.frames) history_.pop_front();
  cover_ = core::median(history_);
}

double GroundCoverEstimator::obstacle_min_height(double min_height) const {
  if (!config_.enabled || cover_ <= 0.0) return min_height;
  return std::clamp(cover_ + config_.margin, min_height, std::max(min_height, config_.cap));
}

void GroundCoverEstimator::reset() {
  history_.clear();
  cover_ = 0.0;
}

}  // namespace rownav::navigate
