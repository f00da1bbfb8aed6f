#include "rownav/control/front_obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rownav::control {

void FrontRectConfig::validate() const {
  core::check_positive(robot_width, "robot_width");
  core::check_non_negative(margin, "margin");
  core::check(std::isfinite(front_x), "front_x", "must be finite");
  core::check_positive(max_distance, "max_distance");
  core::check_positive(min_points, "min_points");
}

void SlowdownConfig::validate() const {
  core::check_non_negative(stop_distance, "stop_distance");
  core::check(slow_down_distance > stop_distance, "slow_down_distance", "must be > stop_distance");
}

double front_obstacle_distance(std::span<const Eigen::Vector2f> points_base,
                               const FrontRectConfig& config) {
  const double half_width = 0.5 * config.robot_width + config.margin;
  std::vector<double> dists;
  for (const auto& p : points_base) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
    const double d = p.x() - config.front_x;
    if (d >= 0.0 && d <= config.max_distance && std::abs(p.y()) <= half_width) dists.push_back(d);
  }
  const auto k = static_cast<std::size_t>(std::max(config.min_points, 1));
  if (dists.size() < k) return std::numeric_limits<double>::infinity();
  std::nth_element(dists.begin(), dists.begin() + static_cast<std::ptrdiff_t>(k - 1), dists.end());
  return dists[k - 1];
}

double obstacle_limited_speed(double speed_ref, double obstacle_distance,
                              const SlowdownConfig& config) {
  if (!std::isfinite(speed_ref)) return 0.0;
  if (std::isnan(obstacle_distance)) return 0.0;
  const double s = (obstacle_distance - config.stop_distance) /
                   (config.slow_down_distance - config.stop_distance);
  return speed_ref * std::clamp(s, 0.0, 1.0);
}

}  // namespace rownav::control
