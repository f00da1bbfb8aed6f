#include "rownav/sim/plant_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rownav::sim {
namespace {

using V3 = Eigen::Vector3f;

/// Two unit vectors orthogonal to `axis` (unit) and to each other.
std::pair<V3, V3> orthonormal_basis(const V3& axis) {
  const V3 helper = std::abs(axis.z()) < 0.9f ? V3::UnitZ() : V3::UnitX();
  const V3 u = axis.cross(helper).normalized();
  return {u, axis.cross(u)};
}

// Unit icosahedron (golden-ratio construction), CCW faces seen from outside.
const std::array<V3, 12>& icosahedron_vertices() {
  static const std::array<V3, 12> v = [] {
    const float p = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::array<V3, 12> out{V3(-1, p, 0), V3(1, p, 0), V3(-1, -p, 0), V3(1, -p, 0),
                           V3(0, -1, p), V3(0, 1, p), V3(0, -1, -p), V3(0, 1, -p),
                           V3(p, 0, -1), V3(p, 0, 1), V3(-p, 0, -1), V3(-p, 0, 1)};
    for (auto& x : out) x.normalize();
    return out;
  }();
  return v;
}
constexpr std::array<std::array<std::uint32_t, 3>, 20> kIcoFaces{
    {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
     {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
     {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}}};
constexpr std::array<std::array<std::uint32_t, 3>, 8> kOctFaces{
    {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}}};

}  // namespace

void add_cylinder(TriangleMesh& mesh, const V3& a, const V3& b, float radius, int sides,
                  SurfaceClass label, bool cap) {
  const V3 axis = b - a;
  if (axis.norm() <= 0.0f || sides < 3) return;
  const auto [u, w] = orthonormal_basis(axis.normalized());
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int i = 0; i < sides; ++i) {
    const float ang = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / sides;
    const V3 off = radius * (std::cos(ang) * u + std::sin(ang) * w);
    mesh.add_vertex(a + off);
    mesh.add_vertex(b + off);
  }
  const auto n = static_cast<std::uint32_t>(sides);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    mesh.add_triangle(base + 2 * i, base + 2 * j, base + 2 * j + 1, label);
    mesh.add_triangle(base + 2 * i, base + 2 * j + 1, base + 2 * i + 1, label);
  }
  if (!cap) return;
  const std::uint32_t centre = mesh.add_vertex(b);
  for (std::uint32_t i = 0; i < n; ++i)
    mesh.add_triangle(centre, base + 2 * i + 1, base + 2 * ((i + 1) % n) + 1, label);
}

void add_blob(TriangleMesh& mesh, const V3& c, const V3& radii, float jitter, std::mt19937_64& rng,
              SurfaceClass label, bool coarse) {
  std::uniform_real_distribution<float> push(1.0f - jitter, 1.0f + jitter);
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  if (coarse) {
    static const std::array<V3, 6> oct{V3::UnitX(),  -V3::UnitX(), V3::UnitY(),
                                       -V3::UnitY(), V3::UnitZ(),  -V3::UnitZ()};
    for (const auto& v : oct) mesh.add_vertex(c + push(rng) * v.cwiseProduct(radii));
    for (const auto& f : kOctFaces) mesh.add_triangle(base + f[0], base + f[1], base + f[2], label);
    return;
  }
  for (const auto& v : icosahedron_vertices())
    mesh.add_vertex(c + push(rng) * v.cwiseProduct(radii));
  for (const auto& f : kIcoFaces) mesh.add_triangle(base + f[0], base + f[1], base + f[2], label);
}

void add_spike(TriangleMesh& mesh, const V3& base, const V3& tip, float base_radius,
               SurfaceClass label) {
  const V3 axis = tip - base;
  if (axis.norm() <= 0.0f) return;
  const auto [u, w] = orthonormal_basis(axis.normalized());
  const auto b = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int i = 0; i < 3; ++i) {
    const float ang = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / 3.0f;
    mesh.add_vertex(base + base_radius * (std::cos(ang) * u + std::sin(ang) * w));
  }
  const std::uint32_t t = mesh.add_vertex(tip);
  for (std::uint32_t i = 0; i < 3; ++i) mesh.add_triangle(b + i, b + (i + 1) % 3, t, label);
}

void add_blade(TriangleMesh& mesh, const V3& base, const V3& tip, const V3& side, float width,
               SurfaceClass label) {
  const V3 half = 0.5f * width * side.normalized();
  const std::uint32_t a = mesh.add_vertex(base - half);
  const std::uint32_t b = mesh.add_vertex(base + half);
  const std::uint32_t c = mesh.add_vertex(0.5f * (base + tip) + half);
  const std::uint32_t d = mesh.add_vertex(tip);
  const std::uint32_t e = mesh.add_vertex(0.5f * (base + tip) - half);
  mesh.add_triangle(a, b, c, label);
  mesh.add_triangle(a, c, e, label);
  mesh.add_triangle(e, c, d, label);
}

PolylinePath::PolylinePath(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
  if (points_.size() < 2) throw std::invalid_argument("polyline: needs at least 2 points");
  cumulative_.reserve(points_.size());
  cumulative_.push_back(0.0);
  for (std::size_t i = 1; i < points_.size(); ++i)
    cumulative_.push_back(cumulative_.back() + (points_[i] - points_[i - 1]).norm());
  if (cumulative_.back() <= 0.0) throw std::invalid_argument("polyline: zero length");
}

std::size_t PolylinePath::segment(double s) const {
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const auto i = static_cast<std::size_t>(std::distance(cumulative_.begin(), it));
  return std::clamp<std::size_t>(i, 1, points_.size() - 1) - 1;
}

Eigen::Vector2d PolylinePath::point(double s) const {
  s = std::clamp(s, 0.0, length());
  const std::size_t i = segment(s);
  const double l = cumulative_[i + 1] - cumulative_[i];
  const double f = l > 0.0 ? (s - cumulative_[i]) / l : 0.0;
  return points_[i] + f * (points_[i + 1] - points_[i]);
}

Eigen::Vector2d PolylinePath::tangent(double s) const {
  std::size_t i = segment(std::clamp(s, 0.0, length()));
  // Skip zero-length segments (duplicated points in imported polylines).
  while (i + 2 < points_.size() && (points_[i + 1] - points_[i]).norm() <= 0.0) ++i;
  const Eigen::Vector2d d = points_[i + 1] - points_[i];
  return d.norm() > 0.0 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::UnitX();
}

double PolylinePath::project(const Eigen::Vector2d& p) const {
  double best = 0.0, best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < points_.size(); ++i) {
    const Eigen::Vector2d d = points_[i + 1] - points_[i];
    const double l2 = d.squaredNorm();
    const double f = l2 > 0.0 ? std::clamp((p - points_[i]).dot(d) / l2, 0.0, 1.0) : 0.0;
    const double d2 = (points_[i] + f * d - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = cumulative_[i] + f * std::sqrt(l2);
    }
  }
  return best;
}

}  // namespace rownav::sim
