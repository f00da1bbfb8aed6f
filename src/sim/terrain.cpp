#include "rownav/sim/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "rownav/core/angle.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace rownav::sim {
namespace {

// Smooth noise as a sum of plane waves of random direction, wavelength and phase. With K
// components of amplitude a the height std-dev is a * sqrt(K / 2).
constexpr int kWaves = 12;
constexpr int kStride = 4;  // kx, ky, phase, amplitude
// [m] downward rays start this far above the draped mesh's top and reach as far below its
// bottom: any margin > 0 works, it only keeps the start outside the mesh.
constexpr float kRayMargin = 1.0f;

TriangleMesh ground_part(const TriangleMesh& mesh) {
  TriangleMesh out;
  out.vertices = mesh.vertices;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    if (mesh.labels[i] == SurfaceClass::ground)
      out.add_triangle(mesh.triangles[i][0], mesh.triangles[i][1], mesh.triangles[i][2],
                       SurfaceClass::ground);
  return out;
}

}  // namespace

void TerrainConfig::validate() const {
  core::check_range(slope_x_deg, -45.0, 45.0, "slope_x_deg");
  core::check_range(slope_y_deg, -45.0, 45.0, "slope_y_deg");
  core::check_range(roughness, 0.0, 1.0, "roughness");
  core::check_positive(roughness_wavelength, "roughness_wavelength");
  core::check_range(cell_size, 0.05, 10.0, "cell_size");
}

Terrain::Terrain(const TerrainConfig& config) : config_(config) {
  config_.validate();
  gx_ = std::tan(core::deg2rad(config_.slope_x_deg));
  gy_ = std::tan(core::deg2rad(config_.slope_y_deg));
  if (config_.roughness <= 0.0) return;
  std::mt19937_64 rng(config_.seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
  std::uniform_real_distribution<double> scale(0.6, 1.6);
  const double amplitude = config_.roughness * std::sqrt(2.0 / kWaves);
  phase_.reserve(kWaves * kStride);
  for (int i = 0; i < kWaves; ++i) {
    const double dir = angle(rng);
    const double k = 2.0 * std::numbers::pi / (config_.roughness_wavelength * scale(rng));
    phase_.push_back(k * std::cos(dir));
    phase_.push_back(k * std::sin(dir));
    phase_.push_back(angle(rng));
    phase_.push_back(amplitude);
  }
}

void Terrain::drape(const TriangleMesh& mesh) {
  TriangleMesh ground = ground_part(mesh);
  if (ground.empty()) return;
  const Eigen::AlignedBox3f box = ground.bounds();
  ray_top_ = box.max().z() + kRayMargin;
  ray_length_ = box.sizes().z() + 2.0f * kRayMargin;
  ground_ = std::make_shared<const RayCaster>(ground);
}

bool Terrain::cast_down(double x, double y, double& z, Eigen::Vector3d* n) const {
  if (!ground_) return false;
  const RayHit hit = ground_->cast(
      Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), ray_top_),
      -Eigen::Vector3f::UnitZ(), 0.0f, ray_length_);
  if (!hit.hit()) return false;
  z = static_cast<double>(ray_top_) - static_cast<double>(hit.distance);
  if (n) *n = hit.normal.cast<double>().normalized();
  return true;
}

double Terrain::height(double x, double y) const {
  if (double zm = 0.0; cast_down(x, y, zm, nullptr)) return zm;
  double z = gx_ * x + gy_ * y;
  for (std::size_t i = 0; i + kStride <= phase_.size(); i += kStride)
    z += phase_[i + 3] * std::sin(phase_[i] * x + phase_[i + 1] * y + phase_[i + 2]);
  return z;
}

Eigen::Vector3d Terrain::normal(double x, double y) const {
  double zm = 0.0;
  if (Eigen::Vector3d n; cast_down(x, y, zm, &n)) return n;
  double dzdx = gx_, dzdy = gy_;
  for (std::size_t i = 0; i + kStride <= phase_.size(); i += kStride) {
    const double c = phase_[i + 3] * std::cos(phase_[i] * x + phase_[i + 1] * y + phase_[i + 2]);
    dzdx += c * phase_[i];
    dzdy += c * phase_[i + 1];
  }
  return Eigen::Vector3d(-dzdx, -dzdy, 1.0).normalized();
}

TriangleMesh Terrain::mesh(const Eigen::Vector2d& min, const Eigen::Vector2d& max) const {
  TriangleMesh out;
  const Eigen::Vector2d size = (max - min).cwiseMax(0.0);
  const int nx = std::max(1, static_cast<int>(std::ceil(size.x() / config_.cell_size)));
  const int ny = std::max(1, static_cast<int>(std::ceil(size.y() / config_.cell_size)));
  const double dx = size.x() / nx, dy = size.y() / ny;
  out.vertices.reserve(static_cast<std::size_t>(nx + 1) * (ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = min.x() + i * dx, y = min.y() + j * dy;
      out.add_vertex(Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y),
                                     static_cast<float>(height(x, y))));
    }
  const auto id = [nx](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  out.triangles.reserve(2 * static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // Counter-clockwise seen from above: normals point up.
      out.add_triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1), SurfaceClass::ground);
      out.add_triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1), SurfaceClass::ground);
    }
  return out;
}

}  // namespace rownav::sim
