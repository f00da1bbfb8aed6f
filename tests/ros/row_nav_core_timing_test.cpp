// RowNavCore when the node's watchdog timer (ros::Time::now()) runs ahead of the odometry: a
// sweep arriving after such a tick must still be tracked and answered (issue 15: under load the
// node logged "frame dropped: not newer than the last one" and the sim-node test counted 284
// answered frames of 645).
#include <gtest/gtest.h>

#include "row_nav_scene.hpp"

using namespace row_nav_test;

TEST(RowNavCoreTiming, ASweepAfterATickAheadOfTheOdometryIsStillAnswered) {
  const Scene scene(0.1, 0.0);
  rb::RowNavCore core(vineyard_setup());
  ASSERT_TRUE(drive(scene, core, 4).ok);  // odometry and sweeps up to t = 100.35
  const sim::RayCaster caster(scene.field.mesh);
  const auto lidar_config = sim::lidar_preset("os1_16");
  sim::Lidar lidar(lidar_config, 7);
  const sim::PoseAt pose_at = [&](double) {
    Eigen::Isometry3d T = scene.pose.to_isometry();
    T.translation().z() = scene.field.terrain.height(scene.pose.x, scene.pose.y);
    return T;
  };
  int answered = 0;
  for (int k = 4; k < 24; ++k) {
    const double t = 100.0 + 0.1 * k;
    core.on_odom(odom_msg(t, scene.pose));
    core.tick(t + 0.08);  // the timer, ahead of the next odometry message
    core.on_odom(odom_msg(t + 0.05, scene.pose));
    auto cloud = lidar.sweep(caster, pose_at, t);
    cloud.frame_id = "os_lidar";
    const rb::FrameResult r = core.on_cloud(rb::to_cloud_msg(cloud));
    EXPECT_TRUE(r.ok) << t << ": " << r.error;
    if (!r.ok) continue;
    ++answered;
    EXPECT_EQ(r.tracking.status, rownav::track::TrackStatus::tracking) << t;
    EXPECT_NEAR(r.tracking.lateral_error, 0.1, 0.1) << t;
  }
  EXPECT_EQ(answered, 20);
}
