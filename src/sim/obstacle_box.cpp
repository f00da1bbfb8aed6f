// Ray and footprint geometry of the boxes outside the Embree scene (sim/obstacle_box.hpp).
#include "rownav/sim/obstacle_box.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rownav/core/line2.hpp"

namespace rownav::sim {

namespace {

using Quad = std::array<Eigen::Vector2d, 4>;

/// Whether p is inside (or on) the counter-clockwise convex quad q.
bool inside(const Quad& q, const Eigen::Vector2d& p) {
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Eigen::Vector2d e = q[(i + 1) % q.size()] - q[i], d = p - q[i];
    if (e.x() * d.y() - e.y() * d.x() < 0.0) return false;
  }
  return true;
}

/// Whether segments ab and cd cross (proper or touching).
bool crosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
             const Eigen::Vector2d& d) {
  auto orient = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    const Eigen::Vector2d u = q - p, v = r - p;
    return u.x() * v.y() - u.y() * v.x();
  };
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  return o1 * o2 <= 0.0 && o3 * o4 <= 0.0;
}

}  // namespace

std::optional<BoxHit> intersect(const ObstacleBox& box, const Eigen::Vector3f& origin,
                                const Eigen::Vector3f& unit_dir, float t_max) {
  if (!origin.allFinite() || !unit_dir.allFinite()) return std::nullopt;
  // Into the box frame (centred, axes along the box), where the slabs are axis-aligned.
  const float c = static_cast<float>(std::cos(box.yaw)), s = static_cast<float>(std::sin(box.yaw));
  const Eigen::Vector3f centre =
      (box.base + Eigen::Vector3d(0.0, 0.0, 0.5 * box.size.z())).cast<float>();
  const Eigen::Vector3f d0 = origin - centre;
  const Eigen::Vector3f o(c * d0.x() + s * d0.y(), -s * d0.x() + c * d0.y(), d0.z());
  const Eigen::Vector3f u(c * unit_dir.x() + s * unit_dir.y(),
                          -s * unit_dir.x() + c * unit_dir.y(), unit_dir.z());
  const Eigen::Vector3f half = 0.5f * box.size.cast<float>();
  float t0 = 0.0f, t1 = t_max;
  int axis = -1;
  float sign = 0.0f;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(u[k]) < 1e-12f) {
      if (std::abs(o[k]) > half[k]) return std::nullopt;  // parallel, outside this slab
      continue;
    }
    float a = (-half[k] - o[k]) / u[k], b = (half[k] - o[k]) / u[k];
    const float entry_sign = u[k] > 0.0f ? -1.0f : 1.0f;  // the face entered faces the ray
    if (a > b) std::swap(a, b);
    if (a > t0) t0 = a, axis = k, sign = entry_sign;
    t1 = std::min(t1, b);
    if (t0 > t1) return std::nullopt;
  }
  BoxHit hit;
  hit.distance = t0;
  Eigen::Vector3f n_box = Eigen::Vector3f::Zero();
  if (axis >= 0) n_box[axis] = sign;
  else n_box = -u;  // origin inside: face the ray
  hit.normal = Eigen::Vector3f(c * n_box.x() - s * n_box.y(), s * n_box.x() + c * n_box.y(),
                               n_box.z());
  return hit;
}

std::array<Eigen::Vector2d, 4> footprint(const ObstacleBox& box) {
  const Eigen::Vector2d f(std::cos(box.yaw), std::sin(box.yaw)), l(-f.y(), f.x());
  const Eigen::Vector2d c = box.base.head<2>();
  const double hx = 0.5 * box.size.x(), hy = 0.5 * box.size.y();
  return {c - hx * f - hy * l, c + hx * f - hy * l, c + hx * f + hy * l, c - hx * f + hy * l};
}

double clearance(const Quad& a, const Quad& b) {
  for (std::size_t i = 0; i < 4; ++i) {
    if (inside(a, b[i]) || inside(b, a[i])) return 0.0;
    for (std::size_t j = 0; j < 4; ++j)
      if (crosses(a[i], a[(i + 1) % 4], b[j], b[(j + 1) % 4])) return 0.0;
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) {
      best = std::min(best, core::Segment2{a[i], a[(i + 1) % 4]}.distance(b[j]));
      best = std::min(best, core::Segment2{b[i], b[(i + 1) % 4]}.distance(a[j]));
    }
  return best;
}

}  // namespace rownav::sim
