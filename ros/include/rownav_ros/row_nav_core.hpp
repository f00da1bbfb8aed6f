#pragma once
/// @file row_nav_core.hpp The node's adapter, without a node handle: ROS messages converted and
/// handed to navigate::NavStack (the stack `rownav run` measures), its answer returned for
/// publishing. The robot's nav_msgs/Odometry is the stack's external odometry; the IMU gives
/// the yaw rate (use_imu) and levels each sweep by gravity.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rownav/navigate/nav_stack.hpp"
#include "rownav_ros/conversions.hpp"
#include "rownav_ros/joint_state_conversion.hpp"
#include "rownav_ros/mission_control.hpp"
#include "rownav_ros/navsat_conversion.hpp"
#include "rownav_ros/node_config.hpp"

namespace rownav::ros_bridge {

/// The answer for one LiDAR frame.
struct FrameResult {
  bool ok = false;     ///< false: `error` says why, cmd is zero, nothing else is meaningful
  bool held = false;   ///< the mission is not running: tracked, but cmd zero (NavStack::set_held)
  std::string error;   ///< one line
  double stamp = 0.0;  ///< [s] frame stamp
  core::Twist2 cmd;    ///< limited command (zero on error or in a terminal state)
  track::RowTracking tracking;
  navigate::NavState state = navigate::NavState::in_row;
  navigate::StopReason stop_reason = navigate::StopReason::none;
  std::vector<navigate::NavEvent> events;
  int corridor = -1;  ///< corridor of the plan being served
};

/// The answer to a wheel JointState message (NodeConfig::odometry = "joint_states").
struct JointAnswer {
  std::optional<core::Twist2> cmd;  ///< as on_odom: the command between frames, or nothing
  std::string skipped;              ///< empty, or why the message gave no wheel sample
};

/// The watchdog tick's answer (a timer, between messages).
struct TickResult {
  core::Twist2 cmd;  ///< zero while inputs are stale, before the first frame, or stopped
  navigate::InputHealth health = navigate::InputHealth::ok;
  double lidar_age = 0.0, odometry_age = 0.0;  ///< [s]
  navigate::NavState state = navigate::NavState::in_row;
  navigate::StopReason stop_reason = navigate::StopReason::none;
  std::vector<navigate::NavEvent> events;
};

/// The NavStack rownav_node runs for `setup` with the LiDAR at `T_base_lidar` (RowNavCore owns
/// one; tests/ros/cli_ros_equivalence_test.cpp compares it with `rownav run`'s). Throws like
/// RowNavCore's constructor.
std::unique_ptr<navigate::NavStack> make_node_stack(const StackSetup& setup,
                                                    const Eigen::Isometry3d& T_base_lidar);

/// Per-frame processing of rownav_node. Not thread-safe (call from one callback queue).
/// Frame and odometry handlers never throw.
///
/// Mission control (start / pause / stop, MissionControl): while the mission is not running
/// the stack is held (NavStack::set_held): every command is exactly zero, but LiDAR frames are
/// still detected and tracked, so a resume starts from the row models of the last frame, not
/// from models as old as the pause; the stack's watchdog goes on reporting stale inputs. (A
/// stack that went on commanding motion while the robot stands would take the odometry for
/// broken: safe stop, odometry_implausible.)
class RowNavCore {
 public:
  /// Builds the detector (identity mount until set_mount), tracker, controller, end-of-row
  /// detector and navigator from `setup`. Throws io::InputError / std::invalid_argument on a
  /// bad name or file, so a misconfigured node fails at start-up.
  explicit RowNavCore(StackSetup setup);
  ~RowNavCore();
  RowNavCore(const RowNavCore&) = delete;
  RowNavCore& operator=(const RowNavCore&) = delete;

  /// Sets T_base_lidar (rebuilds the detection pipeline). Throws like the constructor.
  void set_mount(const Eigen::Isometry3d& T_base_lidar);
  bool has_mount() const { return mount_set_; }

  /// One 3D frame (LiDAR frame).
  FrameResult on_cloud(const sensor_msgs::PointCloud2& msg);
  /// One planar scan (LiDAR frame).
  FrameResult on_scan(const sensor_msgs::LaserScan& msg);
  /// Stores the pose; once frames are processed, returns the navigator's command between frames
  /// (odometry-closed turns and line following), limited. nullopt: nothing to send.
  std::optional<core::Twist2> on_odom(const nav_msgs::Odometry& msg);
  /// Wheel joint states (NodeConfig::odometry = "joint_states"): converted to cumulative wheel
  /// counts (JointStateConverter) for the stack's own wheel odometry + IMU EKF, then answered
  /// like on_odom. Ignored (skipped) when the node takes nav_msgs/Odometry. Never throws.
  JointAnswer on_joints(const sensor_msgs::JointState& msg);
  /// The stack's own pose and velocity at `stamp` for tf / ~odom (nullopt: the pose source is
  /// the robot's nav_msgs/Odometry, or no wheel sample yet).
  std::optional<OdomSample> own_odometry(double stamp) const;
  /// The command at `stamp` from a timer: the stack's watchdog zeroes it when the LiDAR or the
  /// odometry stopped coming (no message: no other call would). Never throws.
  TickResult tick(double stamp);
  /// IMU: gravity levelling of sweeps, gyro yaw rate (NodeConfig::use_imu).
  void on_imu(const sensor_msgs::Imu& msg);
  /// GNSS: converted to the local ENU frame (NavSatConverter) and handed to the stack, a
  /// rejected fix as an outage (valid = false). Returns the conversion (why it was rejected).
  NavSatConversion on_fix(const sensor_msgs::NavSatFix& msg);

  /// Operator requests (MissionControl, with the navigator's current state). A start after a
  /// stop or after the navigator ended the mission begins a new one where the robot stands
  /// (NavStack::restart_mission: the odom frame continues). A resume after a pause during which
  /// the robot was carried out of its rows or into another corridor (NavStack::resume_blocker)
  /// is refused with the reason, and the mission stays paused (issue 15).
  MissionAnswer start();
  /// start(), and a start that begins a new mission reads the mission afresh: `node`'s mission
  /// file and corridor_count (an operator sets `~mission` / `~corridor_count`, puts the robot at
  /// the entrance of that plan's first corridor and calls ~start; issue 15). A file that does
  /// not load or an order that does not resolve answers false in one line and starts nothing.
  /// A resume (after a pause) or a start of the mission already running ignores `node`.
  MissionAnswer start(const NodeConfig& node);
  MissionAnswer pause() { return mission_.pause(navigator().state()); }
  MissionAnswer stop() { return mission_.stop(navigator().state()); }
  const MissionControl& mission() const { return mission_; }
  /// The state to publish for the navigator state `nav` (MissionControl::state).
  std::string state_name(navigate::NavState nav) const { return mission_.state(nav); }

  const StackSetup& setup() const { return setup_; }
  const navigate::Navigator& navigator() const { return stack_->navigator(); }
  const navigate::NavStack& stack() const { return *stack_; }
  /// Points handed to the detector in the last frame (base frame).
  const std::vector<Eigen::Vector2f>& last_points() const;

 private:
  FrameResult frame(double stamp);
  /// A pose sample (odometry or wheel counts) accepted at `stamp`: the command between frames
  /// once frames are processed, else nothing.
  std::optional<core::Twist2> pose_received(double stamp);
  FrameResult fail(double stamp, std::string why);
  /// NavStack::command at `stamp` (the stack held while the mission does not run), or at the
  /// newest instant already commanded when that is later: the watchdog timer (ros::Time::now()) may
  /// run ahead of the odometry, and a frame commanded before it was answered as a late command and
  /// never published.
  navigate::NavCommand command_at(double stamp);

  StackSetup setup_;
  std::unique_ptr<navigate::NavStack> stack_;
  MissionControl mission_;
  NavSatConverter navsat_;
  JointStateConverter joints_;
  bool mount_set_ = false, started_ = false;
  std::optional<double> last_odom_stamp_;
  std::optional<double> last_command_stamp_;  // [s] newest stamp NavStack::command was given
};

}  // namespace rownav::ros_bridge
