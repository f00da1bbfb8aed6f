// DBSCAN (Ester 1996; "DBSCAN revisited, revisited", Schubert 2017, cited by Emmi 2021) in 2D:
// neighbour lists (CSR) from a grid or a kd-tree, core points joined by union-find, border
// points given to the cluster of their first core neighbour.
#include "rownav/detect/dbscan.hpp"

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>
#include <numeric>

namespace rownav::detect {
namespace {

constexpr std::int64_t kMaxDenseCells = 1 << 20;

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    auto& p = parent[static_cast<std::size_t>(i)];
    p = parent[static_cast<std::size_t>(p)];  // path halving
    i = p;
  }
  return i;
}

// nanoflann dataset adaptor over the point vector (finite points only are indexed).
struct PointsAdaptor {
  const std::vector<Eigen::Vector2f>& pts;
  const std::vector<int>& index;  // indexed point -> original point
  std::size_t kdtree_get_point_count() const { return index.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return pts[static_cast<std::size_t>(index[i])][static_cast<int>(dim)];
  }
  template <class B>
  bool kdtree_get_bbox(B&) const { return false; }
};

}  // namespace

void Dbscan::neighbours_grid(const std::vector<Eigen::Vector2f>& points, float eps) {
  const std::size_t n = points.size();
  Eigen::Vector2f lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& p : points)
    if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.x() <= hi.x()) || ((hi - lo) / eps).maxCoeff() > 1e8f) {  // none finite, or far apart
    neighbours_kd_tree(points, eps);
    return;
  }
  const std::int64_t nx = static_cast<std::int64_t>((hi.x() - lo.x()) / eps) + 1;
  const std::int64_t ny = static_cast<std::int64_t>((hi.y() - lo.y()) / eps) + 1;
  keyed_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) continue;
    const auto cx = static_cast<std::int64_t>((points[i].x() - lo.x()) / eps);
    const auto cy = static_cast<std::int64_t>((points[i].y() - lo.y()) / eps);
    keyed_.emplace_back(cy * nx + cx, static_cast<int>(i));
  }
  std::sort(keyed_.begin(), keyed_.end());
  const bool dense = nx * ny <= std::max<std::int64_t>(kMaxDenseCells, 4 * static_cast<std::int64_t>(n));
  if (dense) {  // start of every cell in keyed_, one extra at the end
    cell_start_.assign(static_cast<std::size_t>(nx * ny + 1), 0);
    for (const auto& [key, i] : keyed_) ++cell_start_[static_cast<std::size_t>(key) + 1];
    std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  }
  // Range of keyed_ holding the cells [k0, k1] of one grid row.
  auto range = [&](std::int64_t k0, std::int64_t k1) -> std::pair<int, int> {
    if (dense)
      return {cell_start_[static_cast<std::size_t>(k0)], cell_start_[static_cast<std::size_t>(k1) + 1]};
    auto cmp = [](const auto& e, std::int64_t k) { return e.first < k; };
    const auto a = std::lower_bound(keyed_.begin(), keyed_.end(), k0, cmp);
    const auto b = std::lower_bound(a, keyed_.end(), k1 + 1, cmp);
    return {static_cast<int>(a - keyed_.begin()), static_cast<int>(b - keyed_.begin())};
  };
  const float eps2 = eps * eps;
  offsets_.assign(n + 1, 0);
  adj_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    offsets_[i] = static_cast<int>(adj_.size());
    if (!points[i].allFinite()) continue;
    const auto cx = static_cast<std::int64_t>((points[i].x() - lo.x()) / eps);
    const auto cy = static_cast<std::int64_t>((points[i].y() - lo.y()) / eps);
    for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min(cy + 1, ny - 1); ++y) {
      const auto [a, b] = range(y * nx + std::max<std::int64_t>(cx - 1, 0), y * nx + std::min(cx + 1, nx - 1));
      for (int k = a; k < b; ++k) {
        const int j = keyed_[static_cast<std::size_t>(k)].second;
        if ((points[static_cast<std::size_t>(j)] - points[i]).squaredNorm() <= eps2) adj_.push_back(j);
      }
    }
  }
  offsets_[n] = static_cast<int>(adj_.size());
}

void Dbscan::neighbours_kd_tree(const std::vector<Eigen::Vector2f>& points, float eps) {
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointsAdaptor>,
                                                   PointsAdaptor, 2, std::size_t>;
  const std::size_t n = points.size();
  std::vector<int> index;
  for (std::size_t i = 0; i < n; ++i)
    if (points[i].allFinite()) index.push_back(static_cast<int>(i));
  const PointsAdaptor adaptor{points, index};
  Tree tree(2, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  std::vector<std::pair<std::size_t, float>> matches;
  nanoflann::SearchParams params;
  params.sorted = false;
  offsets_.assign(n + 1, 0);
  adj_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    offsets_[i] = static_cast<int>(adj_.size());
    if (!points[i].allFinite()) continue;
    tree.radiusSearch(points[i].data(), eps * eps, matches, params);  // L2_Simple: squared radius
    for (const auto& m : matches) adj_.push_back(index[m.first]);
  }
  offsets_[n] = static_cast<int>(adj_.size());
}

void Dbscan::label(std::size_t n, int min_pts) {
  auto is_core = [&](std::size_t i) { return offsets_[i + 1] - offsets_[i] >= min_pts; };
  parent_.resize(n);
  std::iota(parent_.begin(), parent_.end(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_core(i)) continue;
    for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(adj_[static_cast<std::size_t>(k)]);
      if (j >= i || !is_core(j)) continue;
      const int a = find_root(parent_, static_cast<int>(i)), b = find_root(parent_, static_cast<int>(j));
      if (a != b) parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);  // root = lowest index
    }
  }
  labels_.assign(n, -1);
  std::vector<int> id_of_root(n, -1);
  clusters_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_core(i)) continue;
    const auto r = static_cast<std::size_t>(find_root(parent_, static_cast<int>(i)));
    if (id_of_root[r] < 0) id_of_root[r] = clusters_++;
    labels_[i] = id_of_root[r];
  }
  for (std::size_t i = 0; i < n; ++i) {  // border points: first core neighbour (lowest index)
    if (labels_[i] >= 0 || offsets_[i + 1] == offsets_[i]) continue;
    int best = -1;
    for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const int j = adj_[static_cast<std::size_t>(k)];
      if (is_core(static_cast<std::size_t>(j)) && (best < 0 || j < best)) best = j;
    }
    if (best >= 0) labels_[i] = labels_[static_cast<std::size_t>(best)];
  }
}

const std::vector<int>& Dbscan::run(const std::vector<Eigen::Vector2f>& points, double eps,
                                    int min_pts, NeighbourSearch search) {
  clusters_ = 0;
  labels_.assign(points.size(), -1);
  if (!(eps > 0.0) || !std::isfinite(eps) || min_pts < 1 || points.empty()) return labels_;
  if (search == NeighbourSearch::kd_tree)
    neighbours_kd_tree(points, static_cast<float>(eps));
  else
    neighbours_grid(points, static_cast<float>(eps));
  label(points.size(), min_pts);
  return labels_;
}

}  // namespace rownav::detect
