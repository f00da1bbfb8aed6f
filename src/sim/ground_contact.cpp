#include "rownav/sim/ground_contact.hpp"

#include <cmath>

namespace rownav::sim {
namespace {

/// Frame with x along `heading` projected on the plane of unit normal `n`, z = n, at `origin`.
Eigen::Isometry3d frame_on_plane(const Eigen::Vector3d& heading, const Eigen::Vector3d& n,
                                 const Eigen::Vector3d& origin) {
  const Eigen::Vector3d x = (heading - heading.dot(n) * n).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = n.cross(x);
  R.col(2) = n;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = origin;
  return T;
}

Eigen::Isometry3d on_centre(const Terrain& terrain, const core::Pose2& p) {
  const Eigen::Vector3d heading(std::cos(p.theta), std::sin(p.theta), 0.0);
  return frame_on_plane(heading, terrain.normal(p.x, p.y),
                        Eigen::Vector3d(p.x, p.y, terrain.height(p.x, p.y)));
}

Eigen::Isometry3d on_footprint(const Terrain& terrain, const RobotConfig& robot,
                               const core::Pose2& p) {
  const double front = robot.base_to_front, rear = robot.base_to_front - robot.length;
  const double half = 0.5 * robot.width;
  const std::array<Eigen::Vector2d, 4> corners = {Eigen::Vector2d(front, half), {rear, half},
                                                  {rear, -half}, {front, -half}};
  const Eigen::Vector2d f(std::cos(p.theta), std::sin(p.theta)), l(-f.y(), f.x());
  // z = a + b u + c v over the corners (u forward, v left of base_link), least squares.
  Eigen::Matrix<double, 4, 3> A;
  Eigen::Vector4d z;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d& c = corners[static_cast<std::size_t>(i)];
    const Eigen::Vector2d w = Eigen::Vector2d(p.x, p.y) + c.x() * f + c.y() * l;
    A.row(i) << 1.0, c.x(), c.y();
    z(i) = terrain.height(w.x(), w.y());
  }
  const Eigen::Vector3d abc = A.colPivHouseholderQr().solve(z);
  const Eigen::Vector2d grad = abc(1) * f + abc(2) * l;  // dz/dx, dz/dy in the world
  const Eigen::Vector3d n = Eigen::Vector3d(-grad.x(), -grad.y(), 1.0).normalized();
  // x climbs the plane straight ahead (slope abc(1)), so the yaw stays p.theta exactly.
  return frame_on_plane(Eigen::Vector3d(f.x(), f.y(), abc(1)), n,
                        Eigen::Vector3d(p.x, p.y, abc(0)));
}

}  // namespace

Eigen::Isometry3d rest_on_ground(const Terrain& terrain, const RobotConfig& robot,
                                 const core::Pose2& p, const GroundContactConfig& config) {
  const bool footprint = config.model == ContactModel::footprint ||
                         (config.model == ContactModel::automatic && terrain.draped());
  return footprint ? on_footprint(terrain, robot, p) : on_centre(terrain, p);
}

}  // namespace rownav::sim
