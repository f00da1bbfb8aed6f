#pragma once
// A simulated cabbage field beside a neighbouring field of another crop (Emmi 2021's B1-like
// market-garden beds, 002_806e72d300173f73.txt Table 2), seen by the simulated camera: the
// target field's rows lie at y = 0 .. (rows - 1) spacing, the neighbour's beyond a gap; the camera
// colours the neighbour's plants with other_crop_colour through its target region.
#include <Eigen/Geometry>
#include <memory>

#include "rownav/sim/pinhole_camera.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/row_crop.hpp"
#include "rownav/sim/truth_labeller.hpp"

namespace rownav::vision::test {

struct FieldScene {
  sim::Field target, neighbour;
  sim::TriangleMesh mesh;
  std::unique_ptr<sim::RayCaster> world;
  Eigen::Vector2d target_min, target_max;  // [m] the target field's region (world x, y)
  double spacing = 1.0;                    // [m] between rows
  int rows = 5;                            // a field

  /// Camera config with the region that tells the two fields' crops apart.
  sim::PinholeCameraConfig camera() const {
    sim::PinholeCameraConfig c;
    c.use_target_region = true;
    c.target_min = target_min;
    c.target_max = target_max;
    return c;
  }
  /// Truth labeller with the same region (crop = the plants' surfaces).
  sim::TruthLabellerConfig truth() const {
    sim::TruthLabellerConfig c;
    c.crop_classes = {sim::SurfaceClass::crop};
    c.use_target_region = true;
    c.target_min = target_min;
    c.target_max = target_max;
    return c;
  }
  /// Pose on the centre line of corridor k (between rows k and k + 1) at x, heading + yaw.
  Eigen::Isometry3d pose(int k, double x, double yaw = 0.0) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, (k + 0.5) * spacing, 0.0);
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  }
};

/// Two cabbage fields, 5 rows x 30 m each, 1 m rows, the neighbour `gap` metres beyond the
/// target's last row (its first row at y = 4 + gap), some weeds, flat ground.
inline FieldScene make_field_scene(std::uint64_t seed, double gap = 1.5) {
  FieldScene s;
  sim::RowCropConfig rc;
  rc.crop = sim::CropType::cabbage;
  rc.rows = s.rows;
  rc.row_length = 30.0;
  rc.row_spacing = s.spacing;
  rc.weeds = sim::WeedLevel::some;
  sim::TerrainConfig flat;
  flat.roughness = 0.0;
  s.target = sim::generate_row_crop(rc, flat, seed);
  s.neighbour = sim::generate_row_crop(rc, flat, seed + 1);
  const double y0 = (s.rows - 1) * s.spacing + gap;
  s.mesh = s.target.mesh;
  s.mesh.append(s.neighbour.mesh, Eigen::Isometry3f(Eigen::Translation3f(0.0f, float(y0), 0.0f)));
  for (auto& p : s.neighbour.plants) p.position.y() += y0;
  s.world = std::make_unique<sim::RayCaster>(s.mesh);
  s.target_min = {-20.0, -0.5 * gap - 0.5 * s.spacing};
  s.target_max = {60.0, (s.rows - 1) * s.spacing + 0.5 * gap};
  return s;
}

}  // namespace rownav::vision::test
