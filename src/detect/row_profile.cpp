// Row centre line and canopy half width from the crown and the inner face (issue 10,
// detect/row_profile.hpp).
#include "rownav/detect/row_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rownav::detect {

namespace {

/// q-quantile of v (reordered); v non-empty.
float quantile(std::vector<float>& v, double q) {
  const auto i = static_cast<std::ptrdiff_t>(std::clamp(q, 0.0, 1.0) * double(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + i, v.end());
  return v[static_cast<std::size_t>(i)];
}

double outwards(const core::RowLine& r) {
  return r.offset >= 0.0 ? 1.0 : -1.0;
}

}  // namespace

void RowProfileConfig::validate() const {
  core::check_range(crown_quantile, 0.0, 1.0, "crown_quantile");
  core::check_range(face_quantile, 0.0, 0.5, "face_quantile");
  core::check_range(inner_ratio, 0.0, 0.5, "inner_ratio");
  core::check_range(outer_ratio, 0.05, 0.5, "outer_ratio");
  core::check_range(outer_ratio_last, 0.05, 2.0, "outer_ratio_last");
  core::check_positive(max_range, "max_range");
  core::check_positive(min_points, "min_points");
}

RowProfile::RowProfile(const RowProfileConfig& config) : config_(config) { config_.validate(); }

void RowProfile::window(const core::RowObservation& obs, std::size_t k, double& lo,
                        double& hi) const {
  // Neighbours in the sorted rows: towards the robot (inner) and away from it (outer).
  const auto& r = obs.rows[k];
  const bool left = outwards(r) > 0.0;
  const std::size_t n = obs.rows.size();
  const bool has_in = left ? k > 0 : k + 1 < n, has_out = left ? k + 1 < n : k > 0;
  const auto gap = [&](std::size_t j) { return std::abs(obs.rows[j].offset - r.offset); };
  // With no inner neighbour (a single row seen) the robot is the inner limit.
  const double g_in = has_in ? gap(left ? k - 1 : k + 1) : std::abs(r.offset);
  // A centre line (trunks) has its inner face between it and the robot: look up to midway.
  lo = -(r.centre_line ? 0.5 : config_.inner_ratio) * g_in;
  hi = has_out ? config_.outer_ratio * gap(left ? k + 1 : k - 1) : config_.outer_ratio_last * g_in;
}

float RowProfile::crown_offset() {
  buf_.clear();
  for (const auto& q : samples_) buf_.push_back(q.z);
  const float z_crown = quantile(buf_, config_.crown_quantile);
  buf_.clear();
  for (const auto& q : samples_)
    if (q.z >= z_crown) buf_.push_back(q.s);
  return buf_.empty() ? std::numeric_limits<float>::quiet_NaN() : quantile(buf_, 0.5);
}

void RowProfile::profile(const core::PointCloud& cloud, core::RowLine& r, double lo, double hi) {
  const Eigen::Vector2d n = r.line.normal() * outwards(r);
  const double c = n.dot(r.line.point), r2 = config_.max_range * config_.max_range;
  samples_.clear();
  for (const auto& p : cloud.points) {
    if (!std::isfinite(p.z) || !(double(p.x) * p.x + double(p.y) * p.y <= r2)) continue;
    if (p.x < r.x_min || p.x > r.x_max) continue;  // the row's own extent
    const double s = n.x() * p.x + n.y() * p.y - c;
    if (s >= lo && s <= hi) samples_.push_back({static_cast<float>(s), p.z});
  }
  if (static_cast<int>(samples_.size()) < config_.min_points) return;
  const float crown = r.centre_line ? 0.0f : crown_offset();  // a centre line needs no crown
  if (!std::isfinite(crown)) return;
  buf_.clear();
  for (const auto& q : samples_) buf_.push_back(q.s);
  const float face = quantile(buf_, config_.face_quantile);
  r.centre_shift = crown;
  r.half_width = std::max(0.0f, crown - face);
}

void RowProfile::apply(const core::PointCloud& cloud, core::RowObservation& obs) {
  if (!config_.enabled || cloud.points.empty()) return;
  for (std::size_t k = 0; k < obs.rows.size(); ++k) {
    auto& r = obs.rows[k];
    if (!r.line.point.allFinite() || !r.line.direction.allFinite()) continue;
    double lo = 0.0, hi = 0.0;
    window(obs, k, lo, hi);
    if (hi > lo) profile(cloud, r, lo, hi);
  }
}

}  // namespace rownav::detect
