// DBSCAN (Ester 1996; "DBSCAN revisited, revisited", Schubert 2017, cited by Emmi 2021) in 2D,
// kd-tree variant: neighbour lists (CSR) from nanoflann, core points joined by union-find, border
// points given to the cluster of their first core neighbour. The grid variant: dbscan_grid.cpp.
#include "rownav/detect/dbscan.hpp"

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>
#include <numeric>

namespace rownav::detect {
namespace {

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
  const auto e = static_cast<float>(eps);
  if (search == NeighbourSearch::grid && run_grid(points, e, min_pts)) return labels_;
  neighbours_kd_tree(points, e);  // or a grid too large for the extent of the points
  label(points.size(), min_pts);
  return labels_;
}

}  // namespace rownav::detect
