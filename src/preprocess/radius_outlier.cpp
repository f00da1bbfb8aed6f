// Radius outlier removal over a hashed grid (cells of edge = radius, 3^D neighbour cells).
#include "rownav/preprocess/radius_outlier.hpp"

namespace rownav::preprocess {

void RadiusOutlierConfig::validate() const {
  core::check_positive(radius, "radius");
  core::check_non_negative(min_neighbors, "min_neighbors");
}

RadiusOutlier::RadiusOutlier(const RadiusOutlierConfig& config) : config_(config) {
  config_.validate();
}

template <int D, class Get>
void RadiusOutlier::mark(std::size_t n, Get get) {
  const float inv = static_cast<float>(1.0 / config_.radius);
  const float r2 = static_cast<float>(config_.radius * config_.radius);
  const auto need = static_cast<std::uint32_t>(config_.min_neighbors);
  constexpr std::uint32_t kDrop = CellHash::kNone;
  hash_.reset(n);
  ijk_.resize(n);
  cell_of_.resize(n);
  keep_.assign(n, 0);
  start_.assign(1, 0);
  // Cells, then a counting sort of the point indices by cell (CSR).
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f p = get(i);
    auto& c = ijk_[i];
    c = {0, 0, 0};
    if (!cell_index(p.x() * inv, c[0]) || !cell_index(p.y() * inv, c[1]) ||
        (D == 3 && !cell_index(p.z() * inv, c[2]))) {
      cell_of_[i] = kDrop;
      continue;
    }
    bool fresh = false;
    cell_of_[i] = hash_.find_or_insert(cell_key(c[0], c[1], c[2]),
                                       static_cast<std::uint32_t>(start_.size() - 1), fresh);
    if (fresh) start_.push_back(0);
    ++start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  order_.resize(start_.back());
  for (std::size_t i = 0; i < n; ++i)
    if (cell_of_[i] != kDrop) order_[start_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
  for (std::size_t c = start_.size() - 1; c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
  constexpr int dz = D == 3 ? 1 : 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (cell_of_[i] == kDrop) continue;
    if (need == 0) {
      keep_[i] = 1;
      continue;
    }
    const Eigen::Vector3f p = get(i);
    std::uint32_t found = 0;
    for (int z = -dz; z <= dz && found < need; ++z)
      for (int y = -1; y <= 1 && found < need; ++y)
        for (int x = -1; x <= 1 && found < need; ++x) {
          const auto& c = ijk_[i];
          const auto cell = hash_.find(cell_key(c[0] + x, c[1] + y, c[2] + z));
          if (cell == CellHash::kNone) continue;
          for (auto k = start_[cell]; k < start_[cell + 1] && found < need; ++k) {
            const auto j = order_[k];
            found += j != i && (get(j) - p).squaredNorm() <= r2;
          }
        }
    keep_[i] = found >= need;
  }
}

void RadiusOutlier::filter(std::span<const core::PointXYZIRT> in,
                           std::vector<core::PointXYZIRT>& out) {
  mark<3>(in.size(), [&](std::size_t i) { return Eigen::Vector3f(in[i].x, in[i].y, in[i].z); });
  out.clear();
  for (std::size_t i = 0; i < in.size(); ++i)
    if (keep_[i]) out.push_back(in[i]);
}

void RadiusOutlier::filter(std::span<const Eigen::Vector2f> in, std::vector<Eigen::Vector2f>& out) {
  mark<2>(in.size(), [&](std::size_t i) { return Eigen::Vector3f(in[i].x(), in[i].y(), 0.0f); });
  out.clear();
  for (std::size_t i = 0; i < in.size(); ++i)
    if (keep_[i]) out.push_back(in[i]);
}

}  // namespace rownav::preprocess
