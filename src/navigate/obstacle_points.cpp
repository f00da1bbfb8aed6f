// Obstacle candidates of a 3D sweep by height above the ground (navigate/obstacle_points.hpp).
#include "rownav/navigate/obstacle_points.hpp"

#include <cmath>

namespace rownav::navigate {

std::vector<Eigen::Vector2f> obstacle_points(const core::PointCloud& cloud_base,
                                             const preprocess::GroundEstimator& ground,
                                             const ObstacleBandConfig& band, double top) {
  std::vector<Eigen::Vector2f> out;
  const auto range = static_cast<float>(band.range), half = static_cast<float>(band.half_width);
  const auto lo = static_cast<float>(band.min_height), hi = static_cast<float>(band.max_height);
  for (const auto& p : cloud_base.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    if (p.x <= 0.0f || p.x >= range || std::abs(p.y) >= half || p.z > top) continue;
    const float h = ground.height(p);
    if (h >= lo && h <= hi) out.emplace_back(p.x, p.y);
  }
  return out;
}

}  // namespace rownav::navigate
