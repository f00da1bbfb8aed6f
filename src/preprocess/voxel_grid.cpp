// Voxel grid: integer keys, open-addressing hash, one accumulator per occupied voxel.
#include "rownav/preprocess/voxel_grid.hpp"

namespace rownav::preprocess {

void VoxelGridConfig::validate() const {
  core::check_non_negative(voxel_size, "voxel_size");
  core::check_positive(min_points_per_voxel, "min_points_per_voxel");
}

VoxelGrid::VoxelGrid(const VoxelGridConfig& config) : config_(config) {
  config_.validate();
  inv_ = config_.voxel_size > 0.0 ? static_cast<float>(1.0 / config_.voxel_size) : 0.0f;
}

void VoxelGrid::finish(std::span<const core::PointXYZIRT> in,
                       std::vector<core::PointXYZIRT>& out) const {
  const auto min_n = static_cast<std::uint32_t>(config_.min_points_per_voxel);
  for (const auto& v : acc_) {
    if (v.count < min_n) continue;
    const float k = 1.0f / static_cast<float>(v.count);
    core::PointXYZIRT q = in[v.first];
    q.x = v.x * k, q.y = v.y * k, q.z = v.z * k, q.intensity = v.intensity * k, q.time = v.time * k;
    out.push_back(q);
  }
}

void VoxelGrid::filter_indexed(std::span<const core::PointXYZIRT> cloud,
                               std::span<const CroppedPoint> pts,
                               std::vector<core::PointXYZIRT>& out) {
  out.clear();
  if (inv_ == 0.0f) {
    for (const auto& c : pts) out.push_back(cloud[c.index]);
    return;
  }
  start(pts.size());
  for (const auto& c : pts) add(c.x, c.y, c.z, cloud[c.index], c.index);
  finish(cloud, out);
}

void VoxelGrid::filter(std::span<const Eigen::Vector2f> in, std::vector<Eigen::Vector2f>& out) {
  out.clear();
  if (inv_ == 0.0f) {
    out.assign(in.begin(), in.end());
    return;
  }
  hash_.reset(std::min(in.size(), acc_.size() + acc_.size() / 2 + 64));
  acc_.clear();
  for (std::uint32_t i = 0; i < in.size(); ++i) {
    int ix = 0, iy = 0;
    if (!cell_index(in[i].x() * inv_, ix) || !cell_index(in[i].y() * inv_, iy)) continue;
    bool fresh = false;
    const auto a =
        hash_.find_or_insert(cell_key(ix, iy), static_cast<std::uint32_t>(acc_.size()), fresh);
    if (fresh) {
      acc_.push_back({in[i].x(), in[i].y(), 0.0f, 0.0f, 0.0f, 1u, i});
      continue;
    }
    acc_[a].x += in[i].x(), acc_[a].y += in[i].y();
    ++acc_[a].count;
  }
  const auto min_n = static_cast<std::uint32_t>(config_.min_points_per_voxel);
  for (const auto& v : acc_)
    if (v.count >= min_n)
      out.emplace_back(v.x / static_cast<float>(v.count), v.y / static_cast<float>(v.count));
}

}  // namespace rownav::preprocess
