// Hough / iterative skewing: config, accumulator columns, heading search and the frame driver.
// Segmentation: hough_skew_segments.cpp; row refinement: hough_skew_rows.cpp.
#include "rownav/detect/hough_skew.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rownav/detect/line_fit.hpp"
#include "rownav/detect/nearest_row.hpp"

namespace rownav::detect {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// Collects the finite x, y of the cloud (preferred, Nehme 2021 votes with the whole cloud) or
/// of the 2D points.
void gather(const DetectorInput& in, bool use_cloud, std::vector<Eigen::Vector2f>& out) {
  out.clear();
  if (use_cloud && in.cloud != nullptr && !in.cloud->empty()) {
    for (const auto& p : in.cloud->points)
      if (p.finite()) out.emplace_back(p.x, p.y);
    return;
  }
  for (const auto& p : in.points)
    if (std::isfinite(p.x()) && std::isfinite(p.y())) out.push_back(p);
}

}  // namespace

void HoughSkewConfig::validate() const {
  using core::check;
  check(heading_min_deg < heading_max_deg, "heading_min_deg", "must be < heading_max_deg");
  core::check_range(heading_min_deg, -89.0, 89.0, "heading_min_deg");
  core::check_range(heading_max_deg, -89.0, 89.0, "heading_max_deg");
  core::check_positive(heading_step_deg, "heading_step_deg");
  core::check_positive(fine_step_deg, "fine_step_deg");
  check(y_min < y_max, "y_min", "must be < y_max");
  core::check_range(bins, 4, 100000, "bins");
  core::check_positive(min_points, "min_points");
  core::check_range(max_vote_points, 100, 100000000, "max_vote_points");
  core::check_non_negative(min_dispersion, "min_dispersion");
  core::check_positive(min_segment_bins, "min_segment_bins");
  core::check_positive(min_segment_points, "min_segment_points");
  core::check_positive(max_segment_width, "max_segment_width");
  core::check_positive(band_half_width, "band_half_width");
  core::check_range(valley_ratio, 0.0, 1.0, "valley_ratio");
  core::check_range(min_relative_support, 0.0, 1.0, "min_relative_support");
  core::check_non_negative(min_contrast, "min_contrast");
  core::check_range(refine_iterations, 1, 100, "refine_iterations");
  core::check_positive(trim_sigma, "trim_sigma");
  core::check_non_negative(min_row_length, "min_row_length");
  core::check_positive(max_row_rms, "max_row_rms");
  core::validate_nested(trunk_offset, "trunk_offset");
  core::validate_nested(nearest_row, "nearest_row");
}

HoughSkewDetector::HoughSkewDetector(const HoughSkewConfig& config)
    : config_((config.validate(), config)), trunks_(config.trunk_offset) {
  const int n = static_cast<int>(
      std::floor((config_.heading_max_deg - config_.heading_min_deg) / config_.heading_step_deg +
                 1e-9)) + 1;
  for (int i = 0; i < n; ++i) {
    const double g = (config_.heading_min_deg + i * config_.heading_step_deg) * kDeg;
    coarse_gamma_.push_back(g);
    coarse_sin_.push_back(std::sin(g));
    coarse_cos_.push_back(std::cos(g));
  }
  hist_.resize(static_cast<std::size_t>(config_.bins));
}

double HoughSkewDetector::column(const std::vector<Eigen::Vector2f>& pts, double s, double c) {
  // Nehme 2021 eq. (1): y_rot = x sin(gamma) + y cos(gamma), one vote per point.
  std::fill(hist_.begin(), hist_.end(), 0);
  const float fs = static_cast<float>(s), fc = static_cast<float>(c);
  const float y0 = static_cast<float>(config_.y_min);
  const float inv = static_cast<float>(config_.bins / (config_.y_max - config_.y_min));
  const int nb = config_.bins;
  for (const auto& p : pts) {
    const float b = (p.x() * fs + p.y() * fc - y0) * inv;
    if (b >= 0.0f && b < static_cast<float>(nb)) ++hist_[static_cast<std::size_t>(b)];
  }
  double sum = 0.0, sq = 0.0;
  for (const int h : hist_) {
    sum += h;
    sq += double(h) * h;
  }
  const double mean = sum / nb;
  return sq / nb - mean * mean;
}

double HoughSkewDetector::best_gamma(double& variance) {
  // Nehme 2021 sec. 3.2.1: the heading maximises the variance of the y-histogram. rownav: the
  // search votes with an evenly strided subset of at most max_vote_points points.
  const std::vector<Eigen::Vector2f>* votes = &pts_;
  if (pts_.size() > static_cast<std::size_t>(config_.max_vote_points)) {
    const std::size_t stride = (pts_.size() + config_.max_vote_points - 1) / config_.max_vote_points;
    subset_.clear();
    for (std::size_t i = 0; i < pts_.size(); i += stride) subset_.push_back(pts_[i]);
    votes = &subset_;
  }
  variance = -1.0;
  double best = 0.0;
  for (std::size_t i = 0; i < coarse_gamma_.size(); ++i) {
    const double v = column(*votes, coarse_sin_[i], coarse_cos_[i]);
    if (v > variance) variance = v, best = coarse_gamma_[i];
  }
  if (config_.refine_heading) {  // rownav: fine pass +- one coarse step around the best column
    const double centre = best, step = config_.fine_step_deg * kDeg;
    const int k = static_cast<int>(std::ceil(config_.heading_step_deg / config_.fine_step_deg));
    for (int i = -k; i <= k; ++i) {
      const double g = centre + i * step;
      if (i == 0 || g < config_.heading_min_deg * kDeg || g > config_.heading_max_deg * kDeg)
        continue;
      const double v = column(*votes, std::sin(g), std::cos(g));
      if (v > variance) variance = v, best = g;
    }
  }
  variance = column(pts_, std::sin(best), std::cos(best));  // every point for the segmentation
  return best;
}

core::RowObservation HoughSkewDetector::detect(const DetectorInput& input) {
  core::RowObservation obs;
  obs.stamp = input.stamp;
  gather(input, config_.use_cloud, pts_);
  if (static_cast<int>(pts_.size()) < config_.min_points) return obs;
  double variance = 0.0;
  const double gamma = best_gamma(variance);
  double mean = 0.0;
  for (const int h : hist_) mean += h;
  mean /= config_.bins;
  // rownav: a row-less (uniform) cloud has a Poisson histogram, variance ~ mean.
  if (mean <= 0.0 || variance / mean < config_.min_dispersion) return obs;
  segment();
  if (segments_.empty()) return obs;
  fit_rows(gamma, input.cloud, obs);
  finalize_observation(obs);
  // Issue 11: a near row the segmentation dropped (weaker than the row behind it; nearest_row.hpp).
  step_in_nearest_rows(obs, input.points, config_.nearest_row, !input.planar_scan);
  return obs;
}

}  // namespace rownav::detect
