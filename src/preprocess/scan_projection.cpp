// Virtual scan, following pointcloud_to_laserscan's per-point loop (nearest range per bin).
#include "rownav/preprocess/scan_projection.hpp"

#include <cmath>
#include <limits>

#include "rownav/core/angle.hpp"

namespace rownav::preprocess {

void ScanProjectionConfig::validate() const {
  core::check(std::isfinite(min_height) && std::isfinite(max_height) && min_height < max_height,
              "max_height", "must be finite and > min_height");
  core::check_range(angle_min_deg, -180.0, 180.0, "angle_min_deg");
  core::check_range(angle_max_deg, -180.0, 180.0, "angle_max_deg");
  core::check(angle_min_deg < angle_max_deg, "angle_max_deg", "must be > angle_min_deg");
  core::check_positive(angle_increment_deg, "angle_increment_deg");
  core::check_non_negative(range_min, "range_min");
  core::check(range_min < range_max, "range_max", "must be > range_min");
}

std::size_t ScanProjectionConfig::bins() const {
  return static_cast<std::size_t>(std::lround((angle_max_deg - angle_min_deg) / angle_increment_deg)) +
         1;
}

ScanProjection::ScanProjection(const ScanProjectionConfig& config) : config_(config) {
  config_.validate();
}

void ScanProjection::project(std::span<const core::PointXYZIRT> cloud,
                             const GroundEstimator* ground, core::Scan2D& scan) const {
  const auto& c = config_;
  const double amin = core::deg2rad(c.angle_min_deg), amax = core::deg2rad(c.angle_max_deg);
  const double inc = core::deg2rad(c.angle_increment_deg);
  scan.frame_id = "base";
  scan.angle_min = amin;
  scan.angle_increment = inc;
  scan.time_increment = 0.0;
  scan.range_min = c.range_min;
  scan.range_max = c.range_max;
  const std::size_t n = c.bins();
  scan.ranges.assign(n, std::numeric_limits<float>::infinity());
  scan.intensities.clear();
  const auto lo = static_cast<float>(c.min_height), hi = static_cast<float>(c.max_height);
  const auto r2_min = static_cast<float>(c.range_min * c.range_min);
  const auto r2_max = static_cast<float>(c.range_max * c.range_max);
  for (const auto& p : cloud) {
    if (!p.finite()) continue;
    const float h = ground ? ground->height(p) : p.z;
    if (h < lo || h > hi) continue;
    const float r2 = p.x * p.x + p.y * p.y;
    if (r2 < r2_min || r2 > r2_max) continue;
    const double a = std::atan2(p.y, p.x);
    if (a < amin || a > amax) continue;
    const auto i = static_cast<std::size_t>((a - amin) / inc);
    if (i >= n) continue;
    const float r = std::sqrt(r2);
    if (r < scan.ranges[i]) scan.ranges[i] = r;
  }
}

void ScanProjection::to_points(const core::Scan2D& scan, std::vector<Eigen::Vector2f>& out) {
  out.clear();
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!scan.valid(i)) continue;
    const double a = scan.angle(i);
    out.emplace_back(static_cast<float>(scan.ranges[i] * std::cos(a)),
                     static_cast<float>(scan.ranges[i] * std::sin(a)));
  }
}

}  // namespace rownav::preprocess
