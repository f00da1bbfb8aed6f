#include "rownav/sim/mesh_transform.hpp"

#include <Eigen/Geometry>

#include "rownav/core/angle.hpp"

namespace rownav::sim {

void MeshTransform::validate() const {
  core::check_range(offset_x, -1e6, 1e6, "offset_x");
  core::check_range(offset_y, -1e6, 1e6, "offset_y");
  core::check_range(offset_z, -1e4, 1e4, "offset_z");
  core::check_range(yaw_deg, -360.0, 360.0, "yaw_deg");
  core::check_range(scale, 1e-6, 1e6, "scale");
}

void transform_mesh(TriangleMesh& mesh, const MeshTransform& t) {
  t.validate();
  if (t.identity()) return;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(core::deg2rad(t.yaw_deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d offset(t.offset_x, t.offset_y, t.offset_z);
  for (auto& v : mesh.vertices)
    v = (R * (t.scale * v.cast<double>()) + offset).cast<float>();
}

}  // namespace rownav::sim
