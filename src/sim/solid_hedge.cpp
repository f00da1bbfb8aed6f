// Solid-hedge canopy (issue 10): a real photogrammetric vineyard mesh is a continuous mound from
// the ground to ~1.8 m with no trunk zone, so a LiDAR inside a corridor sees only the two inner
// faces. Each vine contributes one closed, slightly rough prism piece of that mound.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "rownav/sim/vineyard.hpp"

namespace rownav::sim {
namespace {

constexpr int kProfileSegments = 12;  // cross-section polygon: foot, faces, crown, foot
constexpr double kOverlap = 0.02;     // [m] pieces overlap along the row: no cracks
constexpr double kBelowGround = 0.05; // [m] feet below the ground: rough terrain shows no gap

using V3 = Eigen::Vector3f;

/// Cross-section of the superellipse |y / hw|^p + (z / top)^p = 1 from the left foot over the
/// crown to the right foot: (y across, left +; z up), each vertex moved by the roughness.
std::vector<Eigen::Vector2d> hedge_profile(double hw, double top, double p, double roughness,
                                           std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i <= kProfileSegments; ++i) {
    const double t = std::numbers::pi * i / kProfileSegments;  // 0: left foot, pi: right foot
    const double c = std::cos(t), s = std::sin(t);
    const double y = hw * std::copysign(std::pow(std::abs(c), 2.0 / p), c);
    const double z = top * std::pow(std::abs(s), 2.0 / p);
    const bool foot = i == 0 || i == kProfileSegments;
    out.emplace_back(y + roughness * hw * u(rng), foot ? -kBelowGround : z);
  }
  return out;
}

}  // namespace

double add_hedge_segment(TriangleMesh& mesh, const Eigen::Vector3d& base,
                         const Eigen::Vector2d& tangent, const VineyardConfig& c,
                         std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Vine-to-vine vigour: +-10 % width, +-5 % height (a trimmed hedge is regular).
  const double hw = 0.5 * c.canopy_width * (0.9 + 0.2 * u(rng));
  const double top = c.canopy_top * (0.95 + 0.1 * u(rng));
  const V3 b = base.cast<float>();
  const V3 along(static_cast<float>(tangent.x()), static_cast<float>(tangent.y()), 0.0f);
  const V3 across(-along.y(), along.x(), 0.0f), up = V3::UnitZ();
  const float half_len = static_cast<float>(0.5 * c.plant_spacing + kOverlap);
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  const int n = kProfileSegments + 1;
  for (const float side : {-1.0f, 1.0f}) {
    const auto prof = hedge_profile(hw, top, c.hedge_roundness, c.hedge_roughness, rng);
    for (const auto& q : prof)
      mesh.add_vertex(b + side * half_len * along + static_cast<float>(q.x()) * across +
                      static_cast<float>(q.y()) * up);
  }
  const auto v = [&](int end, int i) { return first + static_cast<std::uint32_t>(end * n + i); };
  for (int i = 0; i + 1 < n; ++i) {  // faces and crown
    mesh.add_triangle(v(0, i), v(1, i), v(1, i + 1), SurfaceClass::canopy);
    mesh.add_triangle(v(0, i), v(1, i + 1), v(0, i + 1), SurfaceClass::canopy);
  }
  for (int i = 1; i + 1 < n; ++i) {  // end caps: fans from the left foot
    mesh.add_triangle(v(0, 0), v(0, i + 1), v(0, i), SurfaceClass::canopy);
    mesh.add_triangle(v(1, 0), v(1, i), v(1, i + 1), SurfaceClass::canopy);
  }
  mesh.add_triangle(v(0, 0), v(0, n - 1), v(1, n - 1), SurfaceClass::canopy);  // bottom
  mesh.add_triangle(v(0, 0), v(1, n - 1), v(1, 0), SurfaceClass::canopy);
  return top;
}

}  // namespace rownav::sim
