#pragma once
/// @file ray_caster.hpp Embree 3 ray casting against a static world TriangleMesh.
///
/// The Embree headers stay in the .cpp (pimpl): users of the simulator need only Eigen.
#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <memory>

#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Result of one ray: distance along the (unit) direction, class and normal of the surface hit.
struct RayHit {
  float distance = std::numeric_limits<float>::infinity();  ///< [m], inf = miss
  SurfaceClass label = SurfaceClass::other;                 ///< class of the triangle hit
  /// Unit geometric normal of the triangle hit, turned to face the ray origin (zero on a miss).
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  /// True when the ray hit a surface within [t_min, t_max].
  bool hit() const { return distance < std::numeric_limits<float>::infinity(); }
};

/// Ray caster over a static scene, built once from a world mesh (Embree BVH).
///
/// Every cast is single-threaded; concurrent const calls from several threads are safe
/// (Embree scenes are immutable after commit, each call uses its own context).
class RayCaster {
 public:
  /// Builds the BVH. Throws std::invalid_argument on an empty mesh, on a label count that
  /// differs from the triangle count or on an out-of-range vertex index; std::runtime_error when
  /// Embree fails.
  explicit RayCaster(const TriangleMesh& world);
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// First hit of the ray origin + t * unit_dir with t in [t_min, t_max] ([m]). A non-finite
  /// ray, or one with a coordinate beyond 1e18 (Embree's limit), misses.
  RayHit cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& unit_dir, float t_min,
              float t_max) const;

  /// Casts n rays (origins[i], unit_dirs[i]) into out[i], in packets of 16 (rtcIntersect16,
  /// coherent context: rays of a LiDAR column share their origin). Rays `cast` rejects miss.
  void cast_batch(const Eigen::Vector3f* origins, const Eigen::Vector3f* unit_dirs, std::size_t n,
                  float t_min, float t_max, RayHit* out) const;

  /// Same, with a per-ray t_min ([m]); used to continue rays past a surface they went through.
  void cast_batch(const Eigen::Vector3f* origins, const Eigen::Vector3f* unit_dirs, std::size_t n,
                  const float* t_min, float t_max, RayHit* out) const;

  /// Number of triangles in the scene.
  std::size_t triangle_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rownav::sim
