// sensor_msgs/JointState -> wheel counts (rownav_node ~odometry: joint_states, issue 15).
#include "rownav_ros/joint_state_conversion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rb = rownav::ros_bridge;

namespace {

sensor_msgs::JointState joints(double t, std::vector<std::string> names, std::vector<double> pos,
                               std::vector<double> vel = {}) {
  sensor_msgs::JointState m;
  m.header.stamp.fromSec(t);
  m.name = std::move(names);
  m.position = std::move(pos);
  m.velocity = std::move(vel);
  return m;
}

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

TEST(JointStateConverter, WheelAnglesBecomeCumulativeCountsAtTheConfiguredResolution) {
  rb::WheelJointConfig c;
  c.ticks_per_rev = 1000;
  rb::JointStateConverter conv(c);
  const auto r = conv.convert(
      joints(10.0, {"right_wheel_joint", "left_wheel_joint"}, {kTwoPi * 0.5, -kTwoPi * 2.25}));
  ASSERT_TRUE(r.sample) << r.skipped;
  EXPECT_DOUBLE_EQ(r.sample->stamp, 10.0);
  EXPECT_EQ(r.sample->left_ticks, -2250);  // by name, whatever the order in the message
  EXPECT_EQ(r.sample->right_ticks, 500);
}

TEST(JointStateConverter, SkidSteerSidesAreTheMeanOfTheirWheels) {
  rb::WheelJointConfig c;
  c.left_joints = {"fl", "rl"};
  c.right_joints = {"fr", "rr"};
  c.ticks_per_rev = 360;
  rb::JointStateConverter conv(c);
  const auto r = conv.convert(joints(1.0, {"fl", "fr", "rl", "rr", "arm"},
                                     {kTwoPi, kTwoPi * 2.0, kTwoPi * 3.0, kTwoPi * 4.0, 99.0}));
  ASSERT_TRUE(r.sample) << r.skipped;
  EXPECT_EQ(r.sample->left_ticks, 720);    // mean of 1 and 3 turns
  EXPECT_EQ(r.sample->right_ticks, 1080);  // mean of 2 and 4 turns
}

TEST(JointStateConverter, AnotherJointGroupOnTheTopicIsSkippedQuietly) {
  rb::JointStateConverter conv(rb::WheelJointConfig{});
  const auto r = conv.convert(joints(1.0, {"arm_shoulder", "arm_elbow"}, {0.1, 0.2}));
  EXPECT_FALSE(r.sample);
  EXPECT_EQ(r.skipped, "no wheel joint in the message");
}

TEST(JointStateConverter, AMissingOrNonFiniteWheelIsSkippedWithItsName) {
  rb::JointStateConverter conv(rb::WheelJointConfig{});
  auto r = conv.convert(joints(1.0, {"left_wheel_joint"}, {0.5}));
  EXPECT_FALSE(r.sample);
  EXPECT_NE(r.skipped.find("right_wheel_joint"), std::string::npos) << r.skipped;
  r = conv.convert(joints(1.0, {"left_wheel_joint", "right_wheel_joint"},
                          {0.5, std::numeric_limits<double>::quiet_NaN()}));
  EXPECT_FALSE(r.sample);
  EXPECT_NE(r.skipped.find("right_wheel_joint"), std::string::npos) << r.skipped;
  r = conv.convert(joints(1.0, {"left_wheel_joint", "right_wheel_joint"}, {0.5}));  // short
  EXPECT_FALSE(r.sample);
}

TEST(JointStateConverter, VelocityOnlyDriversAreIntegratedAndGapsAreNotBridged) {
  rb::WheelJointConfig c;
  c.ticks_per_rev = 1000;
  c.max_velocity_gap = 0.5;
  rb::JointStateConverter conv(c);
  const std::vector<std::string> n{"left_wheel_joint", "right_wheel_joint"};
  ASSERT_TRUE(conv.convert(joints(1.0, n, {}, {kTwoPi, kTwoPi})).sample);  // the first: origin
  auto r = conv.convert(joints(1.1, n, {}, {kTwoPi, -kTwoPi}));            // 0.1 rev each way
  ASSERT_TRUE(r.sample) << r.skipped;
  EXPECT_EQ(r.sample->left_ticks, 100);
  EXPECT_EQ(r.sample->right_ticks, -100);
  r = conv.convert(joints(3.0, n, {}, {kTwoPi, kTwoPi}));  // 1.9 s gap: travel unknown
  ASSERT_TRUE(r.sample);
  EXPECT_EQ(r.sample->left_ticks, 100);
  r = conv.convert(joints(3.0, n, {}, {kTwoPi, kTwoPi}));  // not newer
  EXPECT_FALSE(r.sample);
}

TEST(JointStateConverter, TheSteeringJointGivesACarLikeRobotsSteeringAngle) {
  rb::WheelJointConfig c;
  c.steering_joint = "front_steer";
  rb::JointStateConverter conv(c);
  auto r = conv.convert(
      joints(1.0, {"left_wheel_joint", "right_wheel_joint", "front_steer"}, {0.0, 0.0, 0.3}));
  ASSERT_TRUE(r.sample) << r.skipped;
  EXPECT_DOUBLE_EQ(r.sample->steering_angle, 0.3);
  r = conv.convert(joints(1.1, {"left_wheel_joint", "right_wheel_joint"}, {0.0, 0.0}));
  EXPECT_FALSE(r.sample);
  EXPECT_NE(r.skipped.find("front_steer"), std::string::npos);
}

TEST(JointStateConverter, ABadConfigurationNamesTheField) {
  rb::WheelJointConfig c;
  c.left_joints.clear();
  try {
    rb::JointStateConverter conv(c);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("left_joints"), std::string::npos) << e.what();
  }
  c = {};
  c.ticks_per_rev = 0;
  EXPECT_THROW(rb::JointStateConverter{c}, std::invalid_argument);
}

TEST(JointStateConverter, ADriversMessageOfEncoderCountsConvertsBackToTheSameCounts) {
  rb::WheelJointConfig c;  // 65536 ticks per revolution, the simulator's encoders 2048
  c.steering_joint = "front_steer";
  rb::JointStateConverter conv(c);
  for (std::int64_t ticks : {0L, 1L, -7L, 2047L, 123456789L}) {
    rownav::core::WheelEncoderSample s;
    s.stamp = 1.0 + 1e-3 * static_cast<double>(ticks % 1000);
    s.left_ticks = ticks, s.right_ticks = -3 * ticks, s.steering_angle = 0.25;
    const auto r = conv.convert(rb::to_joint_state_msg(s, 2048, c));
    ASSERT_TRUE(r.sample) << r.skipped;
    EXPECT_EQ(r.sample->left_ticks, 32 * ticks);  // the same angle at 32x the resolution
    EXPECT_EQ(r.sample->right_ticks, -96 * ticks);
    EXPECT_EQ(r.sample->steering_angle, 0.25);
  }
}
