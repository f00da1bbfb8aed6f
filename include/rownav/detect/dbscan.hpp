#pragma once
/// @file dbscan.hpp DBSCAN on 2D points (Ester 1996; Schubert 2017, as used by Emmi 2021,
/// 002_806e72d300173f73.txt), with a grid or a kd-tree neighbour search.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"

namespace rownav::detect {

/// How DBSCAN finds the eps-neighbours of a point.
enum class NeighbourSearch : std::uint8_t {
  grid,    ///< uniform grid of eps cells, 3x3 cells a query (faster: see bench/cluster_bench.cpp)
  kd_tree  ///< nanoflann kd-tree radius search
};

/// Reusable DBSCAN: buffers are kept between calls, so one instance per thread.
class Dbscan {
 public:
  /// Labels every point: cluster id >= 0, or -1 for noise (and for non-finite points). A point
  /// is core with >= min_pts points (itself included) within eps. Clusters are numbered in the
  /// order of their lowest core point index, so the result is deterministic. Never throws for
  /// eps > 0 and min_pts >= 1; other values give all noise.
  const std::vector<int>& run(const std::vector<Eigen::Vector2f>& points, double eps, int min_pts,
                              NeighbourSearch search = NeighbourSearch::grid);
  /// Number of clusters of the last run.
  int cluster_count() const { return clusters_; }

 private:
  void neighbours_grid(const std::vector<Eigen::Vector2f>& points, float eps);
  void neighbours_kd_tree(const std::vector<Eigen::Vector2f>& points, float eps);
  void label(std::size_t n, int min_pts);

  std::vector<int> labels_;
  std::vector<int> offsets_;     // CSR neighbour lists: neighbours of i in adj_[offsets_[i]..)
  std::vector<int> adj_;
  std::vector<std::pair<std::int64_t, int>> keyed_;  // (cell key, point) sorted
  std::vector<int> cell_start_;
  std::vector<int> parent_;
  int clusters_ = 0;
};

}  // namespace rownav::detect

template <>
struct rownav::core::EnumNames<rownav::detect::NeighbourSearch> {
  using E = rownav::detect::NeighbourSearch;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::grid, "grid"}, {E::kd_tree, "kd_tree"}}};
};
