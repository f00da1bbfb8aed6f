#include "rownav/detect/ransac_lines.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {

void RansacLinesConfig::validate() const {
  core::check_positive(iterations, "iterations");
  core::check_positive(inlier_distance, "inlier_distance");
  core::check_range(min_inliers, 2, 1000000, "min_inliers");
  core::check_positive(max_lines, "max_lines");
  core::check_non_negative(sample_min, "sample_min");
  core::check_range(max_row_heading_deg, 0.0, 90.0, "max_row_heading_deg");
  core::validate_nested(nearest_row, "nearest_row");
}

namespace {

/// Best line hypothesis through two sampled points: (normal n, c) with n.p = c, by inlier count.
struct Hypothesis {
  Eigen::Vector2f n = Eigen::Vector2f::Zero();
  float c = 0.0f;
  int count = -1;
};

Hypothesis best_hypothesis(const std::vector<Eigen::Vector2f>& pts, const RansacLinesConfig& cfg,
                           std::mt19937_64& rng) {
  Hypothesis best;
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  const auto tol = static_cast<float>(cfg.inlier_distance);
  const auto min2 = static_cast<float>(cfg.sample_min * cfg.sample_min);
  for (int it = 0; it < cfg.iterations; ++it) {
    const Eigen::Vector2f& a = pts[pick(rng)];
    const Eigen::Vector2f& b = pts[pick(rng)];
    const Eigen::Vector2f d = b - a;
    if (d.squaredNorm() < std::max(min2, 1e-8f)) continue;
    const Eigen::Vector2f n = Eigen::Vector2f(-d.y(), d.x()).normalized();
    const float c = n.dot(a);
    int count = 0;
    for (const auto& p : pts) count += std::abs(n.dot(p) - c) < tol ? 1 : 0;
    if (count > best.count) best = {n, c, count};
  }
  return best;
}

/// Moves the points within tolerance of `line` from pts to out.
void take_inliers(const core::Line2& line, double tol, std::vector<Eigen::Vector2f>& pts,
                  std::vector<Eigen::Vector2f>& out) {
  out.clear();
  std::size_t keep = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (std::abs(line.signed_distance(pts[i].cast<double>())) < tol)
      out.push_back(pts[i]);
    else
      pts[keep++] = pts[i];
  }
  pts.resize(keep);
}

}  // namespace

RansacLinesDetector::RansacLinesDetector(const RansacLinesConfig& config) : config_(config) {
  config_.validate();
}

core::RowObservation RansacLinesDetector::detect(const DetectorInput& input) {
  const RansacLinesConfig& cfg = config_;
  core::RowObservation obs;
  obs.stamp = input.stamp;
  obs.heading = std::numeric_limits<double>::quiet_NaN();
  pts_.clear();
  for (const auto& p : input.points)
    if (std::isfinite(p.x()) && std::isfinite(p.y())) pts_.push_back(p);
  std::mt19937_64 rng(cfg.seed);
  const double max_heading = cfg.max_row_heading_deg * std::numbers::pi / 180.0;
  for (int k = 0; k < cfg.max_lines && static_cast<int>(pts_.size()) >= cfg.min_inliers; ++k) {
    const Hypothesis h = best_hypothesis(pts_, cfg, rng);
    if (h.count < cfg.min_inliers) break;
    const Eigen::Vector2d n = h.n.cast<double>();
    const core::Line2 rough(n * static_cast<double>(h.c), Eigen::Vector2d(n.y(), -n.x()));
    take_inliers(rough, cfg.inlier_distance, pts_, inliers_);
    const auto refit = fit_line_tls(inliers_);  // TLS re-fit on the inliers
    if (!refit) continue;
    const core::RowLine row = make_row_line(*refit, inliers_);
    if (std::abs(row.heading) > max_heading) continue;
    obs.rows.push_back(row);
  }
  finalize_observation(obs, cfg.lookahead);
  // Issue 11: sequential RANSAC takes the best supported lines first (nearest_row.hpp).
  step_in_nearest_rows(obs, input.points, cfg.nearest_row, !input.planar_scan, cfg.lookahead);
  return obs;
}

}  // namespace rownav::detect
