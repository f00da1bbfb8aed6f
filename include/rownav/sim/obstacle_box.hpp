#pragma once
/// @file obstacle_box.hpp A box standing on the ground that is not part of the static Embree
/// scene (a person walking into the corridor, sim/faults.hpp): the LiDAR intersects its rays
/// with it analytically, the simulator measures the footprint's clearance to it.
#include <Eigen/Core>
#include <array>
#include <optional>

namespace rownav::sim {

/// Upright box: bottom face centred on `base` (world, on the terrain), turned by `yaw` about z.
struct ObstacleBox {
  Eigen::Vector3d base = Eigen::Vector3d::Zero();  ///< [m] centre of the bottom face, world
  double yaw = 0.0;                                ///< [rad] about the world z axis
  Eigen::Vector3d size{0.5, 0.5, 1.7};             ///< [m] length (along yaw), width, height
};

/// A ray hit on a box: distance along the unit direction and the face normal (facing the ray).
struct BoxHit {
  float distance = 0.0f;
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
};

/// First intersection of origin + t * unit_dir, t in [0, t_max], with the box (slab method);
/// nullopt on a miss or a non-finite ray. A ray starting inside the box hits at t = 0.
std::optional<BoxHit> intersect(const ObstacleBox& box, const Eigen::Vector3f& origin,
                                const Eigen::Vector3f& unit_dir, float t_max);

/// The box's ground footprint, counter-clockwise.
std::array<Eigen::Vector2d, 4> footprint(const ObstacleBox& box);

/// [m] smallest distance between two convex quadrilaterals (counter-clockwise corners); 0 when
/// they touch or overlap.
double clearance(const std::array<Eigen::Vector2d, 4>& a, const std::array<Eigen::Vector2d, 4>& b);

}  // namespace rownav::sim
