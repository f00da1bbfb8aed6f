// rownav's simulator as a ROS 1 node (rownav_ros/sim_node.hpp).
#include "rownav_ros/sim_node.hpp"

#include <nav_msgs/Odometry.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Imu.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/localize_setup.hpp"
#include "rownav/io/mission_io.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/simulator.hpp"
#include "rownav_ros/conversions.hpp"
#include "rownav_ros/ros_params.hpp"

namespace rownav::ros_bridge {

void SimScore::add(const sim::GroundTruth& g) {
  crushed_ = g.plants_crushed;
  const int corridor = g.place == sim::Place::lane ? g.corridor : -1;
  if (corridor != current_) current_ = corridor, since_ = g.stamp, counted_ = false;
  if (corridor < 0) return;
  if (!counted_ && g.stamp - since_ >= kMinCorridorTime) {
    if (corridors_.empty() || corridors_.back() != corridor) corridors_.push_back(corridor);
    counted_ = true;
  }
  max_lateral_ = std::max(max_lateral_, std::abs(g.lateral_error));
  sum_lateral_ += std::abs(g.lateral_error), ++n_;
}

std::optional<double> SimScore::latency(double q) const {
  return io::percentile(latencies_, q);
}

std::string SimScore::json(double sim_time, const std::string& state, bool timed_out) const {
  std::ostringstream o;
  o << "{\"state\": \"" << state << "\", \"timed_out\": " << (timed_out ? "true" : "false")
    << ", \"sim_time\": " << sim_time << ", \"corridors\": [";
  for (std::size_t i = 0; i < corridors_.size(); ++i) o << (i ? ", " : "") << corridors_[i];
  o << "], \"in_corridor_lateral_error_max\": " << max_lateral_
    << ", \"in_corridor_lateral_error_mean\": " << mean_lateral_error()
    << ", \"plants_crushed\": " << crushed_ << ", \"answered_frames\": " << latencies_.size();
  // The follower's latency, message in to answer out, transport both ways included [ms].
  if (const auto m = latency(0.5)) o << ", \"latency_median_ms\": " << 1e3 * *m;
  if (const auto p = latency(0.99)) o << ", \"latency_p99_ms\": " << 1e3 * *p;
  o << "}\n";
  return o.str();
}

/// Publishes the simulator's samples as a robot's drivers would.
class SimNode::Sink : public sim::SimSink {
 public:
  explicit Sink(SimNode& n) : n_(n) {}
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>&) override {
    core::PointCloud cloud = c;
    cloud.frame_id = n_.config_.lidar_frame;
    const auto msg = to_cloud_msg(cloud);
    n_.sent_cloud(msg.header.stamp);
    n_.cloud_pub_.publish(msg);
  }
  void on_encoders(const core::WheelEncoderSample& s) override {
    n_.publish_joints(s);
    if (!n_.config_.publish_odometry) return;
    n_.odometry_->add_encoders(s);
    const auto e = n_.odometry_->latest();
    if (!e.valid) return;
    const auto& c = n_.config_;
    n_.odom_pub_.publish(
        to_odom_msg({e.stamp, e.T_odom_base, e.twist, c.odom_frame, c.base_frame}));
    n_.tf_.sendTransform(
        to_transform_msg(e.stamp, c.odom_frame, c.base_frame, e.T_odom_base.to_isometry()));
  }
  void on_imu(const core::ImuSample& s) override {
    if (n_.config_.publish_odometry) n_.odometry_->add_imu(s);
    n_.imu_pub_.publish(to_imu_msg(s, n_.config_.base_frame));
  }
  void on_ground_truth(const sim::GroundTruth& g) override {
    {
      const std::lock_guard<std::mutex> lock(n_.mutex_);
      n_.score_.add(g);
    }
    n_.publish_truth(g);
  }

 private:
  SimNode& n_;
};

SimNode::SimNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  read_config(pnh_, "", config_);
  const auto& c = config_;
  field_ = std::make_unique<sim::Field>(io::load_field(c.field));
  const auto robot =
      c.robot.empty() ? sim::RobotConfig{} : io::load_config<sim::RobotConfig>(c.robot);
  const auto sensors = c.sensors.empty() ? sim::SimConfig{} : io::load_sim_config(c.sensors);
  const auto mission = c.mission.empty() ? navigate::MissionPlan{} : io::load_mission(c.mission);
  const sim::FieldTruth truth(*field_);
  const auto order = navigate::resolve_order(mission, truth.corridor_count(mission.block));
  const core::Pose2 start =
      io::mission_start(truth, order, mission.block, mission.first_turn, c.lead_in);
  sim_ = std::make_unique<sim::Simulator>(*field_, robot, sensors, start);
  odometry_.emplace(io::localizer_config_for(robot, sensors.encoders.ticks_per_rev));
  ticks_per_rev_ = sensors.encoders.ticks_per_rev;
  joints_.left_joints = {c.left_wheel_joint};
  joints_.right_joints = {c.right_wheel_joint};
  // A car-like base's driver publishes its steering joint beside the rear wheels.
  if (robot.drive == core::DriveKind::ackermann) joints_.steering_joint = c.steering_joint;
  sink_ = std::make_unique<Sink>(*this);
  ros::param::set("/use_sim_time", true);  // the nodes started after this one follow /clock
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  cloud_pub_ = nh_.advertise<sensor_msgs::PointCloud2>("cloud", 2);
  odom_pub_ = nh_.advertise<nav_msgs::Odometry>("odom", 50);
  imu_pub_ = nh_.advertise<sensor_msgs::Imu>("imu", 200);
  joints_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 100);
  truth_pub_ = pnh_.advertise<nav_msgs::Odometry>("ground_truth", 20);
  state_sub_ = nh_.subscribe(c.state_topic, 10, &SimNode::on_state, this);
  carry_sub_ = pnh_.subscribe("carry", 10, &SimNode::on_carry, this);
  ros::NodeHandle answers(nh_);
  answers.setCallbackQueue(&answers_);
  cmd_sub_ = answers.subscribe("cmd_vel", 10, &SimNode::on_cmd, this);
  tracking_sub_ = answers.subscribe(c.tracking_topic, 10, &SimNode::on_tracking, this);
  answer_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &answers_);
  answer_spinner_->start();
  static_tf_.sendTransform(
      to_transform_msg(sim_->time(), c.base_frame, c.lidar_frame, sensors.lidar.T_base_lidar()));
  ROS_INFO("rownav_sim_node: field %s, %zu corridors planned, start (%.2f, %.2f, %.1f deg)",
           c.field.c_str(), order.size(), start.x, start.y, start.theta * 180.0 / M_PI);
}

SimNode::~SimNode() {
  // The subscriptions on answers_ go before it does (members die in reverse order).
  if (answer_spinner_) answer_spinner_->stop();
  cmd_sub_.shutdown();
  tracking_sub_.shutdown();
}

void SimNode::publish_joints(const core::WheelEncoderSample& s) {
  joints_pub_.publish(to_joint_state_msg(s, ticks_per_rev_, joints_));
}

void SimNode::on_cmd(const geometry_msgs::Twist::ConstPtr& msg) {
  core::Twist2 c;
  c.v = msg->linear.x, c.vy = msg->linear.y, c.omega = msg->angular.z;
  if (!std::isfinite(c.v) || !std::isfinite(c.vy) || !std::isfinite(c.omega)) c = {};
  const std::lock_guard<std::mutex> lock(mutex_);
  cmd_ = c;
}

void SimNode::on_carry(const geometry_msgs::Pose2D::ConstPtr& msg) {
  if (!std::isfinite(msg->x) || !std::isfinite(msg->y) || !std::isfinite(msg->theta)) {
    ROS_WARN("rownav_sim_node: ~carry with a non-finite value ignored");
    return;
  }
  ROS_INFO("rownav_sim_node: carrying the robot by (%.2f m, %.2f m, %.1f deg)", msg->x, msg->y,
           msg->theta * 180.0 / M_PI);
  // On the main thread (pnh_'s queue, spun between the steps): the next step starts the carry.
  sim_->carry(core::Pose2(msg->x, msg->y, msg->theta), config_.carry_speed, config_.carry_yaw_rate);
}

void SimNode::sent_cloud(const ros::Time& stamp) {
  const std::lock_guard<std::mutex> lock(mutex_);
  sent_[stamp.toNSec()] = ros::WallTime::now();
  while (sent_.size() > kMaxPendingFrames) sent_.erase(sent_.begin());  // never answered
}

void SimNode::on_tracking(const geometry_msgs::Vector3Stamped::ConstPtr& msg) {
  const ros::WallTime now = ros::WallTime::now();
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = sent_.find(msg->header.stamp.toNSec());
  if (it == sent_.end()) return;
  score_.add_latency((now - it->second).toSec());
  sent_.erase(sent_.begin(), std::next(it));
}

void SimNode::on_state(const std_msgs::String::ConstPtr& msg) {
  state_ = msg->data;
}

void SimNode::publish_truth(const sim::GroundTruth& g) {
  truth_pub_.publish(to_odom_msg({g.stamp, g.T_world_base, g.twist, "world", config_.base_frame}));
}

void SimNode::finish(bool timed_out) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::string text = score_.json(sim_->time(), state_, timed_out);
  ROS_INFO("rownav_sim_node: %s", text.c_str());
  if (config_.result.empty()) return;
  std::ofstream f(config_.result);
  f << text;
  if (!f) ROS_ERROR("rownav_sim_node: cannot write %s", config_.result.c_str());
}

int SimNode::run() {
  rosgraph_msgs::Clock clock;
  clock.clock.fromSec(sim_->time());
  // Wait for the follower: its cloud subscription and its cmd_vel (wall time; /clock stands).
  while (ros::ok() && (cloud_pub_.getNumSubscribers() == 0 || cmd_sub_.getNumPublishers() == 0)) {
    clock_pub_.publish(clock);
    ROS_INFO_THROTTLE(5.0, "rownav_sim_node: waiting for a subscriber of cloud and cmd_vel");
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  const double t0 = sim_->time();
  const ros::WallTime wall0 = ros::WallTime::now();
  while (ros::ok()) {
    clock.clock.fromSec(sim_->time() + sim_->dt());
    clock_pub_.publish(clock);  // before the step's samples: none is stamped in the future
    core::Twist2 cmd;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      cmd = cmd_;
    }
    sim_->step(cmd, *sink_);
    ros::spinOnce();
    if (state_ == "done" || state_ == "safe_stop") break;
    if (sim_->time() - t0 >= config_.time_limit) {
      finish(true);
      return 1;
    }
    if (config_.rate_factor > 0.0) {
      const ros::WallTime due =
          wall0 + ros::WallDuration((sim_->time() - t0) / config_.rate_factor);
      const ros::WallTime now = ros::WallTime::now();
      if (due > now) (due - now).sleep();
    }
  }
  finish(false);
  return state_ == "done" ? 0 : 1;
}

}  // namespace rownav::ros_bridge
