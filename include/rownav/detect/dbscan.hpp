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
  grid,    ///< grid DBSCAN: cells of side 0.7 eps, dense cells all core, cells joined by one
           ///< core pair (faster on stacked points: see bench/cluster_bench.cpp); same labels
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
  struct Cell {  // an occupied grid cell: its points are keyed_[begin, end)
    std::int64_t key;
    int begin, end;
  };
  // kd-tree variant (dbscan.cpp): neighbour lists, then labels.
  void neighbours_kd_tree(const std::vector<Eigen::Vector2f>& points, float eps);
  void label(std::size_t n, int min_pts);
  // Grid variant (dbscan_grid.cpp). False when the points span too many cells.
  bool run_grid(const std::vector<Eigen::Vector2f>& points, float eps, int min_pts);
  bool build_cells(const std::vector<Eigen::Vector2f>& points, float eps);
  std::pair<int, int> row_cells(std::int64_t cx, std::int64_t y) const;
  template <class F>
  void for_neighbour_cells(int c, F&& f) const;
  void mark_core(const std::vector<Eigen::Vector2f>& points, float eps2, int min_pts);
  bool core_pair_within(const std::vector<Eigen::Vector2f>& points, const Cell& a, const Cell& b,
                        float eps2) const;
  void join_cells(const std::vector<Eigen::Vector2f>& points, float eps2);
  void label_cells(const std::vector<Eigen::Vector2f>& points, float eps2);
  std::int64_t key_of(const Eigen::Vector2f& p) const {
    return static_cast<std::int64_t>((p.y() - lo_.y()) * inv_side_) * nx_ +
           static_cast<std::int64_t>((p.x() - lo_.x()) * inv_side_);
  }

  std::vector<int> labels_;
  std::vector<int> offsets_;  // CSR neighbour lists: neighbours of i in adj_[offsets_[i]..)
  std::vector<int> adj_;
  std::vector<int> parent_;   // union-find: points (kd-tree), cells (grid)
  int clusters_ = 0;
  // grid: origin, 1 / cell side, cells per row; (cell key, point) grouped by cell
  Eigen::Vector2f lo_ = Eigen::Vector2f::Zero();
  float inv_side_ = 1.0f;
  std::int64_t nx_ = 1, ny_ = 1;
  bool dense_ = false;  // first_cell_ holds, for every key, the first occupied cell at or after
  std::vector<std::pair<std::int64_t, int>> keyed_, sorted_;
  std::vector<int> cell_start_, cell_of_, root_id_, first_cell_;
  std::vector<Cell> cells_;
  std::vector<char> core_, cell_has_core_;
};

}  // namespace rownav::detect

template <>
struct rownav::core::EnumNames<rownav::detect::NeighbourSearch> {
  using E = rownav::detect::NeighbourSearch;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::grid, "grid"}, {E::kd_tree, "kd_tree"}}};
};
