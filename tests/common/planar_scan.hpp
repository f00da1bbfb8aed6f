#pragma once
// Test helper: a 270 deg, 1081-beam planar scan (SICK LMS1xx layout, base = scanner frame) of
// points, the nearest return per beam, as the navigation stack's tests feed NavStack::on_scan.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "rownav/core/scan2d.hpp"

namespace rownav::test {

/// The scan of `points` (x, y, and any further coordinates ignored) stamped `stamp`.
template <class Point>
core::Scan2D planar_scan(const std::vector<Point>& points, double stamp) {
  core::Scan2D s;
  s.stamp = stamp;
  s.angle_min = -0.75 * std::numbers::pi;
  s.angle_increment = 0.25 * std::numbers::pi / 180.0;
  s.range_min = 0.05;
  s.range_max = 20.0;
  s.ranges.assign(1081, std::numeric_limits<float>::infinity());
  for (const auto& p : points) {
    const long i = std::lround((std::atan2(p.y(), p.x()) - s.angle_min) / s.angle_increment);
    if (i < 0 || i >= 1081) continue;
    auto& r = s.ranges[static_cast<std::size_t>(i)];
    r = std::min(r, std::sqrt(p.x() * p.x() + p.y() * p.y()));
  }
  return s;
}

}  // namespace rownav::test
