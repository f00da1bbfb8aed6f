// Issue 10: the robot rides an imported terrain mesh (z, roll, pitch from the surface) and the
// LiDAR sees that ground where it is; the mesh is placed by the field file's terrain_transform.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>

#include "rownav/core/angle.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;
using Surface = std::function<double(double, double)>;

/// A grid OBJ of z = surface(x, y) over [lo, hi]^2 (mesh frame), cells of `cell` metres.
void write_grid_obj(const fs::path& file, const Surface& surface, double lo, double hi,
                    double cell) {
  std::ofstream out(file);
  const int n = static_cast<int>(std::lround((hi - lo) / cell));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      out << "v " << lo + i * cell << " " << lo + j * cell << " "
          << surface(lo + i * cell, lo + j * cell) << "\n";
  const auto id = [n](int i, int j) { return j * (n + 1) + i + 1; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      out << "f " << id(i, j) << " " << id(i + 1, j) << " " << id(i + 1, j + 1) << " "
          << id(i, j + 1) << "\n";
}

struct Scene {
  sim::MeshTransform t;
  Surface mesh_surface;
  /// Field-frame height: the inverse transform of (x, y) into the mesh frame.
  double height(double x, double y) const {
    const double a = -core::deg2rad(t.yaw_deg), dx = x - t.offset_x, dy = y - t.offset_y;
    const double mx = (std::cos(a) * dx - std::sin(a) * dy) / t.scale;
    const double my = (std::sin(a) * dx + std::cos(a) * dy) / t.scale;
    return t.scale * mesh_surface(mx, my) + t.offset_z;
  }
  Eigen::Vector3d normal(double x, double y) const {
    const double h = 1e-4;
    const double gx = (height(x + h, y) - height(x - h, y)) / (2 * h);
    const double gy = (height(x, y + h) - height(x, y - h)) / (2 * h);
    return Eigen::Vector3d(-gx, -gy, 1.0).normalized();
  }
};

sim::Field build(const Scene& s, const std::string& name,
                 const sim::MeshLabelConfig& labels = {}) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("rownav_ride_" + name);
  fs::create_directories(dir);
  write_grid_obj(dir / "ground.obj", s.mesh_surface, -60.0, 60.0, 0.5);
  std::ofstream(dir / "rows.csv") << "row,x,y\n1,0,0\n1,20,0\n2,0,2.5\n2,20,2.5\n3,0,5\n3,20,5\n";
  sim::FieldConfig c;
  c.kind = sim::FieldKind::layout;
  c.name = name;
  c.layout.file = "rows.csv";
  c.layout.terrain_mesh = "ground.obj";
  c.layout.terrain_transform = s.t;
  c.layout.terrain_labels = labels;
  return build_field(c, dir);
}

Scene tilted() {
  Scene s;
  s.t.offset_x = 4.0, s.t.offset_y = -3.0, s.t.offset_z = 2.0, s.t.yaw_deg = 30.0;
  s.mesh_surface = [](double x, double y) { return 0.12 * x - 0.07 * y; };  // ~8 % and 4 %
  return s;
}

Scene bumpy() {
  Scene s;
  s.t.scale = 2.0, s.t.yaw_deg = -20.0;
  s.mesh_surface = [](double x, double y) {
    return 0.05 * x + 0.1 * std::sin(x / 3.0) * std::cos(y / 4.0);
  };
  return s;
}

std::size_t count_label(const sim::Field& f, sim::SurfaceClass c) {
  return static_cast<std::size_t>(std::count(f.mesh.labels.begin(), f.mesh.labels.end(), c));
}

/// Roll and pitch (ZYX, yaw theta) give a base z axis along the analytic normal.
void expect_on_surface(const sim::GroundTruth& g, double theta, const Eigen::Vector3d& n,
                       double tol) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(g.pitch, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(g.roll, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  EXPECT_NEAR((R.col(2) - n).norm(), 0.0, tol);
}

TEST(TerrainMeshRide, TiltedPlaneGivesItsHeightRollAndPitch) {
  const Scene s = tilted();
  const sim::Field f = build(s, "tilted");
  ASSERT_TRUE(f.terrain.draped());
  for (const auto& p : f.plants)  // vines and posts stand on the mesh
    EXPECT_NEAR(f.terrain.height(p.position.x(), p.position.y()),
                s.height(p.position.x(), p.position.y()), 1e-3);
  for (const double theta : {0.0, 0.4, 2.0, -2.5}) {
    const core::Pose2 pose{10.0, 1.25, theta};
    const sim::Simulator sim(f, sim::RobotConfig{}, sim::SimConfig{}, pose);
    const sim::GroundTruth& g = sim.ground_truth();
    EXPECT_NEAR(g.z, s.height(pose.x, pose.y), 1e-3) << theta;
    expect_on_surface(g, theta, s.normal(pose.x, pose.y), 1e-4);
    EXPECT_GT(std::abs(g.pitch) + std::abs(g.roll), 0.05);  // really tilted
  }
}

TEST(TerrainMeshRide, BumpyMeshIsDrivenOnNotUnder) {
  const Scene s = bumpy();
  const sim::Field f = build(s, "bumpy");
  for (const double x : {2.0, 7.0, 13.0}) {
    const core::Pose2 pose{x, 1.25, 0.3};
    const sim::Simulator sim(f, sim::RobotConfig{}, sim::SimConfig{}, pose);
    // The footprint (0.9 x 0.6 m) averages bumps of 19 m wavelength: within 1 cm, 1 deg.
    EXPECT_NEAR(sim.ground_truth().z, s.height(pose.x, pose.y), 0.01) << x;
    expect_on_surface(sim.ground_truth(), pose.theta, s.normal(pose.x, pose.y), 0.02);
  }
}

TEST(TerrainMeshRide, HeightRuleSeparatesCanopyFromTheGroundRidden) {
  // A height-map mesh: gentle bumps plus a 1.5 m hedge 0.8 m wide along y = 2.5, one surface.
  Scene s;
  s.mesh_surface = [](double x, double y) {
    return 0.02 * std::sin(x) + (std::abs(y - 2.5) < 0.4 && x > 0 && x < 20 ? 1.5 : 0.0);
  };
  sim::MeshLabelConfig labels;
  const core::Pose2 on_hedge{10.0, 2.5, 0.0};
  {  // all ground: the robot rides up the hedge (a ridge on the 0.5 m grid)
    const sim::Field f = build(s, "hedge_ground", labels);
    const sim::Simulator sim(f, sim::RobotConfig{}, sim::SimConfig{}, on_hedge);
    EXPECT_GT(sim.ground_truth().z, 0.3);
  }
  labels.rule = sim::MeshLabelRule::height;
  const sim::Field f = build(s, "hedge_height", labels);
  EXPECT_GT(count_label(f, sim::SurfaceClass::canopy), 50u);
  const sim::Simulator sim(f, sim::RobotConfig{}, sim::SimConfig{}, on_hedge);
  EXPECT_NEAR(sim.ground_truth().z, 0.0, 0.05);  // the ground under it, not the canopy
  const sim::Simulator lane(f, sim::RobotConfig{}, sim::SimConfig{}, {10.0, 1.25, 0.0});
  EXPECT_NEAR(lane.ground_truth().z, s.height(10.0, 1.25), 0.01);
}

struct Clouds : sim::SimSink {
  std::vector<core::PointCloud> clouds;
  std::vector<std::vector<sim::SurfaceClass>> labels;
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>& l) override {
    clouds.push_back(c);
    labels.push_back(l);
  }
};

TEST(TerrainMeshRide, LidarSeesTheGroundWhereTheSurfaceIs) {
  const Scene s = tilted();
  const sim::Field f = build(s, "lidar");
  const core::Pose2 pose{10.0, 1.25, 0.4};
  sim::SimConfig config;
  sim::Simulator sim(f, sim::RobotConfig{}, config, pose);
  Clouds sink;
  while (sink.clouds.empty()) sim.step(core::Twist2{}, sink);
  const Eigen::Isometry3d T = sim.pose3d(pose) * config.lidar.T_base_lidar();
  int ground = 0, near = 0;
  const auto& cloud = sink.clouds.front();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (sink.labels.front()[i] != sim::SurfaceClass::ground) continue;
    const auto& q = cloud.points[i];
    const Eigen::Vector3d w = T * Eigen::Vector3d(q.x, q.y, q.z);
    ++ground;
    near += std::abs(w.z() - s.height(w.x(), w.y())) < 0.05;  // range noise ~1-3 cm
  }
  RecordProperty("ground_points", ground);
  EXPECT_GT(ground, 1000);
  EXPECT_GT(near, ground * 95 / 100);
}

}  // namespace
}  // namespace rownav::io
