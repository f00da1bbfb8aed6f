#pragma once
/// @file sim_node.hpp rownav's simulator as a ROS 1 node (issue 15): it publishes what a robot's
/// drivers publish (/clock, the LiDAR's PointCloud2, the wheel joint states, the base's wheel
/// odometry, the IMU, tf
/// odom -> base_link -> LiDAR, the true pose), drives the simulated robot with `cmd_vel`, and
/// scores the run from the ground truth (SimScore), so that rownav_node, or any other row
/// follower, can be driven in rownav's fields and measured by rownav's truth.
#include <geometry_msgs/Pose2D.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/String.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/localize/localizer.hpp"
#include "rownav/sim/ground_truth.hpp"
#include "rownav_ros/joint_state_conversion.hpp"

namespace rownav::sim {
class Simulator;
struct Field;
}  // namespace rownav::sim

namespace rownav::ros_bridge {

/// Private parameters of rownav_sim_node (~name). Files are those of `rownav run`.
struct SimNodeConfig {
  std::string field;    ///< field YAML or zoo:SEED:INDEX (required)
  std::string robot;    ///< config/robots/*.yaml (empty: sim::RobotConfig defaults)
  std::string sensors;  ///< config/sensors/*.yaml (empty: sim::SimConfig defaults)
  std::string mission;  ///< config/missions/*.yaml: where the robot starts (empty: MissionPlan{})
  /// [m] start this far before the first corridor's entrance (io::ClosedLoopSetup::lead_in)
  double lead_in = 1.5;
  double rate_factor = 1.0;   ///< [-] simulated seconds per wall second (0: as fast as possible)
  double time_limit = 600.0;  ///< [s] simulated; the node then writes the result and exits
  /// mission state topic of the row follower: "done" or "safe_stop" there end the run
  std::string state_topic = "/rownav_node/state";
  /// the follower's per-frame output stamped with the sweep's stamp (rownav_node: ~tracking):
  /// the wall time from a cloud's publication to it is the follower's latency
  std::string tracking_topic = "/rownav_node/tracking";
  std::string result;  ///< JSON file the score is written to at the end (empty: none)
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  std::string lidar_frame = "lidar";
  /// wheel joints of the sensor_msgs/JointState published on `joint_states` (positions in rad
  /// from the simulated encoder counts, as a base driver publishes them; skid-steer: one per
  /// side, the track)
  std::string left_wheel_joint = "left_wheel_joint";
  std::string right_wheel_joint = "right_wheel_joint";
  /// car-like robots (robot file `drive: ackermann`): the front steering joint published with
  /// the wheels, its position the measured bicycle-model steering angle [rad] (rownav_node
  /// `~wheels/steering_joint`); not published for other drives
  std::string steering_joint = "front_steering_joint";
  /// the base's own odometry: nav_msgs/Odometry on `odom` and tf odom -> base_link. false when
  /// the follower computes its own (rownav_node ~odometry joint_states ~publish_tf), so that
  /// two nodes do not broadcast the same transform
  bool publish_odometry = true;
  /// [m/s] a geometry_msgs/Pose2D on ~carry (x forward, y left, theta: the robot's base frame
  /// when it arrives) moves the robot by that much at this speed without its wheels turning: a
  /// person pushing it, a tow (sim::Simulator::carry; issue 15: a robot moved while paused).
  /// 0.5 m/s: a walking push
  double carry_speed = 0.5;
  double carry_yaw_rate = 0.5;  ///< [rad/s] ... and turns it at this rate

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("field", s.field);
    v("robot", s.robot);
    v("sensors", s.sensors);
    v("mission", s.mission);
    v("lead_in", s.lead_in);
    v("rate_factor", s.rate_factor);
    v("time_limit", s.time_limit);
    v("state_topic", s.state_topic);
    v("tracking_topic", s.tracking_topic);
    v("result", s.result);
    v("odom_frame", s.odom_frame);
    v("base_frame", s.base_frame);
    v("lidar_frame", s.lidar_frame);
    v("left_wheel_joint", s.left_wheel_joint);
    v("right_wheel_joint", s.right_wheel_joint);
    v("steering_joint", s.steering_joint);
    v("publish_odometry", s.publish_odometry);
    v("carry_speed", s.carry_speed);
    v("carry_yaw_rate", s.carry_yaw_rate);
  }
  void validate() const {
    core::check(!field.empty(), "field", "required (a field YAML or zoo:SEED:INDEX)");
    core::check_non_negative(lead_in, "lead_in");
    core::check_non_negative(rate_factor, "rate_factor");
    core::check_positive(time_limit, "time_limit");
    core::check(!left_wheel_joint.empty(), "left_wheel_joint", "must not be empty");
    core::check(!right_wheel_joint.empty(), "right_wheel_joint", "must not be empty");
    core::check(!steering_joint.empty(), "steering_joint", "must not be empty");
    core::check_positive(carry_speed, "carry_speed");
    core::check_positive(carry_yaw_rate, "carry_yaw_rate");
  }
};

/// The run as the ground truth saw it: which corridors the robot drove, how well, what it hit.
/// No ROS: fed the simulator's ground truth (20 Hz), testable alone.
class SimScore {
 public:
  /// [s] a corridor counts as driven when the robot stayed in it this long
  static constexpr double kMinCorridorTime = 2.0;
  void add(const sim::GroundTruth& g);
  /// Corridors driven, in order (a corridor re-entered after another counts again).
  const std::vector<int>& corridors() const { return corridors_; }
  double max_lateral_error() const { return max_lateral_; }  ///< [m] |true| while in corridors
  double mean_lateral_error() const { return n_ ? sum_lateral_ / n_ : 0.0; }  ///< [m]
  int plants_crushed() const { return crushed_; }
  /// [s] wall time from a sweep's publication to the follower's answer to it.
  void add_latency(double seconds) { latencies_.push_back(seconds); }
  /// [s] the q-quantile (0..1, nearest rank) of the latencies; nullopt without any.
  std::optional<double> latency(double q) const;
  /// JSON object: corridors, lateral errors, plants crushed, sim time, the follower's state.
  std::string json(double sim_time, const std::string& state, bool timed_out) const;

 private:
  std::vector<int> corridors_;
  int current_ = -1;
  double since_ = 0.0;
  bool counted_ = false;
  double max_lateral_ = 0.0, sum_lateral_ = 0.0;
  long n_ = 0;
  int crushed_ = 0;
  std::vector<double> latencies_;
};

/// The node. Construction reads ~params, builds the field and the simulator (throws on a bad
/// parameter or file, one line); run() steps it until the follower's mission ends, the time
/// limit or shutdown.
class SimNode {
 public:
  SimNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~SimNode();
  /// Returns 0 when the run ended with the follower's state "done", 1 otherwise.
  int run();

 private:
  class Sink;
  void on_cmd(const geometry_msgs::Twist::ConstPtr& msg);
  void on_carry(const geometry_msgs::Pose2D::ConstPtr& msg);
  void on_state(const std_msgs::String::ConstPtr& msg);
  void on_tracking(const geometry_msgs::Vector3Stamped::ConstPtr& msg);
  void sent_cloud(const ros::Time& stamp);
  void publish_truth(const sim::GroundTruth& g);
  /// The encoder counts as wheel joint positions [rad] on `joint_states`.
  void publish_joints(const core::WheelEncoderSample& s);
  void finish(bool timed_out);

  ros::NodeHandle nh_, pnh_;
  SimNodeConfig config_;
  std::unique_ptr<sim::Field> field_;
  std::unique_ptr<sim::Simulator> sim_;
  std::unique_ptr<Sink> sink_;
  /// the base's wheel odometry (encoders + IMU), as a robot's base driver publishes it
  std::optional<localize::Localizer> odometry_;
  ros::Publisher clock_pub_, cloud_pub_, odom_pub_, imu_pub_, truth_pub_, joints_pub_;
  int ticks_per_rev_ = 1;    ///< the simulated encoders' resolution (counts -> joint angle)
  WheelJointConfig joints_;  ///< the wheel joints of `joint_states` (from the parameters)
  ros::Subscriber cmd_sub_, state_sub_, tracking_sub_, carry_sub_;
  /// cmd_vel and the tracking output are taken on their own thread, when they arrive
  ros::CallbackQueue answers_;
  std::unique_ptr<ros::AsyncSpinner> answer_spinner_;
  std::mutex mutex_;                                    ///< guards cmd_, sent_, score_'s latencies
  std::map<std::uint64_t, ros::WallTime> sent_;         ///< sweep stamp [ns] -> wall time published
  static constexpr std::size_t kMaxPendingFrames = 50;  ///< sweeps kept waiting for an answer
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  core::Twist2 cmd_;
  std::string state_;
  SimScore score_;
  friend class Sink;
};

}  // namespace rownav::ros_bridge
