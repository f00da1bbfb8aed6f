#include "rownav/sim/mesh_labels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rownav::sim {
namespace {

/// Lowest vertex z per grid cell over the mesh's xy bounds.
struct MinGrid {
  Eigen::Vector2f origin;
  float cell;
  int nx, ny;
  std::vector<float> z;

  MinGrid(const TriangleMesh& mesh, float cell_size) : cell(cell_size) {
    const Eigen::AlignedBox3f box = mesh.bounds();
    origin = box.min().head<2>();
    nx = std::max(1, static_cast<int>(std::ceil(box.sizes().x() / cell)) + 1);
    ny = std::max(1, static_cast<int>(std::ceil(box.sizes().y() / cell)) + 1);
    z.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny),
             std::numeric_limits<float>::infinity());
    for (const auto& v : mesh.vertices) {
      float& m = at(index(v.x(), 0), index(v.y(), 1));
      m = std::min(m, v.z());
    }
  }
  int index(float c, int axis) const {
    const int n = axis == 0 ? nx : ny;
    return std::clamp(static_cast<int>((c - origin(axis)) / cell), 0, n - 1);
  }
  float& at(int i, int j) { return z[static_cast<std::size_t>(j) * nx + i]; }
  /// Lowest z in the 3 x 3 cells around (x, y).
  float ground(float x, float y) {
    const int i0 = index(x, 0), j0 = index(y, 1);
    float m = std::numeric_limits<float>::infinity();
    for (int j = std::max(0, j0 - 1); j <= std::min(ny - 1, j0 + 1); ++j)
      for (int i = std::max(0, i0 - 1); i <= std::min(nx - 1, i0 + 1); ++i) m = std::min(m, at(i, j));
    return m;
  }
};

}  // namespace

void MeshLabelConfig::validate() const {
  core::check_range(cell_size, 0.1, 100.0, "cell_size");
  core::check_range(ground_band, 0.0, 10.0, "ground_band");
}

void label_mesh(TriangleMesh& mesh, const MeshLabelConfig& config) {
  config.validate();
  mesh.labels.assign(mesh.triangles.size(), SurfaceClass::ground);
  if (config.rule == MeshLabelRule::ground || mesh.empty()) return;
  MinGrid grid(mesh, static_cast<float>(config.cell_size));
  const std::size_t n = mesh.triangles.size();
  for (std::size_t t = 0; t < n; ++t) {
    Eigen::Vector3f c = Eigen::Vector3f::Zero();
    for (const auto v : mesh.triangles[t]) c += mesh.vertices[v];
    c /= 3.0f;
    if (c.z() - grid.ground(c.x(), c.y()) <= static_cast<float>(config.ground_band)) continue;
    mesh.labels[t] = SurfaceClass::canopy;
    // A height-map mesh has no ground under its canopy: a copy of the triangle on the local
    // ground closes the hole, so the ground is continuous for Terrain::drape.
    std::array<std::uint32_t, 3> ids{};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3f v = mesh.vertices[mesh.triangles[t][static_cast<std::size_t>(k)]];
      ids[static_cast<std::size_t>(k)] =
          mesh.add_vertex(Eigen::Vector3f(v.x(), v.y(), grid.ground(v.x(), v.y())));
    }
    mesh.add_triangle(ids[0], ids[1], ids[2], SurfaceClass::ground);
  }
}

}  // namespace rownav::sim
