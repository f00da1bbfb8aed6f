// Emmi 2021 (002_806e72d300173f73.txt), "Perception system": DBSCAN clusters isolate each row or
// part of a row (gaps split a row), a regression per cluster decides whether two clusters belong
// to the same row, and those are merged. The shape tests (length, roundness) and thresholds are
// ours: the paper gives no values.
#include "rownav/detect/cluster_rows.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Principal-axis shape of a point set.
struct Shape {
  core::Line2 line;        // through the mean along the major axis, oriented towards +x
  double length = 0.0;     // [m] extent along the major axis
  double minor_std = 0.0;  // [m] standard deviation across
  double roundness = 1.0;  // sqrt(minor / major eigenvalue)
};

Shape shape_of(const std::vector<Eigen::Vector2f>& pts) {
  Shape s;
  if (pts.size() < 2) return s;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p.cast<double>();
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) {
    const Eigen::Vector2d d = p.cast<double>() - mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(pts.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d ev = eig.eigenvalues().cwiseMax(0.0);
  Eigen::Vector2d dir = eig.eigenvectors().col(1);
  if (dir.x() < 0.0) dir = -dir;
  s.line = core::Line2(mean, dir);
  s.minor_std = std::sqrt(ev(0));
  s.roundness = ev(1) > 0.0 ? std::sqrt(ev(0) / ev(1)) : 1.0;
  double lo = 0.0, hi = 0.0;
  for (const auto& p : pts) {
    const double a = s.line.arc(p.cast<double>());
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  s.length = hi - lo;
  return s;
}

// Angle between two undirected lines, in [0, pi/2].
double line_angle(const core::Line2& a, const core::Line2& b) {
  return std::acos(std::min(1.0, std::abs(a.direction.dot(b.direction))));
}

struct Group {
  std::vector<Eigen::Vector2f> pts;
  Shape shape;
};

// Index of the group whose line passes within merge_offset of `s`'s centre (with a similar
// direction when `check_angle`), nearest first; -1 when none.
int matching_group(const std::vector<Group>& groups, const Shape& s, const ClusterRowsConfig& c,
                   bool check_angle) {
  int best = -1;
  double best_d = c.merge_offset;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto& gl = groups[g].shape.line;
    if (check_angle && line_angle(gl, s.line) > c.merge_angle_deg * kDeg) continue;
    const double d = std::abs(gl.signed_distance(s.line.point));
    if (d <= best_d) best_d = d, best = static_cast<int>(g);
  }
  return best;
}

void join(Group& g, const std::vector<Eigen::Vector2f>& pts) {
  g.pts.insert(g.pts.end(), pts.begin(), pts.end());
  g.shape = shape_of(g.pts);
}

}  // namespace

ClusterRowsConfig ClusterRowsConfig::row_crop() {
  ClusterRowsConfig c;
  c.eps = 0.2;              // half of the ~0.4 m free space between maize rows 0.7 m apart
  c.min_pts = 3;
  c.min_seed_length = 0.5;  // short visible rows (a 2-3 m view)
  c.merge_offset = 0.15;    // narrow plants
  c.min_row_length = 0.8;
  return c;
}

ClusterRowsConfig ClusterRowsConfig::orchard() {
  ClusterRowsConfig c;
  c.eps = 1.2;              // bridges the 1-2 m between crowns, far below the 3.5-6 m row spacing
  c.min_seed_length = 2.0;
  c.merge_offset = 0.8;     // crowns are 2-3 m wide
  c.min_row_length = 4.0;
  c.max_row_roundness = 0.4;
  return c;
}

void ClusterRowsConfig::validate() const {
  core::check_positive(eps, "eps");
  core::check(min_pts >= 1, "min_pts", "must be >= 1");
  core::check(min_cluster_points >= 2, "min_cluster_points", "must be >= 2");
  core::check_non_negative(min_seed_length, "min_seed_length");
  core::check_range(max_seed_roundness, 0.0, 1.0, "max_seed_roundness");
  core::check_range(merge_angle_deg, 0.0, 90.0, "merge_angle_deg");
  core::check_non_negative(merge_offset, "merge_offset");
  core::check_non_negative(min_row_length, "min_row_length");
  core::check_range(max_row_roundness, 0.0, 1.0, "max_row_roundness");
  core::check_range(max_row_angle_deg, 0.0, 90.0, "max_row_angle_deg");
  core::check(std::isfinite(lookahead), "lookahead", "must be finite");
  core::validate_nested(nearest_row, "nearest_row");
}

ClusterRowsDetector::ClusterRowsDetector(const ClusterRowsConfig& config) : config_(config) {
  config_.validate();
}

core::RowObservation ClusterRowsDetector::detect(const DetectorInput& input) {
  const auto& c = config_;
  core::RowObservation obs;
  obs.stamp = input.stamp;
  const auto& labels = dbscan_.run(input.points, c.eps, c.min_pts, c.neighbour_search);
  std::vector<std::vector<Eigen::Vector2f>> clusters(static_cast<std::size_t>(dbscan_.cluster_count()));
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] >= 0) clusters[static_cast<std::size_t>(labels[i])].push_back(input.points[i]);
  // Regression (principal axis) per cluster; seeds are the elongated ones, largest first.
  std::vector<std::pair<std::size_t, Shape>> seeds, small;
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    if (static_cast<int>(clusters[k].size()) < c.min_cluster_points) continue;
    const Shape s = shape_of(clusters[k]);
    const bool seed = s.length >= c.min_seed_length && s.roundness <= c.max_seed_roundness;
    (seed ? seeds : small).emplace_back(k, s);
  }
  std::stable_sort(seeds.begin(), seeds.end(), [&](const auto& a, const auto& b) {
    return clusters[a.first].size() > clusters[b.first].size();
  });
  // Emmi 2021: clusters on one line (similar direction, centre on the other's line) merge.
  std::vector<Group> groups;
  for (const auto& [k, s] : seeds) {
    const int g = matching_group(groups, s, c, true);
    if (g >= 0)
      join(groups[static_cast<std::size_t>(g)], clusters[k]);
    else
      groups.push_back({clusters[k], s});
  }
  // Short / round pieces (a single plant between gaps) join the row they sit on, if narrow.
  for (const auto& [k, s] : small) {
    if (s.minor_std > c.merge_offset) continue;
    const int g = matching_group(groups, s, c, false);
    if (g >= 0) join(groups[static_cast<std::size_t>(g)], clusters[k]);
  }
  for (const auto& g : groups) {
    if (g.shape.length < c.min_row_length || g.shape.roundness > c.max_row_roundness) continue;
    const auto line = fit_line_tls(g.pts);
    if (!line || std::abs(line->direction.y()) > std::sin(c.max_row_angle_deg * kDeg)) continue;
    obs.rows.push_back(make_row_line(*line, g.pts));
  }
  obs.heading = std::nan("");
  finalize_observation(obs, c.lookahead);
  // Issue 11: a near row too sparse to form a cluster (nearest_row.hpp).
  step_in_nearest_rows(obs, input.points, c.nearest_row, !input.planar_scan, c.lookahead);
  return obs;
}

}  // namespace rownav::detect
