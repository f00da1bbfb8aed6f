#include "rownav/detect/baseline.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {

namespace {

// Ordinary least squares y = a x + b (vertical residuals, as the baseline states, not
// TLS); nullopt when x does not vary.
std::optional<core::Line2> fit_y_of_x(const std::vector<Eigen::Vector2f>& pts) {
  if (pts.size() < 2) return std::nullopt;
  double sx = 0.0, sy = 0.0;
  for (const auto& p : pts) {
    sx += p.x();
    sy += p.y();
  }
  const double n = static_cast<double>(pts.size());
  const double mx = sx / n, my = sy / n;
  double sxx = 0.0, sxy = 0.0;
  for (const auto& p : pts) {
    sxx += (p.x() - mx) * (p.x() - mx);
    sxy += (p.x() - mx) * (p.y() - my);
  }
  if (!(sxx > 1e-9)) return std::nullopt;
  const double a = sxy / sxx;
  return core::Line2::from_slope_intercept(a, my - a * mx);
}

}  // namespace

void BaselineConfig::validate() const {
  core::check(x_min < x_max, "x_max", "must be > x_min");
  core::check_positive(y_max, "y_max");
  core::check(min_points >= 2, "min_points", "must be >= 2");
}

BaselineDetector::BaselineDetector(const BaselineConfig& config) : config_(config) {
  config_.validate();
}

core::RowObservation BaselineDetector::detect(const DetectorInput& input) {
  core::RowObservation obs;
  obs.stamp = input.stamp;
  obs.heading = std::numeric_limits<double>::quiet_NaN();
  left_.clear();
  right_.clear();
  for (const auto& p : input.points) {
    if (!p.allFinite() || p.x() < config_.x_min || p.x() > config_.x_max ||
        std::abs(p.y()) > config_.y_max || p.y() == 0.0f)
      continue;
    (p.y() > 0.0f ? left_ : right_).push_back(p);
  }
  for (const auto* side : {&right_, &left_}) {
    if (static_cast<int>(side->size()) < config_.min_points) continue;
    if (const auto line = fit_y_of_x(*side)) obs.rows.push_back(make_row_line(*line, *side));
  }
  // As published: the two box lines form the corridor whatever their angle (no pairing check;
  // 90 deg is every angle).
  finalize_observation(obs, 0.0, CorridorPairConfig{.max_skew_deg = 90.0});
  return obs;
}

}  // namespace rownav::detect
