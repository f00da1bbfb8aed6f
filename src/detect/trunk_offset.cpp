#include "rownav/detect/trunk_offset.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::detect {

void TrunkOffsetConfig::validate() const {
  core::check(z_max > z_min, "z_max", "must be > z_min");
  core::check_non_negative(inner, "inner");
  core::check_positive(outer, "outer");
  core::check_positive(half_width, "half_width");
  core::check_positive(min_points, "min_points");
  core::check_positive(max_range, "max_range");
  core::check_positive(max_shift, "max_shift");
}

TrunkOffset::TrunkOffset(const TrunkOffsetConfig& config) : config_(config) {
  config_.validate();
}

std::size_t TrunkOffset::collect(const core::PointCloud& cloud, const Eigen::Vector2d& d) {
  band_.clear();
  n_ = Eigen::Vector2d(-d.y(), d.x());
  if (!config_.enabled) return 0;
  const float nx = static_cast<float>(n_.x()), ny = static_cast<float>(n_.y());
  const float z0 = static_cast<float>(config_.z_min), z1 = static_cast<float>(config_.z_max);
  const float r2 = static_cast<float>(config_.max_range * config_.max_range);
  for (const auto& p : cloud.points) {
    if (!(p.z >= z0 && p.z <= z1) || !(p.x * p.x + p.y * p.y <= r2)) continue;  // NaN: dropped
    band_.push_back(nx * p.x + ny * p.y);
  }
  return band_.size();
}

namespace {

/// Median of the values of `in` within [lo, hi] (copied to `buf`); false when fewer than `min`.
bool window_median(const std::vector<float>& in, double lo, double hi, int min,
                   std::vector<float>& buf, double& median) {
  buf.clear();
  for (const float v : in)
    if (v >= lo && v <= hi) buf.push_back(v);
  if (static_cast<int>(buf.size()) < min) return false;
  const auto mid = buf.begin() + static_cast<long>(buf.size() / 2);
  std::nth_element(buf.begin(), mid, buf.end());
  median = *mid;
  return true;
}

}  // namespace

double TrunkOffset::offset(double canopy) {
  // The robot is at offset 0: "outwards" (behind the visible canopy face) is away from it.
  const double out = canopy >= 0.0 ? 1.0 : -1.0;
  const double a = canopy - out * config_.inner, b = canopy + out * config_.outer;
  double m = 0.0;
  if (!window_median(band_, std::min(a, b), std::max(a, b), config_.min_points, window_, m))
    return canopy;
  // Second, narrower pass around the first estimate: trunks and posts only.
  if (!window_median(band_, m - config_.half_width, m + config_.half_width, config_.min_points,
                     window_, m))
    return canopy;
  return std::abs(m - canopy) <= config_.max_shift ? m : canopy;
}

double TrunkOffset::apply(core::RowLine& r) {
  if (band_.empty()) return 0.0;
  const double canopy = n_.dot(r.line.point);
  const double shift = offset(canopy) - canopy;
  if (shift == 0.0) return 0.0;
  r.line.point += shift * n_;
  r.offset = std::abs(r.line.direction.x()) > 1e-9 ? r.line.y_at(0.0) : r.line.point.y();
  return shift;
}

}  // namespace rownav::detect
