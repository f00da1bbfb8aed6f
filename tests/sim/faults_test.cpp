// The simulator's fault injectors (sim/faults.hpp, issue 13): each does what it says, only in its
// window, the same way for the same seed.
#include "rownav/sim/faults.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

struct Capture : SimSink {
  std::vector<core::PointCloud> clouds;
  std::vector<double> cloud_times;  // simulated time each cloud was delivered
  std::vector<core::WheelEncoderSample> encoders;
  std::vector<core::ImuSample> imu;
  std::vector<core::GnssFix> gnss;
  double now = 0.0;
  void on_cloud(const core::PointCloud& c, const std::vector<SurfaceClass>&) override {
    clouds.push_back(c);
    cloud_times.push_back(now);
  }
  void on_encoders(const core::WheelEncoderSample& s) override { encoders.push_back(s); }
  void on_imu(const core::ImuSample& s) override { imu.push_back(s); }
  void on_gnss(const core::GnssFix& s) override { gnss.push_back(s); }
};

core::PointCloud cloud(double stamp, int n = 1000) {
  core::PointCloud c;
  c.stamp = stamp;
  for (int i = 0; i < n; ++i) {
    auto& p = c.points.emplace_back();
    p.x = 1.0f + 0.001f * i, p.y = 0.5f, p.z = 0.3f;
  }
  return c;
}

/// Frames of a 10 Hz LiDAR from 0 to `until` (sweep n stamped n / 10, emitted at (n + 1) / 10),
/// 100 Hz steps; encoders at 50 Hz counting 10 ticks a sample.
Capture drive(const FaultsConfig& f, double until = 20.0, std::uint64_t seed = 1) {
  FaultInjector inj(f, seed);
  Capture cap;
  for (int k = 1; k <= int(std::lround(until * 100)); ++k) {
    const double t = k * 0.01;
    cap.now = t;
    inj.begin_step(t, core::Pose2(), cap);
    if (k % 2 == 0) inj.on_encoders({t, 5 * k, 5 * k, 0.0});
    inj.on_imu({t, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.81)});
    if (k % 20 == 0) inj.on_gnss({t, true, Eigen::Vector3d(1, 2, 0), 0.02});
    if (k % 10 == 0) inj.on_cloud(cloud(t - 0.1), {});
  }
  return cap;
}

int non_finite(const core::PointCloud& c) {
  int n = 0;
  for (const auto& p : c.points) n += !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  return n;
}

TEST(Faults, DefaultPassesEverythingThroughUnchanged) {
  const Capture c = drive(FaultsConfig{});
  ASSERT_EQ(c.clouds.size(), 200u);
  for (std::size_t i = 0; i < c.clouds.size(); ++i) {
    EXPECT_NEAR(c.clouds[i].stamp, 0.1 * double(i), 1e-9);
    EXPECT_EQ(c.clouds[i].points.size(), 1000u);
  }
  ASSERT_EQ(c.encoders.size(), 1000u);
  EXPECT_EQ(c.encoders.back().left_ticks, 10000);
  EXPECT_FALSE(FaultsConfig{}.any());
}

TEST(Faults, DropoutRemovesEveryFrameOfItsWindowOnly) {
  FaultsConfig f;
  f.lidar_dropout = {{true, 5.0, 2.0}};
  const Capture c = drive(f);
  for (std::size_t i = 0; i < c.clouds.size(); ++i)
    EXPECT_FALSE(c.cloud_times[i] >= 5.0 - 1e-9 && c.cloud_times[i] < 7.0 - 1e-9);
  EXPECT_EQ(c.clouds.size(), 180u);  // 20 frames of 10 Hz in 2 s
}

TEST(Faults, LowRateKeepsOneFrameInKeepEvery) {
  FaultsConfig f;
  f.lidar_rate.enabled = true, f.lidar_rate.start = 5.0, f.lidar_rate.duration = 3.0;
  f.lidar_rate.keep_every = 3;
  EXPECT_EQ(drive(f).clouds.size(), 170u + 10u);  // 30 frames in the window -> 10
}

TEST(Faults, JitterDelaysFramesInOrderAndIsSeeded) {
  FaultsConfig f;
  f.lidar_rate.enabled = true, f.lidar_rate.start = 5.0, f.lidar_rate.duration = 5.0;
  f.lidar_rate.keep_every = 1, f.lidar_rate.jitter = 0.3;
  const Capture a = drive(f), b = drive(f), other = drive(f, 20.0, 2);
  ASSERT_EQ(a.clouds.size(), 200u);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.clouds.size(); ++i) {
    const double delay = a.cloud_times[i] - (a.clouds[i].stamp + 0.1);
    EXPECT_GE(delay, -1e-9);
    EXPECT_LE(delay, 0.3 + 0.01 + 1e-9);
    worst = std::max(worst, delay);
    if (i > 0) {
      EXPECT_GT(a.clouds[i].stamp, a.clouds[i - 1].stamp);  // still in order
    }
    EXPECT_EQ(a.cloud_times[i], b.cloud_times[i]);
  }
  EXPECT_GT(worst, 0.15);
  EXPECT_NE(a.cloud_times, other.cloud_times);
}

TEST(Faults, NanBurstPoisonsTheFractionAskedOnlyInItsWindow) {
  FaultsConfig f;
  f.cloud_nan.enabled = true, f.cloud_nan.start = 5.0, f.cloud_nan.duration = 1.0;
  const Capture a = drive(f), b = drive(f);
  int poisoned = 0, frames = 0;
  for (std::size_t i = 0; i < a.clouds.size(); ++i) {
    const int n = non_finite(a.clouds[i]);
    EXPECT_EQ(n, non_finite(b.clouds[i]));
    if (a.cloud_times[i] >= 5.0 - 1e-9 && a.cloud_times[i] < 6.0 - 1e-9)
      poisoned += n, ++frames;
    else
      EXPECT_EQ(n, 0);
  }
  EXPECT_EQ(frames, 10);
  EXPECT_NEAR(poisoned / (1000.0 * frames), 0.2, 0.02);
}

TEST(Faults, PointLossDropsThirtyPercent) {
  FaultsConfig f;
  f.point_loss.enabled = true, f.point_loss.start = 5.0, f.point_loss.duration = 1.0;
  const Capture c = drive(f);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < c.clouds.size(); ++i)
    if (c.cloud_times[i] >= 5.0 - 1e-9 && c.cloud_times[i] < 6.0 - 1e-9) kept += c.clouds[i].points.size();
  EXPECT_NEAR(kept / 10000.0, 0.7, 0.02);
}

TEST(Faults, DuplicateDeliversEachFrameTwice) {
  FaultsConfig f;
  f.frame_repeat.enabled = true, f.frame_repeat.start = 5.0, f.frame_repeat.duration = 1.0;
  const Capture c = drive(f);
  EXPECT_EQ(c.clouds.size(), 210u);
  int twice = 0;
  for (std::size_t i = 1; i < c.clouds.size(); ++i) twice += c.clouds[i].stamp == c.clouds[i - 1].stamp;
  EXPECT_EQ(twice, 10);
}

TEST(Faults, OutOfOrderSwapsPairs) {
  FaultsConfig f;
  f.frame_repeat = {{true, 5.0, 1.0}, RepeatMode::out_of_order};
  const Capture c = drive(f);
  EXPECT_EQ(c.clouds.size(), 200u);  // none lost
  int backwards = 0;
  for (std::size_t i = 1; i < c.clouds.size(); ++i) backwards += c.clouds[i].stamp < c.clouds[i - 1].stamp;
  EXPECT_EQ(backwards, 5);
}

TEST(Faults, TimeBackwardsAndStalledStamps) {
  FaultsConfig f;
  f.lidar_time_backwards = {{true, 5.0, 1.0}, 1.0};
  Capture c = drive(f);
  for (std::size_t i = 0; i < c.clouds.size(); ++i) {
    const bool in = c.cloud_times[i] >= 5.0 - 1e-9 && c.cloud_times[i] < 6.0 - 1e-9;
    EXPECT_NEAR(c.clouds[i].stamp, c.cloud_times[i] - 0.1 - (in ? 1.0 : 0.0), 1e-9);
  }
  FaultsConfig g;
  g.lidar_stamp_stall = {{true, 5.0, 1.0}};
  c = drive(g);
  for (std::size_t i = 0; i < c.clouds.size(); ++i) {
    const bool in = c.cloud_times[i] >= 5.0 - 1e-9 && c.cloud_times[i] < 6.0 - 1e-9;
    EXPECT_NEAR(c.clouds[i].stamp, in ? 4.9 : c.cloud_times[i] - 0.1, 1e-9);
  }
}

TEST(Faults, SlipOverReadsFreezeLosesCoarseQuantises) {
  FaultsConfig f;
  f.odometry_slip.enabled = true, f.odometry_slip.start = 5.0;  // 2 s, x 1.3 by default
  Capture c = drive(f);
  // 10 ticks a sample: 100 samples in the window over-read by 30 %.
  EXPECT_EQ(c.encoders.back().left_ticks, 10000 + 300);
  FaultsConfig g;
  g.encoder = {{true, 5.0, 2.0}, EncoderFaultMode::freeze, 256};
  c = drive(g);
  EXPECT_EQ(c.encoders.back().left_ticks, 10000 - 1000);  // ticks of the window lost, no jump
  for (std::size_t i = 1; i < c.encoders.size(); ++i)
    EXPECT_LE(c.encoders[i].left_ticks - c.encoders[i - 1].left_ticks, 10);
  g.encoder.mode = EncoderFaultMode::coarse;
  c = drive(g);
  for (const auto& e : c.encoders)
    if (e.stamp >= 5.0 && e.stamp < 7.0 - 1e-9) {
      EXPECT_EQ(e.left_ticks % 256, 0);
    }
  EXPECT_EQ(c.encoders.back().left_ticks, 10000);
}

TEST(Faults, GyroBiasStepAndGnssJump) {
  FaultsConfig f;
  f.gyro_bias = {{true, 5.0, 1.0}, 2.0};
  f.gnss_jump = {{true, 5.0, 1.0}, Eigen::Vector2d(5.0, 0.0)};
  const Capture c = drive(f);
  for (const auto& s : c.imu)
    EXPECT_NEAR(s.angular_velocity.z(), s.stamp >= 5.0 && s.stamp < 6.0 - 1e-9 ? core::deg2rad(2.0) : 0.0, 1e-12);
  for (const auto& s : c.gnss)
    EXPECT_NEAR(s.position_enu.x(), s.stamp >= 5.0 && s.stamp < 6.0 - 1e-9 ? 6.0 : 1.0, 1e-12);
}

TEST(Faults, PersonWalksToTheRobotsLineStandsAndLeaves) {
  FaultsConfig f;
  f.person.enabled = true, f.person.start = 2.0, f.person.duration = 5.0;  // ahead 5, side 1.5
  FaultInjector inj(f, 1);
  Capture cap;
  inj.begin_step(1.0, core::Pose2(0, 0, 0), cap);
  EXPECT_FALSE(inj.person_at(1.0));
  inj.begin_step(2.0, core::Pose2(1.0, 0.0, 0.0), cap);
  auto at = [&](double t) { return inj.person_at(t)->base.head<2>().eval(); };
  EXPECT_TRUE(at(2.0).isApprox(Eigen::Vector2d(6.0, 1.5)));
  EXPECT_TRUE(at(2.75).isApprox(Eigen::Vector2d(6.0, 0.75)));
  EXPECT_TRUE(at(4.0).isApprox(Eigen::Vector2d(6.0, 0.0)));
  EXPECT_TRUE(at(6.9).isApprox(Eigen::Vector2d(6.0, 0.0)));
  EXPECT_TRUE(at(7.5).isApprox(Eigen::Vector2d(6.0, -0.5)));
  EXPECT_TRUE(at(20.0).isApprox(Eigen::Vector2d(6.0, -1.5)));
}

TEST(ObstacleBox, RaysHitTheNearFaceAndFootprintsMeasureClearance) {
  ObstacleBox b;
  b.base = Eigen::Vector3d(5.0, 0.0, 0.0);
  const auto h = intersect(b, Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(1, 0, 0), 100.0f);
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->distance, 4.75f, 1e-5f);
  EXPECT_TRUE(h->normal.isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_FALSE(intersect(b, Eigen::Vector3f(0, 0, 1.8f), Eigen::Vector3f(1, 0, 0), 100.0f));
  EXPECT_FALSE(intersect(b, Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(1, 0, 0), 4.0f));
  EXPECT_FALSE(intersect(b, Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(-1, 0, 0), 100.0f));
  b.yaw = core::deg2rad(45.0);  // a corner towards the ray
  EXPECT_NEAR(intersect(b, Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(1, 0, 0), 100.f)->distance,
              5.0f - 0.25f * std::sqrt(2.0f), 1e-4f);
  const std::array<Eigen::Vector2d, 4> robot{Eigen::Vector2d(-1, -0.3), Eigen::Vector2d(1, -0.3),
                                             Eigen::Vector2d(1, 0.3), Eigen::Vector2d(-1, 0.3)};
  b.yaw = 0.0;
  EXPECT_NEAR(clearance(robot, footprint(b)), 3.75, 1e-9);
  b.base = Eigen::Vector3d(1.1, 0.0, 0.0);
  EXPECT_EQ(clearance(robot, footprint(b)), 0.0);
}

TEST(Faults, ValidateNamesTheField) {
  FaultsConfig f;
  f.point_loss.fraction = 1.5;
  try {
    f.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point_loss.fraction"), std::string::npos) << e.what();
  }
  f = {};
  f.lidar_dropout.duration = 0.0;
  EXPECT_THROW(f.validate(), std::invalid_argument);
  f = {};
  f.lidar_rate.keep_every = 0;
  EXPECT_THROW(FaultInjector(f, 1), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::sim
