#pragma once
/// @file voxel_grid.hpp Voxel-grid downsampling to one centroid per occupied voxel (Nehme 2021
/// sec. 4: 0.15 m; as pcl::VoxelGrid). Single pass over integer voxel keys with an
/// open-addressing hash; buffers reused across frames.
#include <Eigen/Core>
#include <algorithm>
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
  void filter(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out) {
    filter_if(in, out, [](const core::PointXYZIRT&) { return true; });
  }
  /// As filter() on the points of `in` for which keep(p) holds, in one pass (the preprocessor
  /// fuses its height band into the voxel pass this way). Same output as filtering a copy.
  /// Every point is looked up in the hash: a "same voxel as the previous point" shortcut costs
  /// more in mispredicted branches than it saves (bench/preprocess_bench.cpp, BM_ChainStep/3).
  template <class Keep>
  void filter_if(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out,
                 Keep&& keep);
  /// 2D (pixels of voxel_size): centroid of each occupied pixel.
  void filter(std::span<const Eigen::Vector2f> in, std::vector<Eigen::Vector2f>& out);
  const VoxelGridConfig& config() const { return config_; }

 private:
  void finish(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out) const;
  struct Acc {  // float sums: < 1e-4 m error for the few hundred points of a voxel
    float x, y, z, intensity, time;
    std::uint32_t count, first;
  };
  VoxelGridConfig config_;
  float inv_ = 0.0f;
  CellHash hash_;
  std::vector<Acc> acc_;
};

template <class Keep>
void VoxelGrid::filter_if(std::span<const core::PointXYZIRT> in,
                          std::vector<core::PointXYZIRT>& out, Keep&& keep) {
  out.clear();
  if (inv_ == 0.0f) {
    for (const auto& p : in)
      if (keep(p)) out.push_back(p);
    return;
  }
  // Size the table for last frame's voxel count (it grows if needed) so that it stays in cache.
  hash_.reset(std::min(in.size(), acc_.size() + acc_.size() / 2 + 64));
  acc_.clear();
  for (std::uint32_t i = 0; i < in.size(); ++i) {
    const auto& p = in[i];
    int ix = 0, iy = 0, iz = 0;
    if (!keep(p) || !cell_index(p.x * inv_, ix) || !cell_index(p.y * inv_, iy) ||
        !cell_index(p.z * inv_, iz))
      continue;
    bool fresh = false;
    const std::uint32_t a = hash_.find_or_insert(cell_key(ix, iy, iz),
                                                 static_cast<std::uint32_t>(acc_.size()), fresh);
    if (fresh) {
      acc_.push_back({p.x, p.y, p.z, p.intensity, p.time, 1u, i});
      continue;
    }
    Acc& v = acc_[a];
    v.x += p.x, v.y += p.y, v.z += p.z, v.intensity += p.intensity, v.time += p.time;
    ++v.count;
  }
  finish(in, out);
}

}  // namespace rownav::preprocess
