#include "rownav/localize/odometry_scale_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace rownav::localize {

void OdometryScaleConfig::validate() const {
  core::check_positive(baseline, "baseline");
  core::check_range(max_heading_change_deg, 0.0, 90.0, "max_heading_change_deg");
  core::check_positive(window, "window");
  core::check_range(min_samples, 1, window, "min_samples");
  core::check_non_negative(max_spread, "max_spread");
  core::check_non_negative(min_change, "min_change");
  core::validate_nested(match, "match");
}

namespace {

// The average of the two middle values for an even count: between 5 and 15 samples the count is
// often even, and an alpha between two samples is the estimate, not one of them (core::median
// returns the upper one; the alphas in BENCHMARK.md were measured with this one).
double midpoint_median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

}  // namespace

OdometryScaleEstimator::OdometryScaleEstimator(const OdometryScaleConfig& config)
    : config_(config) {
  config_.validate();
}

std::optional<double> OdometryScaleEstimator::add_frame(const std::vector<Eigen::Vector2f>& points,
                                                        const core::Pose2& T_odom_base,
                                                        double alpha) {
  if (!key_ || key_->alpha != alpha) {  // a new alpha: the stretch so far mixes two scales
    key_ = Key{points, T_odom_base, alpha};
    return std::nullopt;
  }
  const core::Pose2 T_key_cur = key_->T_odom_base.inverse() * T_odom_base;
  const double max_turn = config_.max_heading_change_deg * std::numbers::pi / 180.0;
  if (std::abs(T_key_cur.theta) > max_turn) {
    key_ = Key{points, T_odom_base, alpha};
    return std::nullopt;
  }
  if (T_key_cur.translation().norm() < config_.baseline) return std::nullopt;
  const ScanScaleMatch m = match_scan_scale(key_->points, points, T_key_cur, config_.match);
  ++matches_;
  key_ = Key{points, T_odom_base, alpha};
  if (m.status != ScaleMatchStatus::ok) return std::nullopt;
  ++accepted_;
  return take(alpha * m.scale, alpha);
}

std::optional<double> OdometryScaleEstimator::take(double sample, double alpha) {
  samples_.push_back(sample);
  while (std::ssize(samples_) > config_.window) samples_.pop_front();
  if (std::ssize(samples_) < config_.min_samples) return std::nullopt;
  const double m = midpoint_median({samples_.begin(), samples_.end()});
  std::vector<double> dev;
  dev.reserve(samples_.size());
  for (double s : samples_) dev.push_back(std::abs(s - m));
  if (midpoint_median(std::move(dev)) > config_.max_spread ||
      std::abs(m - alpha) <= config_.min_change)
    return std::nullopt;
  return m;
}

}  // namespace rownav::localize
