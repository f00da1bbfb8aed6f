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
#include "rownav/preprocess/cropped_point.hpp"

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
  /// As filter() on the points of `in` for which keep(p) holds, in one pass. Same output as
  /// filtering a copy.
  /// Every point is looked up in the hash: a "same voxel as the previous point" shortcut costs
  /// more in mispredicted branches than it saves (bench/preprocess_bench.cpp, BM_ChainStep/3).
  template <class Keep>
  void filter_if(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out,
                 Keep&& keep);
  /// As filter() on the cloud points pts[j].index, in the order of `pts`, with the coordinates
  /// of `pts` (the preprocessor's cropped points): the other fields are read from `cloud` only for
  /// these points. Same output as filter() on the gathered points. `out` must not alias `cloud`.
  void filter_indexed(std::span<const core::PointXYZIRT> cloud, std::span<const CroppedPoint> pts,
                      std::vector<core::PointXYZIRT>& out);
  /// 2D (pixels of voxel_size): centroid of each occupied pixel.
  void filter(std::span<const Eigen::Vector2f> in, std::vector<Eigen::Vector2f>& out);
  const VoxelGridConfig& config() const { return config_; }

 private:
  void finish(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out) const;
  void start(std::size_t n) {
    // Size the table for last frame's voxel count (it grows if needed): it stays in cache.
    hash_.reset(std::min(n, acc_.size() + acc_.size() / 2 + 64));
    acc_.clear();
  }
  /// Adds point `first` (index in the cloud) at (x, y, z) to its voxel's sums.
  void add(float x, float y, float z, const core::PointXYZIRT& p, std::uint32_t first) {
    int ix = 0, iy = 0, iz = 0;
    if (!cell_index(x * inv_, ix) || !cell_index(y * inv_, iy) || !cell_index(z * inv_, iz)) return;
    bool fresh = false;
    const std::uint32_t a =
        hash_.find_or_insert(cell_key(ix, iy, iz), static_cast<std::uint32_t>(acc_.size()), fresh);
    if (fresh) {
      acc_.push_back({x, y, z, p.intensity, p.time, 1u, first});
      return;
    }
    Acc& v = acc_[a];
    v.x += x, v.y += y, v.z += z, v.intensity += p.intensity, v.time += p.time;
    ++v.count;
  }
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
  start(in.size());
  for (std::uint32_t i = 0; i < in.size(); ++i) {
    const auto& p = in[i];
    if (keep(p)) add(p.x, p.y, p.z, p, i);
  }
  finish(in, out);
}

}  // namespace rownav::preprocess
