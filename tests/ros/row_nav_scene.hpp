#pragma once
// Shared by the RowNavCore tests: a small simulated vineyard, OS1-16 sweeps of it as
// PointCloud2 and nav_msgs/Odometry of a static robot, no ROS master.
#include "rownav_ros/conversions.hpp"
#include "rownav_ros/row_nav_core.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav_ros/odom_buffer.hpp"

namespace rb = rownav::ros_bridge;
namespace sim = rownav::sim;
using rownav::core::Pose2;

namespace row_nav_test {

/// Robot in corridor 2 of a 6-row vineyard, `offset` m left of the centre line, heading
/// `yaw_error` rad left of the corridor direction.
struct Scene {
  sim::Field field;
  Pose2 pose;
  Scene(double offset, double yaw_error) : field(make_field()) {
    const auto c = sim::FieldTruth(field).corridor_centre(0, 2);  // a copy: the truth is a temporary
    const std::size_t i = c.size() / 3;
    const Eigen::Vector2d d = (c[i + 1] - c[i]).normalized(), n(-d.y(), d.x());
    const Eigen::Vector2d p = c[i] + offset * n;
    pose = Pose2(p.x(), p.y(), std::atan2(d.y(), d.x()) + yaw_error);
  }
  static sim::Field make_field() {
    sim::FieldConfig f;
    f.vineyard.rows = 6;
    f.vineyard.row_length = 30.0;
    return sim::generate_field(f);
  }
};

inline nav_msgs::Odometry odom_msg(double t, const Pose2& p) {
  return rb::to_odom_msg({t, p, {}, "odom", "base_link"});
}

inline rb::StackSetup vineyard_setup() {
  rb::NodeConfig n;
  n.detect_config = ROWNAV_SOURCE_DIR "/config/detect/vineyard.yaml";
  n.track_config = ROWNAV_SOURCE_DIR "/config/track/default.yaml";
  n.control_config = ROWNAV_SOURCE_DIR "/config/control/default.yaml";
  n.robot = ROWNAV_SOURCE_DIR "/config/robots/skid_steer.yaml";
  return rb::load_stack(n);
}

/// OS1-16 sweeps from a static robot, one PointCloud2 per call (the mount stays set).
class Sweeps {
 public:
  explicit Sweeps(const Scene& scene)
      : scene_(scene),
        caster_(scene.field.mesh),
        config_(sim::lidar_preset("os1_16")),
        lidar_(config_, 5) {}
  Eigen::Isometry3d mount() const { return config_.T_base_lidar(); }
  sensor_msgs::PointCloud2 at(double t) {
    const Pose2 p = scene_.pose;
    const sim::PoseAt pose_at = [&](double) {
      Eigen::Isometry3d T = p.to_isometry();
      T.translation().z() = scene_.field.terrain.height(p.x, p.y);
      return T;
    };
    auto cloud = lidar_.sweep(caster_, pose_at, t);
    cloud.frame_id = "os_lidar";
    return rb::to_cloud_msg(cloud);
  }

 private:
  const Scene& scene_;
  const sim::RayCaster caster_;
  sim::LidarConfig config_;
  sim::Lidar lidar_;
};

/// Odometry at t and t + 0.05 s, then the sweep stamped t.
inline rb::FrameResult step(rb::RowNavCore& core, Sweeps& sweeps, const Pose2& p, double t) {
  core.on_odom(odom_msg(t, p));
  core.on_odom(odom_msg(t + 0.05, p));
  return core.on_cloud(sweeps.at(t));
}

inline void expect_zero(const rownav::core::Twist2& c) {
  EXPECT_EQ(c.v, 0.0);
  EXPECT_EQ(c.vy, 0.0);
  EXPECT_EQ(c.omega, 0.0);
}

/// Runs `frames` sweeps at 10 Hz from a static robot; returns the last frame's result.
inline rb::FrameResult drive(const Scene& scene, rb::RowNavCore& core, int frames) {
  const sim::RayCaster caster(scene.field.mesh);
  const auto lidar_config = sim::lidar_preset("os1_16");
  sim::Lidar lidar(lidar_config, 5);
  const Pose2 p = scene.pose;
  const sim::PoseAt pose_at = [&](double) {
    Eigen::Isometry3d T = p.to_isometry();
    T.translation().z() = scene.field.terrain.height(p.x, p.y);
    return T;
  };
  core.set_mount(lidar_config.T_base_lidar());
  rb::FrameResult r;
  for (int k = 0; k < frames; ++k) {
    const double t = 100.0 + 0.1 * k;
    core.on_odom(odom_msg(t, p));
    core.on_odom(odom_msg(t + 0.05, p));
    auto cloud = lidar.sweep(caster, pose_at, t);
    cloud.frame_id = "os_lidar";
    r = core.on_cloud(rb::to_cloud_msg(cloud));
    EXPECT_TRUE(r.ok) << r.error;
  }
  return r;
}

}  // namespace row_nav_test
