#include "rownav/sim/lidar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

/// Horizontal square [-half, half]^2 at height z.
TriangleMesh plane(float z, float half, SurfaceClass label) {
  TriangleMesh m;
  const auto a = m.add_vertex({-half, -half, z}), b = m.add_vertex({half, -half, z});
  const auto c = m.add_vertex({half, half, z}), d = m.add_vertex({-half, half, z});
  m.add_triangle(a, b, c, label);
  m.add_triangle(a, c, d, label);
  return m;
}

/// Vertical wall x = x0 spanning y in [-half, half], z in [-1, 4].
TriangleMesh wall_x(float x0, float half, SurfaceClass label) {
  TriangleMesh m;
  const auto a = m.add_vertex({x0, -half, -1}), b = m.add_vertex({x0, half, -1});
  const auto c = m.add_vertex({x0, half, 4}), d = m.add_vertex({x0, -half, 4});
  m.add_triangle(a, b, c, label);
  m.add_triangle(a, c, d, label);
  return m;
}

/// Room [x0, x1] x [y0, y1] with a floor at z = 0 and walls up to 4 m (labelled obstacle).
TriangleMesh room(float x0, float x1, float y0, float y1) {
  TriangleMesh m = plane(0.0f, 50.0f, SurfaceClass::ground);
  const float hy = std::max(-y0, y1) + 1.0f, hx = std::max(-x0, x1) + 1.0f;
  m.append(wall_x(x0, hy, SurfaceClass::obstacle));
  m.append(wall_x(x1, hy, SurfaceClass::obstacle));
  const Eigen::Isometry3f rot(
      Eigen::AngleAxisf(std::numbers::pi_v<float> / 2, Eigen::Vector3f::UnitZ()));
  m.append(wall_x(y0, hx, SurfaceClass::obstacle), rot);  // x = y0 rotated to y = y0
  m.append(wall_x(y1, hx, SurfaceClass::obstacle), rot);
  return m;
}

/// Distance from (px, py) along bearing a to the inside of the room's walls.
double room_range(double px, double py, double a, double x0, double x1, double y0, double y1) {
  const double c = std::cos(a), s = std::sin(a);
  double t = 1e9;
  if (c > 1e-12) t = std::min(t, (x1 - px) / c);
  if (c < -1e-12) t = std::min(t, (x0 - px) / c);
  if (s > 1e-12) t = std::min(t, (y1 - py) / s);
  if (s < -1e-12) t = std::min(t, (y0 - py) / s);
  return t;
}

PoseAt still(const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity()) {
  return [T](double) { return T; };
}

TEST(LidarConfig, PresetsValidateAndMatchDatasheets) {
  for (const auto& name : lidar_preset_names())
    EXPECT_NO_THROW(lidar_preset(name).validate()) << name;
  EXPECT_EQ(lidar_preset_names().size(), 6u);
  EXPECT_EQ(lidar_preset("os1_64").rings, 64);
  EXPECT_DOUBLE_EQ(lidar_preset("os1_64").vertical_fov_max_deg, 22.5);
  EXPECT_EQ(lidar_preset("vlp16").columns, 1800);
  EXPECT_NEAR(core::rad2deg(lidar_preset("vlp16").azimuth_increment()), 0.2, 1e-12);
  EXPECT_NEAR(core::rad2deg(lidar_preset("lms_1081").azimuth_increment()), 0.25, 1e-12);
  EXPECT_NEAR(core::rad2deg(lidar_preset("sick_lms111").azimuth_increment()), 0.5, 1e-12);
  EXPECT_NEAR(core::rad2deg(lidar_preset("sick_tim571").azimuth_increment()), 1.0 / 3.0, 1e-12);
  const auto vlp = lidar_preset("vlp16").ring_elevations();
  EXPECT_NEAR(core::rad2deg(vlp.front()), -15.0, 1e-12);
  EXPECT_NEAR(core::rad2deg(vlp[8]), 1.0, 1e-12);
  try {
    lidar_preset("hdl64");
    FAIL() << "unknown preset accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("os1_16"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lms_1081"), std::string::npos) << e.what();
  }
}

void expect_invalid(LidarConfig c, const std::string& field) {
  try {
    c.validate();
    FAIL() << field << " accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind(field + ":", 0), 0u) << e.what();
  }
  EXPECT_THROW(Lidar(c, 1), std::invalid_argument);
}

TEST(LidarConfig, InvalidFieldsThrowNamingTheField) {
  LidarConfig c;
  c.columns = 0;
  expect_invalid(c, "columns");
  c = lidar_preset("lms_1081");
  c.rings = 2;
  expect_invalid(c, "rings");
  c = LidarConfig{};
  c.vertical_angles_deg = {-1.0, 1.0};
  expect_invalid(c, "vertical_angles_deg");
  c.rings = 2;
  c.vertical_angles_deg = {1.0, -1.0};
  expect_invalid(c, "vertical_angles_deg");
  c = LidarConfig{};
  c.range_max = 0.1;
  expect_invalid(c, "range_max");
  c = LidarConfig{};
  c.dropout_probability = 1.5;
  expect_invalid(c, "dropout_probability");
  c = LidarConfig{};
  c.rate_hz = 0.0;
  expect_invalid(c, "rate_hz");
  c = LidarConfig{};
  c.horizontal_fov_deg = 400.0;
  expect_invalid(c, "horizontal_fov_deg");
}

TEST(Lidar, PlanarScanInBoxRoomMatchesAnalyticRanges) {
  const double x0 = -4, x1 = 6, y0 = -3, y1 = 5, sigma = 0.01;
  const RayCaster world(room(x0, x1, y0, y1));
  LidarConfig c = lidar_preset("lms_1081");
  c.range_max = 30.0;
  c.range_noise_std = sigma;
  c.mount_xyz = {0.3, 0.2, 0.5};
  Lidar lidar(c, 42);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.5, -0.4, 0.0);
  std::vector<SurfaceClass> labels;
  const core::Scan2D s = lidar.scan(world, still(T), 3.0, &labels);
  ASSERT_EQ(s.ranges.size(), 1081u);
  EXPECT_DOUBLE_EQ(s.stamp, 3.0);
  EXPECT_NEAR(s.angle_min, -0.75 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(s.time_increment, 1.0 / (25.0 * 1440.0), 1e-12);
  double sum = 0, sum2 = 0, worst = 0;
  for (std::size_t i = 0; i < s.ranges.size(); ++i) {
    ASSERT_TRUE(s.valid(i)) << i;
    EXPECT_EQ(labels[i], SurfaceClass::obstacle);
    const double err = s.ranges[i] - room_range(0.8, -0.2, s.angle(i), x0, x1, y0, y1);
    sum += err;
    sum2 += err * err;
    worst = std::max(worst, std::abs(err));
    EXPECT_GT(s.intensities[i], 0.0f);
  }
  const double n = double(s.ranges.size()), mean = sum / n;
  EXPECT_LT(worst, 4.5 * sigma);
  EXPECT_LT(std::abs(mean), 4.0 * sigma / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), sigma, 0.1 * sigma);
}

TEST(Lidar, MountYawRotatesTheScan) {
  const RayCaster world(room(-4, 6, -3, 5));
  LidarConfig c = lidar_preset("sick_lms111");
  c.range_noise_std = 0.0;
  c.mount_xyz = {0.0, 0.0, 0.5};
  c.mount_rpy_deg = {0.0, 0.0, 90.0};
  Lidar lidar(c, 1);
  const core::Scan2D s = lidar.scan(world, still(), 0.0);
  EXPECT_NEAR(s.ranges[270], 5.0, 1e-4);  // bearing 0 looks along base +y
  EXPECT_NEAR(s.ranges[90], 6.0, 1e-4);   // bearing -90 deg looks along base +x
  EXPECT_NEAR(s.ranges[450], 4.0, 1e-4);  // bearing +90 deg looks along base -x
}

TEST(Lidar, SweepOverGroundRecoversRingElevations) {
  const RayCaster world(plane(0.0f, 400.0f, SurfaceClass::ground));
  LidarConfig c = lidar_preset("os1_16");
  c.mount_xyz = {0.0, 0.0, 0.6};
  Lidar lidar(c, 5);
  std::vector<SurfaceClass> labels;
  const core::PointCloud cloud = lidar.sweep(world, still(), 10.0, &labels);
  ASSERT_EQ(cloud.size(), 8u * 1024u);  // the 8 downward rings hit, the 8 upward see sky
  ASSERT_EQ(labels.size(), cloud.size());
  EXPECT_TRUE(cloud.has_ring && cloud.has_time && cloud.has_intensity);
  const auto elev = c.ring_elevations();
  for (const auto& p : cloud.points) {
    ASSERT_LT(p.ring, 8);
    const double e = std::atan2(p.z, std::hypot(p.x, p.y));
    EXPECT_NEAR(e, elev[p.ring], 2e-5);
    EXPECT_NEAR(std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z), 0.6 / std::sin(-elev[p.ring]),
                6.0 * 0.015);
    EXPECT_NEAR(p.time, p.column / (10.0 * 1024.0), 1e-7);
    const double az = -std::numbers::pi + p.column * 2.0 * std::numbers::pi / 1024.0;
    EXPECT_NEAR(core::angle_diff(std::atan2(p.y, p.x), az), 0.0, 1e-4);
  }
  for (const auto l : labels) EXPECT_EQ(l, SurfaceClass::ground);
}

TEST(Lidar, DropoutRateIsStatisticallyRight) {
  const RayCaster world(plane(0.0f, 400.0f, SurfaceClass::ground));
  LidarConfig c = lidar_preset("os1_16");
  c.dropout_probability = 0.3;
  Lidar lidar(c, 11);
  std::size_t kept = 0, total = 0;
  for (int i = 0; i < 4; ++i) {
    kept += lidar.sweep(world, still(), 0.1 * i).size();
    total += 8 * 1024;
  }
  const double frac = double(kept) / double(total), sd = std::sqrt(0.21 / double(total));
  EXPECT_NEAR(frac, 0.7, 4.0 * sd);
}

TEST(Lidar, SameSeedSameCloudOtherSeedDiffers) {
  TriangleMesh m = room(-5, 5, -3, 3);
  m.append(wall_x(2.0f, 1.0f, SurfaceClass::canopy));
  const RayCaster world(m);
  LidarConfig c = lidar_preset("os1_16");
  c.dropout_probability = 0.05;
  c.foliage_pass_probability = 0.3;
  auto run = [&](std::uint64_t seed) { return Lidar(c, seed).sweep(world, still(), 0.0); };
  const auto a = run(9), b = run(9), d = run(10);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.points[i].x, b.points[i].x);
    EXPECT_EQ(a.points[i].intensity, b.points[i].intensity);
    EXPECT_EQ(a.points[i].column, b.points[i].column);
  }
  bool differ = a.size() != d.size();
  for (std::size_t i = 0; !differ && i < a.size(); ++i) differ = a.points[i].x != d.points[i].x;
  EXPECT_TRUE(differ);
}

/// Spinning single-ring LiDAR at 0 deg elevation, no noise.
LidarConfig flat_spinner(bool motion) {
  LidarConfig c;
  c.rings = 1;
  c.vertical_fov_min_deg = c.vertical_fov_max_deg = 0.0;
  c.range_noise_std = 0.0;
  c.mount_xyz = {0.0, 0.0, 0.5};
  c.motion_during_sweep = motion;
  return c;
}

TEST(Lidar, MotionDuringSweepShiftsLaterColumns) {
  const RayCaster world(room(-10, 10, -10, 10));
  const double v = 2.0;  // [m/s] along +x
  const PoseAt moving = [v](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(v * (t - 1.0), 0.0, 0.0);
    return T;
  };
  for (const bool motion : {true, false}) {
    Lidar lidar(flat_spinner(motion), 3);
    const auto cloud = lidar.sweep(world, moving, 1.0);
    ASSERT_EQ(cloud.size(), 1024u);
    const auto& first = cloud.points.front();  // azimuth -180 deg: the back wall
    const auto& last = cloud.points.back();    // azimuth +180 - 0.35 deg, 0.1 s later
    const auto& ahead = cloud.points[512];     // azimuth 0: the front wall, at 0.05 s
    const double t_last = 1023.0 / 10240.0, t_ahead = 512.0 / 10240.0;
    EXPECT_NEAR(-first.x, 10.0, 1e-3);
    const double shift = motion ? v * t_last : 0.0;
    EXPECT_NEAR(std::hypot(last.x, last.y) - (-first.x), shift, 2e-3) << motion;
    EXPECT_NEAR(ahead.x, 10.0 - (motion ? v * t_ahead : 0.0), 1e-3) << motion;
  }
}

TEST(Lidar, PointsDeskewedWithTheirOwnPoseLieOnTheWalls) {
  const RayCaster world(room(-10, 10, -10, 10));
  LidarConfig c = flat_spinner(true);
  c.mount_xyz = {0.3, 0.1, 0.5};
  c.mount_rpy_deg = {0.0, 0.0, 30.0};
  const PoseAt turning = [](double t) {  // 1.5 m/s forward-left while yawing at 2 rad/s
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(1.5 * t, 0.5 * t, 0.0);
    T.linear() = Eigen::AngleAxisd(2.0 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
  Lidar lidar(c, 6);
  const double stamp = 0.4;
  const auto cloud = lidar.sweep(world, turning, stamp);
  ASSERT_EQ(cloud.size(), 1024u);
  const Eigen::Isometry3d T_base_lidar = c.T_base_lidar();
  double worst = 0.0, worst_static = 0.0;
  for (const auto& p : cloud.points) {
    const Eigen::Vector3d q(p.x, p.y, p.z);
    const Eigen::Vector3d w = turning(stamp + p.time) * T_base_lidar * q;
    const Eigen::Vector3d w0 = turning(stamp) * T_base_lidar * q;  // ignoring the motion
    worst = std::max(worst, std::abs(10.0 - std::max(std::abs(w.x()), std::abs(w.y()))));
    worst_static =
        std::max(worst_static, std::abs(10.0 - std::max(std::abs(w0.x()), std::abs(w0.y()))));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(worst_static, 0.1);  // the motion matters: without it the walls smear
}

TEST(Lidar, FoliagePassThroughFractionMatchesProbability) {
  TriangleMesh m = wall_x(4.0f, 20.0f, SurfaceClass::canopy);
  m.append(wall_x(7.0f, 30.0f, SurfaceClass::post));
  const RayCaster world(m);
  LidarConfig c = lidar_preset("lms_1081");
  c.horizontal_fov_deg = 60.0;  // all beams see the canopy wall
  c.range_noise_std = 0.0;
  c.mount_xyz = {0.0, 0.0, 1.0};
  c.foliage_pass_probability = 0.35;
  Lidar lidar(c, 17);
  std::size_t passed = 0, total = 0;
  for (int k = 0; k < 10; ++k) {
    std::vector<SurfaceClass> labels;
    const core::Scan2D s = lidar.scan(world, still(), 0.04 * k, &labels);
    for (std::size_t i = 0; i < s.ranges.size(); ++i) {
      const double cos_a = std::cos(s.angle(i));
      const bool far = labels[i] == SurfaceClass::post;
      EXPECT_NEAR(s.ranges[i], (far ? 7.0 : 4.0) / cos_a, 1e-4);
      passed += far;
      ++total;
    }
  }
  const double sd = std::sqrt(0.35 * 0.65 / double(total));
  EXPECT_NEAR(double(passed) / double(total), 0.35, 4.0 * sd);
}

TEST(Lidar, MinimumRangeBlocksAndReportsNaN) {
  const RayCaster world(wall_x(0.3f, 5.0f, SurfaceClass::obstacle));
  LidarConfig c = lidar_preset("sick_lms111");  // range_min 0.5
  c.mount_xyz = {0.0, 0.0, 0.5};
  Lidar lidar(c, 2);
  const core::Scan2D s = lidar.scan(world, still(), 0.0);
  EXPECT_TRUE(std::isnan(s.ranges[270]));  // wall 0.3 m ahead, closer than 0.5 m
  EXPECT_TRUE(std::isinf(s.ranges[0]));    // -135 deg: nothing behind
}

TEST(Lidar, PitchedBaseScanHitsGroundAtAnalyticRange) {
  const RayCaster world(plane(0.0f, 100.0f, SurfaceClass::ground));
  LidarConfig c = lidar_preset("lms_1081");
  c.range_noise_std = 0.0;
  c.range_max = 30.0;
  c.mount_xyz = {0.0, 0.0, 0.0};
  Lidar lidar(c, 4);
  const double h = 0.5, pitch = core::deg2rad(10.0);  // nose down (REP 103)
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(3.0, -2.0, h);
  T.linear() = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  std::vector<SurfaceClass> labels;
  const core::Scan2D s = lidar.scan(world, still(T), 0.0, &labels);
  int checked = 0;
  for (std::size_t i = 0; i < s.ranges.size(); ++i) {
    const double down = std::sin(pitch) * std::cos(s.angle(i));  // -z of the beam direction
    const double expect = down > 0.0 ? h / down : 1e9;
    if (std::abs(expect - 30.0) < 0.5) continue;  // at range_max: either way
    if (expect > 30.0) {
      EXPECT_TRUE(std::isinf(s.ranges[i])) << i;  // looks up or beyond range_max: no return
      continue;
    }
    EXPECT_NEAR(s.ranges[i], expect, 1e-4 * expect) << i;
    EXPECT_EQ(labels[i], SurfaceClass::ground);
    ++checked;
  }
  EXPECT_GT(checked, 500);
}

TEST(Lidar, IntensityDependsOnClassRangeAndIncidence) {
  TriangleMesh m;
  const auto a = m.add_vertex({3, -10, -1}), b = m.add_vertex({3, 0, -1});
  const auto c = m.add_vertex({3, 0, 4}), d = m.add_vertex({3, -10, 4});
  const auto e = m.add_vertex({3, 10, -1}), f = m.add_vertex({3, 10, 4});
  m.add_triangle(a, b, c, SurfaceClass::wire);  // right half (y < 0)
  m.add_triangle(a, c, d, SurfaceClass::wire);
  m.add_triangle(b, e, f, SurfaceClass::ground);  // left half (y > 0)
  m.add_triangle(b, f, c, SurfaceClass::ground);
  const RayCaster world(m);
  LidarConfig cfg = lidar_preset("lms_1081");
  cfg.range_noise_std = 0.0;
  cfg.intensity_noise_std = 0.0;
  cfg.mount_xyz = {0.0, 0.0, 1.0};
  Lidar lidar(cfg, 8);
  const core::Scan2D s = lidar.scan(world, still(), 0.0);
  const std::size_t ahead = 540, step = 80;                             // 20 deg either side
  EXPECT_GT(s.intensities[ahead - step], s.intensities[ahead + step]);  // wire beats ground
  EXPECT_NEAR(s.intensities[ahead - step] / s.intensities[ahead + step], 0.8 / 0.25, 1e-3);
  EXPECT_GT(s.intensities[ahead + step], s.intensities[ahead + 2 * step]);  // farther, oblique
  EXPECT_GT(s.intensities[ahead + 2 * step], 0.0f);
}

}  // namespace
}  // namespace rownav::sim
