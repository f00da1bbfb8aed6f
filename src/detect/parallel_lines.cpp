#include "rownav/detect/parallel_lines.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// Points between the two lines count against a hypothesis only when they are off both lines.
struct Counts {
  int left = 0, right = 0, between = 0;
  int outside = 0;  // off both lines, within 2 d beyond either line (away from the corridor)
};

/// Classifies points against y = a x + b_l / b_r with perpendicular distance d.
template <class Pts>
Counts classify(const Pts& pts, double a, double bl, double br, double d) {
  Counts c;
  const double lim = d * std::sqrt(1.0 + a * a);  // vertical residual of distance d
  for (const auto& p : pts) {
    const double r = p.y() - a * p.x();
    if (std::abs(r - bl) <= lim && std::abs(r - bl) <= std::abs(r - br)) ++c.left;
    else if (std::abs(r - br) <= lim) ++c.right;
    else if (r > br && r < bl) ++c.between;
    else if (r - bl <= 2.0 * lim && br - r <= 2.0 * lim) ++c.outside;
  }
  return c;
}

/// Nearest (to the robot) cluster centre of the points; false when no cluster is big enough.
/// Clusters: single linkage at `radius`, found with a sweep along x.
bool nearest_cluster(std::vector<Eigen::Vector2f>& pts, double radius, int min_points,
                     double max_size, std::vector<int>& parent, Eigen::Vector2d& centre) {
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return a.x() < b.x(); });
  parent.resize(pts.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)];
    return i;
  };
  const float r2 = static_cast<float>(radius * radius);
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = i + 1; j < pts.size() && pts[j].x() - pts[i].x() <= radius; ++j)
      if ((pts[j] - pts[i]).squaredNorm() <= r2)
        parent[static_cast<std::size_t>(root(static_cast<int>(j)))] = root(static_cast<int>(i));
  struct Cluster {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int n = 0;
    Eigen::AlignedBox2f box;
  };
  std::vector<Cluster> clusters(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    auto& c = clusters[static_cast<std::size_t>(root(static_cast<int>(i)))];
    c.sum += pts[i].cast<double>();
    ++c.n;
    c.box.extend(pts[i]);
  }
  double best = std::numeric_limits<double>::infinity();
  for (const auto& c : clusters) {
    // A trunk is compact; long clusters are wires, low canopy or ground.
    if (c.n < min_points || c.box.diagonal().norm() > max_size) continue;
    const Eigen::Vector2d m = c.sum / c.n;
    if (m.norm() < best) best = m.norm(), centre = m;
  }
  return std::isfinite(best);
}

}  // namespace

void ParallelLinesConfig::validate() const {
  core::check_positive(iterations, "iterations");
  core::check_positive(inlier_distance, "inlier_distance");
  core::check_range(score_points, 10, 10000000, "score_points");
  core::check_non_negative(min_sample_dx, "min_sample_dx");
  core::check_range(max_heading_deg, 1.0, 80.0, "max_heading_deg");
  core::check_positive(min_width, "min_width");
  core::check(max_width > min_width, "max_width", "must be > min_width");
  core::check_non_negative(between_penalty, "between_penalty");
  core::check_non_negative(step_out_ratio, "step_out_ratio");
  core::check_range(refine_iterations, 1, 100, "refine_iterations");
  core::check_positive(min_inliers, "min_inliers");
  core::check_non_negative(min_row_length, "min_row_length");
  core::check(trunk_z_max > trunk_z_min, "trunk_z_max", "must be > trunk_z_min");
  core::check_positive(trunk_cluster_radius, "trunk_cluster_radius");
  core::check_positive(trunk_min_points, "trunk_min_points");
  core::check_positive(trunk_max_size, "trunk_max_size");
  core::check_positive(trunk_max_line_distance, "trunk_max_line_distance");
  core::check_positive(trunk_max_range, "trunk_max_range");
  core::validate_nested(trunk_offset, "trunk_offset");
  core::validate_nested(nearest_row, "nearest_row");
}

ParallelLinesDetector::ParallelLinesDetector(const ParallelLinesConfig& config)
    : config_((config.validate(), config)), offsets_(config.trunk_offset) {}

double ParallelLinesDetector::score(const Model& m) const {
  const Counts c = classify(scoring_, m.a, m.bl, m.br, config_.inlier_distance);
  return c.left + c.right - config_.between_penalty * c.between;
}

bool ParallelLinesDetector::ransac(Model& best) {
  // Lan 2022 sec. 3.3: RANSAC yields the supporting lines; hypotheses here are two points on one
  // row (slope a and its intercept) and one point on the other side of the robot.
  std::mt19937_64 rng(config_.seed);
  std::uniform_int_distribution<std::size_t> pick(0, scoring_.size() - 1);
  const double max_slope = std::tan(config_.max_heading_deg * kDeg);
  double best_score = -std::numeric_limits<double>::infinity();
  for (int it = 0; it < config_.iterations; ++it) {
    const auto& p = scoring_[pick(rng)];
    const auto& q = scoring_[pick(rng)];
    const double dx = double(q.x()) - p.x();
    if (std::abs(dx) < std::max(config_.min_sample_dx, 1e-3)) continue;
    const double a = (double(q.y()) - p.y()) / dx;
    if (std::abs(a) > max_slope) continue;
    const double b1 = p.y() - a * p.x();
    double b2 = b1;
    for (int t = 0; t < 8 && b2 * b1 >= 0.0; ++t) {
      const auto& k = scoring_[pick(rng)];
      b2 = k.y() - a * k.x();
    }
    if (b2 * b1 >= 0.0) continue;  // the two lines must straddle the robot
    const Model m{a, std::max(b1, b2), std::min(b1, b2)};
    const double width = (m.bl - m.br) / std::sqrt(1.0 + a * a);
    if (width < config_.min_width || width > config_.max_width) continue;
    const double s = score(m);
    if (s > best_score) best_score = s, best = m;
  }
  return std::isfinite(best_score);
}

void ParallelLinesDetector::refine(Model& m) {
  // Lan 2022 eq. (23) / the algorithm's r: joint least squares on (a, b_l, b_r).
  for (int it = 0; it < config_.refine_iterations; ++it) {
    const double lim = config_.inlier_distance * std::sqrt(1.0 + m.a * m.a);
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity() * 1e-9;  // keeps an empty side at its b
    Eigen::Vector3d rhs(1e-9 * m.a, 1e-9 * m.bl, 1e-9 * m.br);
    left_.clear();
    right_.clear();
    for (const auto& p : pts_) {
      const double r = p.y() - m.a * p.x();
      const bool l = std::abs(r - m.bl) <= lim && std::abs(r - m.bl) <= std::abs(r - m.br);
      if (!l && std::abs(r - m.br) > lim) continue;
      (l ? left_ : right_).push_back(p);
      const Eigen::Vector3d row(p.x(), l ? 1.0 : 0.0, l ? 0.0 : 1.0);
      A += row * row.transpose();
      rhs += row * double(p.y());
    }
    const Eigen::Vector3d x = A.ldlt().solve(rhs);
    if (!x.allFinite() || std::abs(x(0)) > std::tan(config_.max_heading_deg * kDeg)) return;
    m = {x(0), x(1), x(2)};
  }
}

bool ParallelLinesDetector::step_out(Model& m) {
  bool moved = false;
  // rownav: a weed strip (or a sparse line of leaves) in the corridor can out-score the real row
  // behind it, since that row's corridor holds the weeds. When a line at least
  // step_out_ratio x better supported lies farther out on the same side (within max_width), the
  // side moves to it.
  const double lim = config_.inlier_distance * std::sqrt(1.0 + m.a * m.a);
  const double reach = config_.max_width * std::sqrt(1.0 + m.a * m.a);
  for (int side = 0; side < 2; ++side) {
    double& b = side == 0 ? m.bl : m.br;
    const double sign = side == 0 ? 1.0 : -1.0;
    residuals_.clear();
    int current = 0;
    for (const auto& p : scoring_) {
      const double out = sign * (p.y() - m.a * p.x() - b);  // > 0: beyond the line
      if (std::abs(out) <= lim) ++current;
      else if (out > lim && out < reach) residuals_.push_back(out);
    }
    std::sort(residuals_.begin(), residuals_.end());
    const auto need = std::max<std::size_t>(1, std::size_t(config_.step_out_ratio * current));
    for (std::size_t i = 0, j = 0; i < residuals_.size(); ++i) {  // nearest dense 2 lim window
      while (residuals_[i] - residuals_[j] > 2.0 * lim) ++j;
      if (i - j + 1 < need) continue;
      b += sign * 0.5 * (residuals_[i] + residuals_[j]);
      moved = true;
      break;
    }
  }
  return moved;
}

void ParallelLinesDetector::find_trunks(const core::PointCloud& cloud, const Model& m, bool has_l,
                                        bool has_r) {
  // Lan 2022 Fig. 1: X_l, X_r, the closest trunk centre each side, from the points of the
  // trunk height band (ground assumed flat at base z = 0, as the paper assumes).
  const double c = 1.0 / std::sqrt(1.0 + m.a * m.a);
  for (int side = 0; side < 2; ++side) {
    if (side == 0 ? !has_l : !has_r) continue;
    const double b = side == 0 ? m.bl : m.br;
    band_.clear();
    for (const auto& p : cloud.points) {
      if (!p.finite() || p.z < config_.trunk_z_min || p.z > config_.trunk_z_max) continue;
      if (std::hypot(p.x, p.y) > config_.trunk_max_range) continue;
      if (std::abs(p.y - m.a * p.x - b) * c <= config_.trunk_max_line_distance)
        band_.emplace_back(p.x, p.y);
    }
    auto& t = trunks_[static_cast<std::size_t>(side)];
    t.found = nearest_cluster(band_, config_.trunk_cluster_radius, config_.trunk_min_points,
                              config_.trunk_max_size, label_, t.centre);
  }
}

core::RowObservation ParallelLinesDetector::detect(const DetectorInput& input) {
  core::RowObservation obs;
  obs.stamp = input.stamp;
  trunks_ = {};
  pts_.clear();
  for (const auto& p : input.points)
    if (std::isfinite(p.x()) && std::isfinite(p.y())) pts_.push_back(p);
  if (static_cast<int>(pts_.size()) < 2 * config_.min_inliers) return obs;
  // Deterministic, evenly strided scoring subset keeps the RANSAC cost bounded.
  scoring_.clear();
  const std::size_t stride = (pts_.size() + config_.score_points - 1) / config_.score_points;
  for (std::size_t i = 0; i < pts_.size(); i += stride) scoring_.push_back(pts_[i]);
  Model m;
  if (!ransac(m)) return obs;
  refine(m);
  if (config_.step_out_ratio > 0.0 && step_out(m)) refine(m);
  const Counts n = classify(pts_, m.a, m.bl, m.br, config_.inlier_distance);
  const double d = config_.inlier_distance, c = 1.0 / std::sqrt(1.0 + m.a * m.a);
  // Background density across the rows: between the lines and in a d guard band beyond each.
  const double background = (n.between + n.outside) /
                            (std::max((m.bl - m.br) * c - 2.0 * d, 0.0) + 2.0 * d);
  const auto keep = [&](int count, const std::vector<Eigen::Vector2f>& support) {
    if (count < config_.min_inliers || support.size() < 2) return false;
    if (count / (2.0 * d) < config_.min_contrast * background) return false;
    const auto [lo, hi] = std::minmax_element(
        support.begin(), support.end(), [](const auto& a, const auto& b) { return a.x() < b.x(); });
    return hi->x() - lo->x() >= config_.min_row_length;
  };
  const bool has_l = keep(n.left, left_), has_r = keep(n.right, right_);
  if (has_l) obs.rows.push_back(make_row_line(core::Line2::from_slope_intercept(m.a, m.bl), left_));
  if (has_r) obs.rows.push_back(make_row_line(core::Line2::from_slope_intercept(m.a, m.br), right_));
  // The lines fit the corridor faces of the canopy walls; the rows are the trunk lines behind
  // them (trunk_offset.hpp). The 3D cloud is needed; 2D points keep the canopy lines.
  if (input.cloud != nullptr &&
      offsets_.collect(*input.cloud, Eigen::Vector2d(1.0, m.a).normalized()) > 0)
    for (auto& r : obs.rows) offsets_.apply(r);
  obs.heading = std::atan(m.a);
  finalize_observation(obs);
  // Issue 11: the pair may have skipped the near row of a 2D scan (nearest_row.hpp); the two
  // reported rows stay the corridor pair.
  step_in_nearest_rows(obs, pts_, config_.nearest_row, !input.planar_scan, 0.0, true);
  if (config_.detect_trunks && input.cloud != nullptr) find_trunks(*input.cloud, m, has_l, has_r);
  return obs;
}

}  // namespace rownav::detect
