#include "rownav/sim/simulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "rownav/core/angle.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/scripted_path.hpp"

namespace rownav::sim {
namespace {

/// A small vineyard (rows along +x from x = 0, row k at y = k * spacing): fast to build.
FieldConfig vineyard_config(double spacing, GrowthStage stage, int rows = 6, double length = 24.0,
                            double slope_x_deg = 0.0, double roughness = 0.02) {
  FieldConfig c;
  c.kind = FieldKind::vineyard;
  c.vineyard.rows = rows;
  c.vineyard.row_length = length;
  c.vineyard.row_spacing = spacing;
  c.vineyard.stage = stage;
  c.vineyard.gap_count = 0;
  c.vineyard.headland_width = 5.0;
  c.terrain.slope_x_deg = slope_x_deg;
  c.terrain.roughness = roughness;
  c.seed = 3;
  return c;
}

Field small_vineyard(double spacing, GrowthStage stage, int rows = 6, double length = 24.0,
                     double slope_x_deg = 0.0, double roughness = 0.02) {
  return generate_field(vineyard_config(spacing, stage, rows, length, slope_x_deg, roughness));
}

/// Keeps everything the simulator emits.
struct Capture : SimSink {
  std::vector<core::PointCloud> clouds;
  std::vector<std::vector<SurfaceClass>> cloud_labels;
  std::vector<core::Scan2D> scans;
  std::vector<std::vector<SurfaceClass>> scan_labels;
  std::vector<core::WheelEncoderSample> encoders;
  std::vector<core::ImuSample> imu;
  std::vector<GroundTruth> truth;

  void on_cloud(const core::PointCloud& c, const std::vector<SurfaceClass>& l) override {
    clouds.push_back(c);
    cloud_labels.push_back(l);
  }
  void on_scan(const core::Scan2D& s, const std::vector<SurfaceClass>& l) override {
    scans.push_back(s);
    scan_labels.push_back(l);
  }
  void on_encoders(const core::WheelEncoderSample& s) override { encoders.push_back(s); }
  void on_imu(const core::ImuSample& s) override { imu.push_back(s); }
  void on_ground_truth(const GroundTruth& g) override { truth.push_back(g); }
};

/// Steps the simulator for `seconds` with a constant command.
void run(Simulator& sim, SimSink& sink, double seconds, const core::Twist2& cmd = {}) {
  const int steps = static_cast<int>(std::lround(seconds / sim.dt()));
  for (int i = 0; i < steps; ++i) sim.step(cmd, sink);
}

bool is_row_surface(SurfaceClass c) {
  return c == SurfaceClass::canopy || c == SurfaceClass::trunk || c == SurfaceClass::post;
}

/// Row-surface returns per row (index = round(y / spacing) in the world frame, within half a
/// spacing of the row line) of a sweep taken while standing still.
std::vector<int> points_per_row(const Simulator& sim, const Field& field,
                                const core::PointCloud& cloud,
                                const std::vector<SurfaceClass>& labels) {
  const double s = field.row_spacing;
  const Eigen::Isometry3d T_world_lidar =
      sim.pose3d(sim.robot_state().pose) * sim.config().lidar.T_base_lidar();
  std::vector<int> count(field.rows.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!is_row_surface(labels[i])) continue;
    const auto& p = cloud.points[i];
    const Eigen::Vector3d w = T_world_lidar * Eigen::Vector3d(p.x, p.y, p.z);
    const long k = std::lround(w.y() / s);
    if (k < 0 || k >= static_cast<long>(count.size())) continue;
    if (std::abs(w.y() - static_cast<double>(k) * s) < 0.5 * s)
      ++count[static_cast<std::size_t>(k)];
  }
  return count;
}

/// One stationary OS1-16 sweep from the middle of corridor 2 (between rows 2 and 3).
struct CorridorSweep {
  std::vector<int> per_row;
  int ground = 0, total = 0;
};

CorridorSweep corridor_sweep(const Field& field) {
  const double s = field.row_spacing;
  SimConfig cfg;  // OS1-16 (default)
  Simulator sim(field, RobotConfig{}, cfg, {12.0, 2.5 * s, 0.0});
  Capture cap;
  run(sim, cap, 0.1);
  EXPECT_EQ(cap.clouds.size(), 1u);
  CorridorSweep out;
  if (cap.clouds.empty()) return out;
  const auto& cloud = cap.clouds.front();
  const auto& labels = cap.cloud_labels.front();
  EXPECT_EQ(labels.size(), cloud.size());
  out.per_row = points_per_row(sim, field, cloud, labels);
  out.total = static_cast<int>(cloud.size());
  out.ground = static_cast<int>(std::count(labels.begin(), labels.end(), SurfaceClass::ground));
  return out;
}

TEST(Simulator, SweepInNarrowVineyardSeesCorridorRows) {
  const Field field = small_vineyard(1.8, GrowthStage::high);
  const CorridorSweep sw = corridor_sweep(field);
  ASSERT_EQ(sw.per_row.size(), 6u);
  const auto& n = sw.per_row;
  RecordProperty("row_points", ::testing::PrintToString(n));
  RecordProperty("ground_points", sw.ground);
  // Observed (seed 3): rows 0..5 = 410 950 2538 2678 1164 333, ground 5258 of 13386 points.
  EXPECT_GT(n[2], 1500);  // the two rows bounding the corridor
  EXPECT_GT(n[3], 1500);
  EXPECT_GT(n[2], 2 * n[1]);  // the next rows are half hidden behind the nearest ones
  EXPECT_GT(n[3], 2 * n[4]);
  EXPECT_GT(n[2], n[0]);  // two spacings away
  EXPECT_GT(n[3], n[5]);
  EXPECT_GT(sw.ground, 2000);
  EXPECT_LT(sw.total, 16 * 1024);
}

TEST(Simulator, HighCanopyReturnsMoreThanLow) {
  const CorridorSweep high = corridor_sweep(small_vineyard(1.8, GrowthStage::high));
  const CorridorSweep low = corridor_sweep(small_vineyard(1.8, GrowthStage::low));
  ASSERT_EQ(high.per_row.size(), 6u);
  ASSERT_EQ(low.per_row.size(), 6u);
  // Observed: high 2538 + 2678, low 1773 + 1644 returns on the corridor rows.
  EXPECT_GT(high.per_row[2] + high.per_row[3], 1.2 * (low.per_row[2] + low.per_row[3]));
}

struct PlanarCounts {
  int left = 0, right = 0, canopy = 0;
};

/// One lms_1081 scan 0.4 m above the ground from the middle of corridor 2 at `x`, facing +x:
/// valid row-surface returns within 5 m ahead on rows 3 (left) and 2 (right).
PlanarCounts planar_scan(const Field& field, double x) {
  const double s = field.row_spacing;
  SimConfig cfg;
  cfg.lidar = lidar_preset("lms_1081");
  cfg.lidar.mount_xyz = {0.3, 0.0, 0.4};
  Simulator sim(field, RobotConfig{}, cfg, {x, 2.5 * s, 0.0});
  Capture cap;
  run(sim, cap, 1.0 / cfg.lidar.rate_hz);
  PlanarCounts out;
  EXPECT_EQ(cap.scans.size(), 1u);
  if (cap.scans.empty()) return out;
  const core::Scan2D& scan = cap.scans.front();
  const auto& labels = cap.scan_labels.front();
  EXPECT_EQ(labels.size(), scan.ranges.size());
  const Eigen::Isometry3d T_world_base = sim.pose3d(sim.robot_state().pose);
  const Eigen::Isometry3d T_world_lidar = T_world_base * cfg.lidar.T_base_lidar();
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!scan.valid(i) || !is_row_surface(labels[i])) continue;
    const double a = scan.angle(i), r = scan.ranges[i];
    const Eigen::Vector3d w = T_world_lidar * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0);
    const double ahead = (T_world_base.inverse() * w).x();
    if (ahead < 0.0 || ahead > 5.0) continue;
    const bool left = std::abs(w.y() - 3.0 * s) < 0.5 * s,
               right = std::abs(w.y() - 2.0 * s) < 0.5 * s;
    out.left += left;
    out.right += right;
    out.canopy += (left || right) && labels[i] == SurfaceClass::canopy;
  }
  return out;
}

// A 2D scanner 0.4 m above the ground of a VSP vineyard scans below most of the canopy (its
// bottom is 5 cm above the cordon, 0.3-0.6 m): it sees trunks, cordon arms, posts and the lowest
// foliage, a few tens of returns a row within 5 m ahead (observed 26..247 per scan, 70-100 on
// average), more where a cordon arm runs at the scan height. Six positions along the corridor.
TEST(Simulator, PlanarScanSeesBothCorridorRowsAhead) {
  int canopy[2] = {0, 0};
  for (const bool low_cordon : {false, true}) {
    // Flat ground: on rough ground the base follows the terrain normal and the scan plane tilts
    // by a few degrees, so 0.4 m above the ground it meets the ground within ~5 m.
    FieldConfig c = vineyard_config(1.8, GrowthStage::high, 6, 24.0, 0.0, 0.0);
    if (low_cordon) c.vineyard.cordon_height_min = 0.2, c.vineyard.cordon_height_max = 0.3;
    const Field field = generate_field(c);
    int left = 0, right = 0, scans = 0;
    for (double x = 3.0; x < 20.0; x += 3.0, ++scans) {
      const PlanarCounts n = planar_scan(field, x);
      EXPECT_GT(n.left, 15) << "x " << x << " low cordon " << low_cordon;
      EXPECT_GT(n.right, 15) << "x " << x << " low cordon " << low_cordon;
      left += n.left;
      right += n.right;
      canopy[low_cordon] += n.canopy;
    }
    EXPECT_GT(left, 50 * scans) << "low cordon " << low_cordon;
    EXPECT_GT(right, 50 * scans) << "low cordon " << low_cordon;
  }
  // Vines trained low (cordon 0.2-0.3 m): the scan plane cuts the canopy wall (observed 1024
  // canopy returns against 100 for the default cordon height).
  EXPECT_GT(canopy[1], 4 * canopy[0]);
  EXPECT_GT(canopy[1], 600);
}

/// Compares two captures field by field, bit for bit.
bool identical(const Capture& a, const Capture& b) {
  if (a.clouds.size() != b.clouds.size() || a.encoders.size() != b.encoders.size() ||
      a.imu.size() != b.imu.size() || a.truth.size() != b.truth.size())
    return false;
  for (std::size_t i = 0; i < a.clouds.size(); ++i) {
    const auto &p = a.clouds[i].points, &q = b.clouds[i].points;
    if (a.clouds[i].stamp != b.clouds[i].stamp || p.size() != q.size()) return false;
    if (a.cloud_labels[i] != b.cloud_labels[i]) return false;
    for (std::size_t j = 0; j < p.size(); ++j)
      if (p[j].x != q[j].x || p[j].y != q[j].y || p[j].z != q[j].z ||
          p[j].intensity != q[j].intensity || p[j].time != q[j].time || p[j].ring != q[j].ring ||
          p[j].column != q[j].column)
        return false;
  }
  for (std::size_t i = 0; i < a.encoders.size(); ++i) {
    const auto &e = a.encoders[i], &f = b.encoders[i];
    if (e.stamp != f.stamp || e.left_ticks != f.left_ticks || e.right_ticks != f.right_ticks ||
        e.steering_angle != f.steering_angle)
      return false;
  }
  for (std::size_t i = 0; i < a.imu.size(); ++i) {
    const auto &e = a.imu[i], &f = b.imu[i];
    if (e.stamp != f.stamp || e.angular_velocity != f.angular_velocity ||
        e.linear_acceleration != f.linear_acceleration)
      return false;
  }
  for (std::size_t i = 0; i < a.truth.size(); ++i) {
    const auto &g = a.truth[i], &h = b.truth[i];
    if (g.stamp != h.stamp || g.T_world_base.x != h.T_world_base.x ||
        g.T_world_base.y != h.T_world_base.y || g.T_world_base.theta != h.T_world_base.theta ||
        g.z != h.z || g.roll != h.roll || g.pitch != h.pitch || g.twist.v != h.twist.v ||
        g.twist.vy != h.twist.vy || g.twist.omega != h.twist.omega || g.place != h.place ||
        g.corridor != h.corridor || g.lateral_error != h.lateral_error ||
        g.heading_error != h.heading_error || g.plants_crushed != h.plants_crushed ||
        g.rows.size() != h.rows.size())
      return false;
  }
  return true;
}

Capture drive(const Field& field, std::uint64_t seed, double seconds) {
  SimConfig cfg;
  cfg.seed = seed;
  cfg.lidar.dropout_probability = 0.05;  // exercise every random draw of the sensor model
  cfg.lidar.foliage_pass_probability = 0.2;
  Simulator sim(field, RobotConfig{}, cfg, {2.0, 2.5 * field.row_spacing, 0.0});
  Capture cap;
  const int steps = static_cast<int>(std::lround(seconds / sim.dt()));
  for (int i = 0; i < steps; ++i) sim.step({1.0, 0.0, 0.1 * std::sin(0.02 * i)}, cap);
  return cap;
}

TEST(Simulator, SameSeedSameDataDifferentSeedDifferent) {
  const Field field = small_vineyard(1.8, GrowthStage::medium);
  const Capture a = drive(field, 42, 3.0), b = drive(field, 42, 3.0);
  ASSERT_EQ(a.clouds.size(), 30u);
  ASSERT_EQ(a.encoders.size(), 150u);
  ASSERT_EQ(a.imu.size(), 300u);
  ASSERT_EQ(a.truth.size(), 60u);
  EXPECT_TRUE(identical(a, b));
  const Capture c = drive(field, 43, 3.0);
  ASSERT_EQ(c.clouds.size(), a.clouds.size());
  EXPECT_FALSE(identical(a, c));
  // The noise differs in every stream, not only in one.
  const auto &pa = a.clouds[5].points, &pc = c.clouds[5].points;
  EXPECT_FALSE(pa.size() == pc.size() &&
               std::memcmp(pa.data(), pc.data(), pa.size() * sizeof(core::PointXYZIRT)) == 0);
  EXPECT_NE(a.imu[50].angular_velocity, c.imu[50].angular_velocity);
  EXPECT_NE(a.truth.back().T_world_base.y, c.truth.back().T_world_base.y);  // slip noise
}

TEST(Simulator, StreamRatesAndStamps) {
  const Field field = small_vineyard(1.8, GrowthStage::low);
  SimConfig cfg;  // 100 Hz physics, 10 Hz LiDAR, 50 Hz encoders, 100 Hz IMU, 20 Hz truth
  Simulator sim(field, RobotConfig{}, cfg, {2.0, 2.5 * field.row_spacing, 0.0});
  ASSERT_DOUBLE_EQ(sim.dt(), 0.01);
  Capture cap;
  run(sim, cap, 2.0, {0.5, 0.0, 0.0});
  EXPECT_NEAR(sim.time(), 2.0, 1e-9);
  ASSERT_EQ(cap.clouds.size(), 20u);
  for (std::size_t i = 0; i < cap.clouds.size(); ++i)
    EXPECT_NEAR(cap.clouds[i].stamp, 0.1 * static_cast<double>(i), 1e-9) << i;
  EXPECT_EQ(cap.encoders.size(), 100u);
  EXPECT_EQ(cap.imu.size(), 200u);
  EXPECT_EQ(cap.truth.size(), 40u);
  auto check_spacing = [](const std::vector<double>& t, double period, const char* what) {
    for (std::size_t i = 1; i < t.size(); ++i)
      EXPECT_NEAR(t[i] - t[i - 1], period, 1e-6) << what << " " << i;
  };
  std::vector<double> te, ti, tg;
  for (const auto& e : cap.encoders) te.push_back(e.stamp);
  for (const auto& e : cap.imu) ti.push_back(e.stamp);
  for (const auto& g : cap.truth) tg.push_back(g.stamp);
  check_spacing(te, 0.02, "encoders");
  check_spacing(ti, 0.01, "imu");
  check_spacing(tg, 0.05, "truth");
  ASSERT_FALSE(te.empty());
  EXPECT_NEAR(te.back(), 2.0, 1e-6);
  EXPECT_NEAR(tg.back(), 2.0, 1e-6);
}

// Issue 15: a push, a hand or a tow moves the robot without its wheels turning (the ROS sim
// node's ~carry): the pose moves at the carry's speed, the encoders count nothing, the ground
// truth sees the next corridor.
TEST(Simulator, ACarryMovesTheRobotAtItsSpeedAndTheEncodersDoNotSeeIt) {
  const Field field = small_vineyard(1.8, GrowthStage::low);
  const double s = field.row_spacing;
  Simulator sim(field, RobotConfig{}, SimConfig{}, {12.0, 2.5 * s, 0.0});
  Capture cap;
  run(sim, cap, 0.5);
  ASSERT_FALSE(cap.truth.empty());
  EXPECT_EQ(cap.truth.back().corridor, 2);
  const core::WheelEncoderSample before = cap.encoders.back();
  sim.carry({0.0, s, 0.0}, 0.5, 0.5);  // one spacing to the left, at 0.5 m/s
  EXPECT_TRUE(sim.carrying());
  run(sim, cap, 1.0);
  EXPECT_NEAR(sim.robot_state().pose.y, 2.5 * s + 0.5, 1e-9);  // half a metre in a second
  EXPECT_NEAR(sim.robot_state().pose.x, 12.0, 1e-9);
  EXPECT_TRUE(sim.carrying());
  run(sim, cap, 3.0);
  EXPECT_FALSE(sim.carrying());
  EXPECT_NEAR(sim.robot_state().pose.y, 3.5 * s, 1e-9);
  EXPECT_NEAR(sim.robot_state().pose.theta, 0.0, 1e-12);
  EXPECT_EQ(cap.encoders.back().left_ticks, before.left_ticks);
  EXPECT_EQ(cap.encoders.back().right_ticks, before.right_ticks);
  EXPECT_EQ(cap.truth.back().corridor, 3);

  // In the base frame: facing +y, "forward" is +y; a turn at its yaw rate; speed 0 is at once.
  Simulator turned(field, RobotConfig{}, SimConfig{}, {12.0, 2.5 * s, core::deg2rad(90.0)});
  turned.carry({1.0, 0.0, 0.5}, 10.0, 0.25);
  run(turned, cap, 1.0);
  EXPECT_NEAR(turned.robot_state().pose.theta, core::deg2rad(90.0) + 0.25, 1e-9);
  EXPECT_NEAR(turned.robot_state().pose.y, 2.5 * s + 0.5, 1e-9);  // the turn sets the pace
  turned.carry({0.0, -1.0, 0.0}, 0.0, 0.0);
  run(turned, cap, 0.01);
  EXPECT_FALSE(turned.carrying());
  EXPECT_NEAR(turned.robot_state().pose.x, 12.0 + std::cos(0.25), 1e-9);  // right of heading
}

TEST(Simulator, GroundTruthInALane) {
  const Field field = small_vineyard(1.8, GrowthStage::medium);
  const double s = field.row_spacing;
  SimConfig cfg;
  cfg.lidar = lidar_preset("lms_1081");  // cheap: this test is about the truth
  const FieldTruth truth(field);
  ASSERT_EQ(truth.corridor_count(0), 5);
  // 0.2 m left of the centre of corridor 2 (between rows 2 and 3), facing +x.
  const Eigen::Vector2d c = truth.corridor_centre(0, 2)[40];
  Simulator sim(field, RobotConfig{}, cfg, {c.x(), c.y() + 0.2, 0.0});
  const GroundTruth& g = sim.ground_truth();
  EXPECT_EQ(g.place, Place::lane);
  EXPECT_EQ(g.corridor, 2);
  EXPECT_NEAR(g.lateral_error, 0.2, 1e-6);
  EXPECT_NEAR(g.heading_error, 0.0, 1e-9);
  EXPECT_EQ(g.left_row, 3);
  EXPECT_EQ(g.right_row, 2);
  ASSERT_FALSE(g.rows.empty());
  EXPECT_NEAR(std::abs(g.rows.front().lateral), 0.5 * s - 0.2, 0.05);  // nearest: the left row
  EXPECT_EQ(g.plants_crushed, 0);

  // Drive the centre of corridor 2 with the scripted driver: nothing crushed.
  PathConfig path;
  path.corridors = {2};
  path.speed = 1.5;
  PathFollower driver(build_path(truth, path, RobotConfig{}));
  const auto& p0 = driver.path().front().p;
  const auto& p1 = driver.path()[1].p;
  Simulator lane(field, RobotConfig{}, cfg,
                 {p0.x(), p0.y(), std::atan2(p1.y() - p0.y(), p1.x() - p0.x())});
  Capture cap;
  int in_lane = 0;
  while (!driver.done() && lane.time() < 60.0) {
    lane.step(driver.command(lane.robot_state().pose), cap);
    if (lane.ground_truth().place == Place::lane) {
      ++in_lane;
      EXPECT_EQ(lane.ground_truth().corridor, 2);
    }
  }
  EXPECT_TRUE(driver.done());
  EXPECT_GT(in_lane, 1000);  // ~24 m at <= 1.5 m/s at 100 Hz
  EXPECT_EQ(lane.ground_truth().plants_crushed, 0);
}

TEST(Simulator, DrivingOverARowCrushesPlants) {
  const Field field = small_vineyard(1.8, GrowthStage::medium);
  const double s = field.row_spacing;
  SimConfig cfg;
  cfg.lidar = lidar_preset("lms_1081");
  // From the centre of corridor 2 heading 30 deg left: straight across row 3.
  Simulator sim(field, RobotConfig{}, cfg, {6.0, 2.5 * s, core::deg2rad(30.0)});
  Capture cap;
  run(sim, cap, 1.0, {1.0, 0.0, 0.0});  // 0.5 m driven: the corner is still 0.1 m off
  EXPECT_EQ(sim.ground_truth().plants_crushed, 0);
  run(sim, cap, 3.0, {1.0, 0.0, 0.0});
  EXPECT_GT(sim.robot_state().pose.y, 3.0 * s + 0.5);  // crossed row 3
  EXPECT_GE(sim.ground_truth().plants_crushed, 1);
  EXPECT_LE(sim.ground_truth().plants_crushed, 6);
}

/// [m] mean distance of post-labelled points (world frame via `T_world_lidar_at(time)`) to the
/// surface of the nearest post; also counts them.
template <class PoseFn>
double post_surface_error(const Field& field, const core::PointCloud& cloud,
                          const std::vector<SurfaceClass>& labels, const PoseFn& T_world_lidar_at,
                          int& n) {
  double sum = 0.0;
  n = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (labels[i] != SurfaceClass::post) continue;
    const auto& p = cloud.points[i];
    const Eigen::Vector3d w = T_world_lidar_at(p.time) * Eigen::Vector3d(p.x, p.y, p.z);
    double best = 1e9;
    for (const auto& plant : field.plants) {
      if (plant.kind != PlantKind::post && plant.kind != PlantKind::end_post) continue;
      best = std::min(best, std::abs((w.head<2>() - plant.position).norm() - plant.radius));
    }
    sum += best;
    ++n;
  }
  return n ? sum / n : 0.0;
}

TEST(Simulator, MotionDuringTheSweepReachesTheCloud) {
  const Field field = small_vineyard(1.8, GrowthStage::low, 6, 30.0, 0.0, 0.0);
  const double s = field.row_spacing;
  SimConfig cfg;
  cfg.lidar.range_noise_std = 0.005;
  Simulator sim(field, RobotConfig{}, cfg, {1.0, 2.5 * s, 0.0});
  Capture cap;
  // Accelerate to 1.5 m/s (1 m/s^2), then record the poses of the next sweep.
  run(sim, cap, 1.7, {1.5, 0.0, 0.0});
  std::vector<std::pair<double, Eigen::Isometry3d>> poses;
  const std::size_t before = cap.clouds.size();
  while (cap.clouds.size() == before) {
    poses.emplace_back(sim.time(), sim.pose3d(sim.robot_state().pose));
    sim.step({1.5, 0.0, 0.0}, cap);
  }
  poses.emplace_back(sim.time(), sim.pose3d(sim.robot_state().pose));
  EXPECT_NEAR(sim.robot_state().twist.v, RobotConfig{}.alpha * 1.5, 0.05);  // true speed
  const core::PointCloud& cloud = cap.clouds.back();
  const auto& labels = cap.cloud_labels.back();
  ASSERT_TRUE(cloud.has_time);
  float t_min = 1e9f, t_max = -1e9f;
  for (const auto& p : cloud.points)
    t_min = std::min(t_min, p.time), t_max = std::max(t_max, p.time);
  EXPECT_NEAR(t_min, 0.0, 0.002);
  EXPECT_NEAR(t_max, 0.1, 0.002);

  const Eigen::Isometry3d T_base_lidar = cfg.lidar.T_base_lidar();
  auto pose_at = [&](double t) {  // linear between physics steps (the robot drives straight)
    for (std::size_t i = 1; i < poses.size(); ++i)
      if (t <= poses[i].first + 1e-12) {
        const double a = (t - poses[i - 1].first) / (poses[i].first - poses[i - 1].first);
        Eigen::Isometry3d T = poses[i - 1].second;
        T.translation() += a * (poses[i].second.translation() - T.translation());
        return T;
      }
    return poses.back().second;
  };
  int n_own = 0, n_stamp = 0;
  const double own = post_surface_error(
      field, cloud, labels, [&](float t) { return pose_at(cloud.stamp + t) * T_base_lidar; },
      n_own);
  const double at_stamp = post_surface_error(
      field, cloud, labels, [&](float) { return pose_at(cloud.stamp) * T_base_lidar; }, n_stamp);
  // Observed: 554 post points, 4.4 mm with their own poses, 31 mm with the sweep-start pose.
  ASSERT_GT(n_own, 50);
  EXPECT_LT(own, 0.012);      // each point at its own time: on the post surface
  EXPECT_GT(at_stamp, 0.02);  // one pose for the sweep: smeared by up to 0.135 m
  EXPECT_GT(at_stamp, 3 * own);
}

TEST(Simulator, SlopedTerrainSetsHeightRollPitch) {
  // Ground rises along +x by 5 deg (z = x tan 5 deg), no roughness.
  const Field field = small_vineyard(1.8, GrowthStage::low, 4, 20.0, 5.0, 0.0);
  const double s = field.row_spacing, slope = core::deg2rad(5.0);
  SimConfig cfg;
  cfg.lidar = lidar_preset("lms_1081");
  struct Case {
    double yaw_deg, roll_deg, pitch_deg;
  };
  // REP 103 / ZYX (R = Rz(yaw) Ry(pitch) Rx(roll), as src/sim/simulator.cpp): pitch is positive
  // nose DOWN, roll positive left side UP. Facing uphill (+x) the nose is up: pitch = -5 deg;
  // facing +y the left side (-x) is downhill: roll = -5 deg.
  for (const Case c : {Case{0.0, 0.0, -5.0}, Case{180.0, 0.0, 5.0}, Case{90.0, -5.0, 0.0},
                       Case{-90.0, 5.0, 0.0}}) {
    const double x = 10.0;
    Simulator sim(field, RobotConfig{}, cfg, {x, 1.5 * s, core::deg2rad(c.yaw_deg)});
    Capture cap;
    run(sim, cap, 0.05);
    const GroundTruth& g = sim.ground_truth();
    EXPECT_NEAR(g.z, x * std::tan(slope), 1e-3) << c.yaw_deg;
    EXPECT_NEAR(core::rad2deg(g.roll), c.roll_deg, 0.05) << c.yaw_deg;
    EXPECT_NEAR(core::rad2deg(g.pitch), c.pitch_deg, 0.05) << c.yaw_deg;
    // The base's z axis is the terrain normal; the IMU sees gravity tilted accordingly.
    ASSERT_FALSE(cap.imu.empty());
    const Eigen::Vector3d a = cap.imu.back().linear_acceleration;
    // At rest it measures the specific force R^T (0, 0, g): x = -g sin(pitch),
    // y = g cos(pitch) sin(roll) (biases up to ~0.1 m/s^2).
    EXPECT_NEAR(a.x(), -9.81 * std::sin(g.pitch), 0.15) << c.yaw_deg;
    EXPECT_NEAR(a.y(), 9.81 * std::cos(g.pitch) * std::sin(g.roll), 0.15) << c.yaw_deg;
  }
}

}  // namespace
}  // namespace rownav::sim
