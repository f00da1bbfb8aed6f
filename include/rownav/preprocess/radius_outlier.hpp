#pragma once
/// @file radius_outlier.hpp Radius outlier removal (as pcl::RadiusOutlierRemoval; Bertoglio 2023
/// sec. II-A outlier filtering): a point is kept when at least `min_neighbors` other points lie
/// within `radius`. Neighbours are found with a hashed grid of cells of edge `radius`.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/cell_hash.hpp"

namespace rownav::preprocess {

/// Radius outlier parameters.
struct RadiusOutlierConfig {
  bool enabled = false;  ///< run the filter (off by default: Nehme 2021 does not use it)
  double radius = 0.3;   ///< [m] neighbourhood radius (about two 0.15 m voxels)
  int min_neighbors = 2;  ///< [-] other points needed within radius to keep a point

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("radius", s.radius);
    v("min_neighbors", s.min_neighbors);
  }
  void validate() const;
};

/// Radius outlier filter, 3D (x, y, z) or 2D. Buffers reused; never throws after construction.
/// The `enabled` flag is the caller's business: filter() always filters.
class RadiusOutlier {
 public:
  explicit RadiusOutlier(const RadiusOutlierConfig& config = {});
  /// `out` is cleared first; `in` and `out` must not alias.
  void filter(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out);
  void filter(std::span<const Eigen::Vector2f> in, std::vector<Eigen::Vector2f>& out);
  const RadiusOutlierConfig& config() const { return config_; }

 private:
  template <int D, class Get>
  void mark(std::size_t n, Get get);

  RadiusOutlierConfig config_;
  CellHash hash_;
  std::vector<std::array<int, 3>> ijk_;
  std::vector<std::uint32_t> cell_of_, start_, order_;
  std::vector<std::uint8_t> keep_;
};

}  // namespace rownav::preprocess
