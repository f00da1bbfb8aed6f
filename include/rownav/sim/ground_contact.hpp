#pragma once
/// @file ground_contact.hpp How a robot rests on the ground: height, roll and pitch of its base
/// from the terrain under it (procedural or an imported mesh).
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/terrain.hpp"

namespace rownav::sim {

/// Contact model of the base with the ground.
enum class ContactModel : std::uint8_t {
  automatic,      ///< footprint on a draped (mesh) terrain, centre_normal on a procedural one
  centre_normal,  ///< z and normal of the terrain at base_link (smooth procedural terrain)
  footprint,      ///< plane fitted to the heights under the four footprint corners (wheels)
};

/// Ground contact of the simulated base.
struct GroundContactConfig {
  /// automatic keeps procedural fields bit-identical to the centre-normal model they were
  /// measured with (BENCHMARK.md) and rides an imported mesh on its corners (issue 10: a
  /// faceted mesh has one normal per triangle, the wheels average over the footprint)
  ContactModel model = ContactModel::automatic;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("model", s.model);
  }
  void validate() const {}
};

/// T_world_base of a robot at planar pose `p` resting on `terrain`: z along the ground normal,
/// origin on the ground under base_link; x along the heading projected on the ground plane
/// (centre_normal) or climbing the plane straight ahead, so the ZYX yaw is p.theta (footprint).
/// footprint: the heights under the four corners of robot's footprint rectangle (length x width,
/// base_to_front ahead of base_link; a ray cast down when the terrain is draped over a mesh)
/// are fitted by a plane in least squares (a rigid base on four wheels, compliant suspension).
Eigen::Isometry3d rest_on_ground(const Terrain& terrain, const RobotConfig& robot,
                                 const core::Pose2& p, const GroundContactConfig& config);

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::ContactModel> {
  using E = rownav::sim::ContactModel;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::automatic, "automatic"}, {E::centre_normal, "centre_normal"},
       {E::footprint, "footprint"}}};
};
