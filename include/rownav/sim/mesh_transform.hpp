#pragma once
/// @file mesh_transform.hpp Placement of an imported mesh in the field frame: uniform scale,
/// then a yaw about z, then an offset (a mesh from another tool rarely shares the layout's frame
/// or unit).
#include "rownav/core/config_fields.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// p_field = Rz(yaw) * (scale * p_mesh) + offset. Defaults: identity.
struct MeshTransform {
  double offset_x = 0.0;  ///< [m] field-frame x of the mesh origin
  double offset_y = 0.0;  ///< [m] field-frame y of the mesh origin
  double offset_z = 0.0;  ///< [m] field-frame z of the mesh origin
  double yaw_deg = 0.0;   ///< [deg] rotation about z, counter-clockwise seen from above
  double scale = 1.0;     ///< [-] uniform scale (0.001 for a mesh in millimetres)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("offset_x", s.offset_x);
    v("offset_y", s.offset_y);
    v("offset_z", s.offset_z);
    v("yaw_deg", s.yaw_deg);
    v("scale", s.scale);
  }
  void validate() const;
  /// True for the identity (nothing to apply).
  bool identity() const {
    return offset_x == 0.0 && offset_y == 0.0 && offset_z == 0.0 && yaw_deg == 0.0 &&
           scale == 1.0;
  }
};

/// Applies `t` to every vertex of `mesh` (labels and triangles unchanged).
void transform_mesh(TriangleMesh& mesh, const MeshTransform& t);

}  // namespace rownav::sim
