// Grid DBSCAN (Gunawan 2013, "A faster algorithm for DBSCAN"; de Berg 2017): cells of side
// < eps / sqrt(2) hold points that are all within eps of each other, so a cell with >= min_pts
// points is all core, its points need no neighbour count, and two cells are joined by one core
// pair within eps. Same labels as the neighbour-list DBSCAN of dbscan.cpp (core = >= min_pts
// points within eps, itself included; clusters in the order of their lowest core point; border
// points to the cluster of their lowest-index core neighbour), without its O(n k) neighbour
// lists: after a 3D voxel grid a canopy wall stacks a dozen voxels on one (x, y) spot.
#include <algorithm>
#include <cmath>

#include "rownav/detect/dbscan.hpp"

namespace rownav::detect {
namespace {

// Cell side as a fraction of eps: sqrt(0.5) = 0.7071 less a 1 % margin, so that float rounding
// of the cell index and of the squared distance never puts two points farther than eps apart
// in one cell (checked for extents below kMaxCellsPerAxis cells).
constexpr float kCellPerEps = 0.70f;
constexpr float kMaxCellsPerAxis = 1e4f;
constexpr int kReach = 2;  // eps / side < 2: neighbours lie within 2 cells

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    auto& p = parent[static_cast<std::size_t>(i)];
    p = parent[static_cast<std::size_t>(p)];  // path halving
    i = p;
  }
  return i;
}

}  // namespace

bool Dbscan::build_cells(const std::vector<Eigen::Vector2f>& points, float eps) {
  Eigen::Vector2f lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& p : points)
    if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.x() <= hi.x())) return true;  // no finite point: all noise
  const float side = kCellPerEps * eps;
  if (((hi - lo) / side).maxCoeff() > kMaxCellsPerAxis) return false;
  lo_ = lo, inv_side_ = 1.0f / side;
  nx_ = static_cast<std::int64_t>((hi.x() - lo.x()) * inv_side_) + 1;
  ny_ = static_cast<std::int64_t>((hi.y() - lo.y()) * inv_side_) + 1;
  keyed_.clear();
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].allFinite()) keyed_.emplace_back(key_of(points[i]), static_cast<int>(i));
  // Points grouped by cell, ascending index within a cell: counting sort on a dense grid.
  const std::int64_t cells = nx_ * ny_;
  if (cells <= 4 * static_cast<std::int64_t>(points.size()) + 4096) {
    cell_start_.assign(static_cast<std::size_t>(cells + 1), 0);
    for (const auto& e : keyed_) ++cell_start_[static_cast<std::size_t>(e.first) + 1];
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    sorted_.resize(keyed_.size());
    for (const auto& e : keyed_) sorted_[static_cast<std::size_t>(cell_start_[e.first]++)] = e;
    keyed_.swap(sorted_);
  } else {
    std::sort(keyed_.begin(), keyed_.end());
  }
  dense_ = cells <= 4 * static_cast<std::int64_t>(points.size()) + 4096;
  cells_.clear();
  cell_of_.assign(points.size(), -1);
  for (std::size_t k = 0; k < keyed_.size(); ++k) {
    if (k == 0 || keyed_[k].first != keyed_[k - 1].first)
      cells_.push_back({keyed_[k].first, static_cast<int>(k), static_cast<int>(k)});
    ++cells_.back().end;
    cell_of_[static_cast<std::size_t>(keyed_[k].second)] = static_cast<int>(cells_.size()) - 1;
  }
  if (dense_) {  // first occupied cell at or after every key: row ranges without a search
    first_cell_.resize(static_cast<std::size_t>(cells + 1));
    int c = 0;
    for (std::int64_t k = 0; k <= cells; ++k) {
      while (c < static_cast<int>(cells_.size()) && cells_[static_cast<std::size_t>(c)].key < k) ++c;
      first_cell_[static_cast<std::size_t>(k)] = c;
    }
  }
  return true;
}

std::pair<int, int> Dbscan::row_cells(std::int64_t cx, std::int64_t y) const {
  const std::int64_t k0 = y * nx_ + std::max<std::int64_t>(cx - kReach, 0);
  const std::int64_t k1 = y * nx_ + std::min<std::int64_t>(cx + kReach, nx_ - 1);
  if (dense_)
    return {first_cell_[static_cast<std::size_t>(k0)], first_cell_[static_cast<std::size_t>(k1 + 1)]};
  auto cmp = [](const Cell& c, std::int64_t k) { return c.key < k; };
  const auto a = std::lower_bound(cells_.begin(), cells_.end(), k0, cmp);
  const auto b = std::lower_bound(a, std::min(a + 2 * kReach + 1, cells_.end()), k1 + 1, cmp);
  return {static_cast<int>(a - cells_.begin()), static_cast<int>(b - cells_.begin())};
}

template <class F>
void Dbscan::for_neighbour_cells(int c, F&& f) const {
  const std::int64_t key = cells_[static_cast<std::size_t>(c)].key;
  const std::int64_t cx = key % nx_, cy = key / nx_;
  for (std::int64_t y = std::max<std::int64_t>(cy - kReach, 0); y <= std::min(cy + kReach, ny_ - 1);
       ++y) {
    const auto [a, b] = row_cells(cx, y);
    for (int d = a; d < b; ++d)
      if (!f(d)) return;
  }
}

void Dbscan::mark_core(const std::vector<Eigen::Vector2f>& points, float eps2, int min_pts) {
  core_.assign(points.size(), 0);
  for (int c = 0; c < static_cast<int>(cells_.size()); ++c) {
    const Cell& cell = cells_[static_cast<std::size_t>(c)];
    const int own = cell.end - cell.begin;
    for (int k = cell.begin; k < cell.end; ++k) {
      const auto i = static_cast<std::size_t>(keyed_[static_cast<std::size_t>(k)].second);
      int count = own;  // every point of the cell is within eps
      if (count < min_pts)
        for_neighbour_cells(c, [&](int d) {
          if (d == c) return true;
          const Cell& e = cells_[static_cast<std::size_t>(d)];
          for (int m = e.begin; m < e.end && count < min_pts; ++m)
            count += (points[static_cast<std::size_t>(keyed_[static_cast<std::size_t>(m)].second)] -
                      points[i]).squaredNorm() <= eps2;
          return count < min_pts;
        });
      core_[i] = count >= min_pts;
    }
  }
}

bool Dbscan::core_pair_within(const std::vector<Eigen::Vector2f>& points, const Cell& a,
                              const Cell& b, float eps2) const {
  for (int k = a.begin; k < a.end; ++k) {
    const auto i = static_cast<std::size_t>(keyed_[static_cast<std::size_t>(k)].second);
    if (!core_[i]) continue;
    for (int m = b.begin; m < b.end; ++m) {
      const auto j = static_cast<std::size_t>(keyed_[static_cast<std::size_t>(m)].second);
      if (core_[j] && (points[j] - points[i]).squaredNorm() <= eps2) return true;
    }
  }
  return false;
}

void Dbscan::join_cells(const std::vector<Eigen::Vector2f>& points, float eps2) {
  const int m = static_cast<int>(cells_.size());
  parent_.resize(static_cast<std::size_t>(m));
  cell_has_core_.assign(static_cast<std::size_t>(m), 0);
  for (int c = 0; c < m; ++c) {
    parent_[static_cast<std::size_t>(c)] = c;
    const Cell& cell = cells_[static_cast<std::size_t>(c)];
    for (int k = cell.begin; k < cell.end; ++k)
      cell_has_core_[static_cast<std::size_t>(c)] |=
          core_[static_cast<std::size_t>(keyed_[static_cast<std::size_t>(k)].second)];
  }
  for (int c = 0; c < m; ++c) {
    if (!cell_has_core_[static_cast<std::size_t>(c)]) continue;
    for_neighbour_cells(c, [&](int d) {  // each pair once: d > c
      if (d <= c || !cell_has_core_[static_cast<std::size_t>(d)]) return true;
      const int a = find_root(parent_, c), b = find_root(parent_, d);
      if (a != b && core_pair_within(points, cells_[static_cast<std::size_t>(c)],
                                     cells_[static_cast<std::size_t>(d)], eps2))
        parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      return true;
    });
  }
}

void Dbscan::label_cells(const std::vector<Eigen::Vector2f>& points, float eps2) {
  const std::size_t n = points.size();
  root_id_.assign(cells_.size(), -1);
  for (std::size_t i = 0; i < n; ++i) {  // clusters numbered by their lowest core point
    if (!core_[i]) continue;
    const auto r = static_cast<std::size_t>(find_root(parent_, cell_of_[i]));
    if (root_id_[r] < 0) root_id_[r] = clusters_++;
    labels_[i] = root_id_[r];
  }
  for (std::size_t i = 0; i < n; ++i) {  // border points: lowest-index core point within eps
    if (core_[i] || cell_of_[i] < 0) continue;
    int best = -1;
    for_neighbour_cells(cell_of_[i], [&](int d) {
      const Cell& e = cells_[static_cast<std::size_t>(d)];
      for (int m = e.begin; m < e.end; ++m) {  // ascending index: the first hit is the lowest
        const int j = keyed_[static_cast<std::size_t>(m)].second;
        if (best >= 0 && j >= best) break;
        const auto u = static_cast<std::size_t>(j);
        if (core_[u] && (d == cell_of_[i] || (points[u] - points[i]).squaredNorm() <= eps2)) {
          best = j;
          break;
        }
      }
      return true;
    });
    if (best >= 0) labels_[i] = labels_[static_cast<std::size_t>(best)];
  }
}

bool Dbscan::run_grid(const std::vector<Eigen::Vector2f>& points, float eps, int min_pts) {
  if (!build_cells(points, eps)) return false;
  if (keyed_.empty()) return true;
  const float eps2 = eps * eps;
  mark_core(points, eps2, min_pts);
  join_cells(points, eps2);
  label_cells(points, eps2);
  return true;
}

}  // namespace rownav::detect
