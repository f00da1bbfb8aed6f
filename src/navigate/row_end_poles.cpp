#include "rownav/navigate/row_end_poles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <unordered_map>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace rownav::navigate {

namespace {

// Union-find over point indices.
int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

std::int64_t cell_key(int cx, int cy) {
  return (std::int64_t(cx) << 32) ^ std::uint32_t(cy);
}

// Euclidean cluster extraction (003 sec. II-C, Rusu 2009) on a grid of cell = tolerance: points
// closer than the tolerance share a cluster. Returns one index list per cluster.
std::vector<std::vector<int>> euclidean_clusters(const std::vector<Eigen::Vector2d>& pts,
                                                 double tol) {
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  std::vector<std::pair<int, int>> cells(pts.size());
  for (int i = 0; i < static_cast<int>(pts.size()); ++i) {
    cells[i] = {int(std::floor(pts[i].x() / tol)), int(std::floor(pts[i].y() / tol))};
    grid[cell_key(cells[i].first, cells[i].second)].push_back(i);
  }
  std::vector<int> parent(pts.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < static_cast<int>(pts.size()); ++i)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find(cell_key(cells[i].first + dx, cells[i].second + dy));
        if (it == grid.end()) continue;
        for (const int j : it->second)
          if (j > i && (pts[i] - pts[j]).squaredNorm() <= tol * tol)
            parent[find(parent, i)] = find(parent, j);
      }
  std::unordered_map<int, std::vector<int>> by_root;
  for (int i = 0; i < static_cast<int>(pts.size()); ++i) by_root[find(parent, i)].push_back(i);
  std::vector<std::vector<int>> out;
  for (auto& [root, members] : by_root) out.push_back(std::move(members));
  // Deterministic order (unordered_map iteration is not): by smallest member index.
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a[0] < b[0]; });
  return out;
}

// Pole of one cluster, in row coordinates (u along the rows, v across): the centroid of the
// end slice at the cluster's extreme nearest the robot (u = 0) along the rows.
Eigen::Vector2d end_slice_centroid(const std::vector<Eigen::Vector2d>& uv,
                                   const std::vector<int>& members, double slice) {
  double u_min = std::numeric_limits<double>::infinity(), u_max = -u_min;
  for (const int i : members)
    u_min = std::min(u_min, uv[i].x()), u_max = std::max(u_max, uv[i].x());
  const bool take_max = std::abs(u_max) <= std::abs(u_min);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int n = 0;
  for (const int i : members)
    if (take_max ? uv[i].x() >= u_max - slice : uv[i].x() <= u_min + slice) sum += uv[i], ++n;
  return sum / std::max(n, 1);
}

// Nearest policy (003 sec. II-C): "the nearest cluster point to the robot center, which is
// surrounded by a minimum number of points at a threshold distance" (a stray return next to the
// cluster is no end point). Members by distance to the robot (the origin), the first supported.
int nearest_supported(const std::vector<Eigen::Vector2d>& uv, std::vector<int> members,
                      const RowEndConfig& c) {
  std::sort(members.begin(), members.end(), [&](int a, int b) {
    return uv[a].squaredNorm() < uv[b].squaredNorm() ||
           (uv[a].squaredNorm() == uv[b].squaredNorm() && a < b);
  });
  const double r2 = c.nearest_radius * c.nearest_radius;
  for (const int i : members) {
    int around = 0;
    for (const int j : members) around += j != i && (uv[j] - uv[i]).squaredNorm() <= r2;
    if (around >= c.nearest_min_neighbours) return i;
  }
  return members.front();  // no point is supported: the nearest one
}

// The line through `members` by RANSAC (003 sec. II-C: 100 iterations, 0.1 m), refined by total
// least squares on its inliers: a point on it and its direction; nullopt under two points.
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> cluster_line(
    const std::vector<Eigen::Vector2d>& uv, const std::vector<int>& members, const RowEndConfig& c,
    std::mt19937_64& rng) {
  const int n = static_cast<int>(members.size());
  if (n < 2) return std::nullopt;
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<int> best, in;
  for (int it = 0; it < c.ransac_iterations; ++it) {
    const Eigen::Vector2d a = uv[members[pick(rng)]], d = uv[members[pick(rng)]] - a;
    if (d.norm() < 1e-6) continue;
    const Eigen::Vector2d normal(-d.normalized().y(), d.normalized().x());
    in.clear();
    for (const int i : members)
      if (std::abs(normal.dot(uv[i] - a)) <= c.ransac_threshold) in.push_back(i);
    if (in.size() > best.size()) best.swap(in);
  }
  if (best.size() < 2) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const int i : best) mean += uv[i];
  mean /= double(best.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const int i : best) cov += (uv[i] - mean) * (uv[i] - mean).transpose();
  return std::make_pair(
      mean,
      Eigen::Vector2d(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvectors().col(1)));
}

// The end point of one cluster by the configured policy, in row coordinates.
Eigen::Vector2d end_point(const std::vector<Eigen::Vector2d>& uv, const std::vector<int>& members,
                          const RowEndConfig& c, std::mt19937_64& rng) {
  if (c.policy == RowEndPolicy::end_slice) return end_slice_centroid(uv, members, c.end_slice);
  const Eigen::Vector2d nearest = uv[nearest_supported(uv, members, c)];
  if (c.policy == RowEndPolicy::nearest) return nearest;
  // Line fitting (003 sec. II-C): the Nearest point projected onto the line fitted to the cluster.
  const auto line = cluster_line(uv, members, c, rng);
  if (!line) return nearest;
  const auto& [point, direction] = *line;
  return point + direction * direction.dot(nearest - point);
}

// The nearest pole to the robot on each side (v > 0 left).
void pick_nearest(const std::vector<Eigen::Vector2d>& uv, const std::vector<int>& candidates,
                  std::optional<int>& left, std::optional<int>& right) {
  for (const int i : candidates) {
    auto& side = uv[i].y() > 0.0 ? left : right;
    if (!side || uv[i].norm() < uv[*side].norm()) side = i;
  }
}

struct LineFit {
  std::vector<int> inliers;
  Eigen::Vector2d point, direction;  // row coordinates
};

// RANSAC (003 sec. II-C: 100 iterations, 0.1 m) for the line through the row ends, kept within
// max_angle of perpendicular to the rows (v axis); refined by total least squares on the inliers.
std::optional<LineFit> ransac_end_line(const std::vector<Eigen::Vector2d>& uv,
                                       const RowEndConfig& c) {
  const int n = static_cast<int>(uv.size());
  if (n < 2) return std::nullopt;
  std::mt19937_64 rng(c.seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  const double max_sin = std::sin(c.max_line_angle_deg * std::numbers::pi / 180.0);
  LineFit best;
  for (int it = 0; it < c.ransac_iterations; ++it) {
    const int a = pick(rng), b = pick(rng);
    const Eigen::Vector2d d = uv[b] - uv[a];
    if (a == b || d.norm() < 1e-6 || std::abs(d.normalized().x()) > max_sin) continue;
    const Eigen::Vector2d normal(-d.normalized().y(), d.normalized().x());
    std::vector<int> in;
    for (int i = 0; i < n; ++i)
      if (std::abs(normal.dot(uv[i] - uv[a])) <= c.ransac_threshold) in.push_back(i);
    if (in.size() > best.inliers.size()) best = {in, uv[a], d.normalized()};
  }
  if (best.inliers.size() < 2) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const int i : best.inliers) mean += uv[i];
  mean /= double(best.inliers.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const int i : best.inliers) cov += (uv[i] - mean) * (uv[i] - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  best.point = mean;
  best.direction = es.eigenvectors().col(1);
  if (best.direction.y() > 0.0) best.direction = -best.direction;  // left (v > 0) to right
  return best;
}

}  // namespace

void RowEndConfig::validate() const {
  core::check_positive(cluster_tolerance, "cluster_tolerance");
  core::check_positive(min_cluster_points, "min_cluster_points");
  core::check_range(ransac_iterations, 1, 100000, "ransac_iterations");
  core::check_positive(ransac_threshold, "ransac_threshold");
  core::check_positive(end_slice, "end_slice");
  core::check_range(max_line_angle_deg, 0.0, 90.0, "max_line_angle_deg");
  core::check_positive(nearest_radius, "nearest_radius");
  core::check_non_negative(nearest_min_neighbours, "nearest_min_neighbours");
}

RowEnds estimate_row_ends(std::span<const Eigen::Vector2f> points_base, double row_heading,
                          double spacing, const RowEndConfig& config) {
  (void)spacing;  // the policies need no spacing; kept for the contract
  RowEnds out;
  if (!std::isfinite(row_heading) || !(config.cluster_tolerance > 0.0)) return out;
  // Row coordinates: u along the rows, v across (left +).
  const Eigen::Rotation2Dd R_row_base(-row_heading);
  std::vector<Eigen::Vector2d> uv;
  uv.reserve(points_base.size());
  for (const auto& p : points_base)
    if (std::isfinite(p.x()) && std::isfinite(p.y())) uv.push_back(R_row_base * p.cast<double>());
  std::vector<Eigen::Vector2d> poles_uv;
  std::mt19937_64 rng(config.seed);
  for (const auto& members : euclidean_clusters(uv, config.cluster_tolerance))
    if (static_cast<int>(members.size()) >= config.min_cluster_points)
      poles_uv.push_back(end_point(uv, members, config, rng));
  const Eigen::Rotation2Dd R_base_row(row_heading);
  for (const auto& q : poles_uv) out.poles.push_back(R_base_row * q);
  std::vector<int> candidates(poles_uv.size());
  std::iota(candidates.begin(), candidates.end(), 0);
  // The block's row ends lie on one line across the rows: its inliers are the candidates for the
  // followed rows' ends (rownav; the Nearest policy, as published, keeps every cluster).
  if (config.policy != RowEndPolicy::nearest)
    if (const auto fit = ransac_end_line(poles_uv, config)) {
      candidates = fit->inliers;
      out.end_line = core::Line2(R_base_row * fit->point, R_base_row * fit->direction);
    }
  std::optional<int> left, right;
  pick_nearest(poles_uv, candidates, left, right);
  if (left) out.left_end = out.poles[static_cast<std::size_t>(*left)];
  if (right) out.right_end = out.poles[static_cast<std::size_t>(*right)];
  return out;
}

}  // namespace rownav::navigate
