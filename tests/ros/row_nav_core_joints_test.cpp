// rownav_node with ~odometry: joint_states (issue 15): the robot's wheel joint states and IMU
// run through the stack's own wheel odometry + EKF (the localizer `rownav run` measures), no
// nav_msgs/Odometry, no ROS master.
#include <gtest/gtest.h>

#include <cmath>

#include "row_nav_scene.hpp"
#include "rownav/core/sensor_samples.hpp"

using namespace row_nav_test;

namespace {

rb::StackSetup joint_setup() {
  rb::NodeConfig n;
  n.detect_config = ROWNAV_SOURCE_DIR "/config/detect/vineyard.yaml";
  n.track_config = ROWNAV_SOURCE_DIR "/config/track/default.yaml";
  n.control_config = ROWNAV_SOURCE_DIR "/config/control/default.yaml";
  n.robot = ROWNAV_SOURCE_DIR "/config/robots/skid_steer.yaml";
  n.odometry = "joint_states";
  return rb::load_stack(n);
}

sensor_msgs::JointState wheels(double t, double left_rad, double right_rad) {
  sensor_msgs::JointState m;
  m.header.stamp.fromSec(t);
  m.name = {"left_wheel_joint", "right_wheel_joint"};
  m.position = {left_rad, right_rad};
  return m;
}

sensor_msgs::Imu level_imu(double t, double yaw_rate = 0.0) {
  rownav::core::ImuSample s;
  s.stamp = t;
  s.angular_velocity.z() = yaw_rate;
  s.linear_acceleration.z() = 9.81;
  return rb::to_imu_msg(s, "base_link");
}

}  // namespace

TEST(RowNavCoreJoints, WheelJointStatesDriveTheStacksOwnOdometry) {
  rb::RowNavCore core(joint_setup());
  const double r = core.setup().localizer.odometry.wheel_radius, v = 0.5;
  for (int k = 0; k <= 100; ++k) {  // 2 s straight at 0.5 m/s, 50 Hz
    const double t = 10.0 + 0.02 * k, angle = v * (t - 10.0) / r;
    core.on_imu(level_imu(t));
    const rb::JointAnswer a = core.on_joints(wheels(t, angle, angle));
    EXPECT_TRUE(a.skipped.empty()) << a.skipped;
  }
  const auto o = core.own_odometry(12.0);
  ASSERT_TRUE(o);
  // The travel between two instants is the wheels' (the first sample is the origin: the pose
  // starts one encoder interval late, 0.0125 m here).
  const auto before = core.own_odometry(10.5);
  ASSERT_TRUE(before);
  EXPECT_NEAR(o->T_odom_base.x - before->T_odom_base.x, 0.75, 0.002);
  EXPECT_NEAR(o->T_odom_base.x, 1.0, 0.02);
  EXPECT_NEAR(o->T_odom_base.y, 0.0, 0.01);
  EXPECT_NEAR(o->T_odom_base.theta, 0.0, 0.01);
  EXPECT_NEAR(o->twist.v, v, 0.05);
  EXPECT_EQ(o->frame_id, "odom");
  EXPECT_EQ(o->child_frame_id, "base_link");
  // nav_msgs/Odometry is not the pose source then: it is ignored.
  EXPECT_FALSE(core.on_odom(odom_msg(12.01, Pose2(5.0, 5.0, 1.0))));
  EXPECT_NEAR(core.own_odometry(12.0)->T_odom_base.x, o->T_odom_base.x, 1e-9);
}

TEST(RowNavCoreJoints, OppositeWheelsTurnTheRobotInPlace) {
  rb::RowNavCore core(joint_setup());
  const auto& odo = core.setup().localizer.odometry;
  const double omega = 0.5;  // [rad/s]: each side at omega * track / 2
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.02 * k, side = omega * 0.5 * odo.track_width * t / odo.wheel_radius;
    core.on_imu(level_imu(t, omega));
    core.on_joints(wheels(t, -side, side));
  }
  const auto o = core.own_odometry(2.0);
  ASSERT_TRUE(o);
  EXPECT_NEAR(o->T_odom_base.theta, 1.0, 0.05);  // 2 s at 0.5 rad/s, left (counter-clockwise)
  EXPECT_NEAR(std::hypot(o->T_odom_base.x, o->T_odom_base.y), 0.0, 0.02);
}

TEST(RowNavCoreJoints, FramesAreAnsweredAsWithTheRobotsOdometry) {
  const Scene scene(0.3, 0.1);
  rb::RowNavCore with_odom(vineyard_setup());
  const rb::FrameResult expected = drive(scene, with_odom, 8);
  ASSERT_TRUE(expected.ok) << expected.error;

  rb::RowNavCore core(joint_setup());
  Sweeps sweeps(scene);
  core.set_mount(sweeps.mount());
  rb::FrameResult r;
  for (int k = 0; k < 8; ++k) {  // a static robot: the wheels do not turn
    const double t = 100.0 + 0.1 * k;
    for (double dt : {0.0, 0.05}) {
      core.on_imu(level_imu(t + dt));
      core.on_joints(wheels(t + dt, 0.0, 0.0));
    }
    r = core.on_cloud(sweeps.at(t));
    ASSERT_TRUE(r.ok) << r.error;
  }
  EXPECT_EQ(r.tracking.status, expected.tracking.status);
  EXPECT_NEAR(r.tracking.lateral_error, expected.tracking.lateral_error, 0.01);
  EXPECT_NEAR(r.tracking.heading_error, expected.tracking.heading_error, 0.01);
  EXPECT_GT(r.cmd.v, 0.05);
  EXPECT_LT(r.cmd.omega, 0.0);  // steers back to the right, as with odometry
}

TEST(RowNavCoreJoints, JointStatesAreIgnoredWhenTheRobotsOdometryIsTheSource) {
  rb::RowNavCore core(vineyard_setup());
  const rb::JointAnswer a = core.on_joints(wheels(1.0, 0.0, 0.0));
  EXPECT_FALSE(a.cmd);
  EXPECT_NE(a.skipped.find("odom"), std::string::npos);
  EXPECT_FALSE(core.own_odometry(1.0));
}

TEST(RowNavCoreJoints, AnUnknownPoseSourceFailsAtStartUpNamingTheParameter) {
  rb::NodeConfig n;
  n.odometry = "wheels";
  try {
    rb::load_stack(n);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("odometry"), std::string::npos) << e.what();
  }
}

// With the stack's own localizer the NavSatFix input is fused (with the robot's nav_msgs/
// Odometry as the pose source it is only counted: docs/ros.md).
TEST(RowNavCoreJoints, NavSatFixesAreFusedOnceTheRobotHasMoved) {
  rb::RowNavCore core(joint_setup());
  const double r = core.setup().localizer.odometry.wheel_radius, v = 1.0;
  const double lat0 = 45.0, lon0 = 7.0, metres_per_deg_lon = 111320.0 * std::cos(lat0 * M_PI / 180);
  for (int k = 0; k <= 500; ++k) {  // 10 s east at 1 m/s, 50 Hz wheels and IMU, 5 Hz fixes
    const double t = 0.02 * k, angle = v * t / r;
    core.on_imu(level_imu(t));
    core.on_joints(wheels(t, angle, angle));
    if (k % 10 == 0) {
      sensor_msgs::NavSatFix f;
      f.header.stamp.fromSec(t + 1e-3);
      f.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
      f.latitude = lat0, f.longitude = lon0 + v * t / metres_per_deg_lon, f.altitude = 200.0;
      f.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
      f.position_covariance[0] = f.position_covariance[4] = 0.05 * 0.05;
      EXPECT_TRUE(core.on_fix(f).fix.valid);
    }
  }
  EXPECT_EQ(core.stack().stats().gnss, 51u);
  EXPECT_GT(core.stack().localizer().stats().gnss_used, 10);
  EXPECT_NEAR(core.own_odometry(10.0)->T_odom_base.x, 10.0, 0.1);
}
