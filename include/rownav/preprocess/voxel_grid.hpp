#pragma once
/// @file voxel_grid.hpp Voxel-grid downsampling to one centroid per occupied voxel (Nehme 2021
/// sec. 4: 0.15 m; as pcl::VoxelGrid). Single pass over integer voxel keys with an
/// open-addressing hash; buffers reused across frames.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/cell_hash.hpp"

namespace rownav::preprocess {

/// Voxel grid parameters. Voxel (i, j, k) covers [i s, (i + 1) s) x ... with s = voxel_size.
struct VoxelGridConfig {
  double voxel_size = 0.15;   ///< [m] voxel edge, 0 = no downsampling (Nehme 2021 sec. 4)
  int min_points_per_voxel = 1;  ///< [-] voxels with fewer points are dropped (PCL default 0/1)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("voxel_size", s.voxel_size);
    v("min_points_per_voxel", s.min_points_per_voxel);
  }
  void validate() const;
};

/// Voxel-grid filter. Output order: voxels by first point. Points whose voxel index overflows
/// 21 bits (|coordinate| > ~1e6 voxel sizes) are dropped. Never throws after construction.
class VoxelGrid {
 public:
  explicit VoxelGrid(const VoxelGridConfig& config = {});
  /// 3D: centroid of x, y, z, intensity and time; ring / column of the voxel's first point.
  /// With voxel_size 0, copies. `out` is cleared first; `in` and `out` must not alias.
  void filter(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out);
  /// 2D (pixels of voxel_size): centroid of each occupied pixel.
  void filter(std::span<const Eigen::Vector2f> in, std::vector<Eigen::Vector2f>& out);
  const VoxelGridConfig& config() const { return config_; }

 private:
  struct Acc {  // float sums: < 1e-4 m error for the few hundred points of a voxel
    float x, y, z, intensity, time;
    std::uint32_t count, first;
  };
  VoxelGridConfig config_;
  float inv_ = 0.0f;
  CellHash hash_;
  std::vector<Acc> acc_;
};

}  // namespace rownav::preprocess
