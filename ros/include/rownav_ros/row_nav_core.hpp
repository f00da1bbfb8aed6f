#pragma once
/// @file row_nav_core.hpp The node's per-frame processing, without a node handle: ROS messages
/// in, the command and what to publish out. Wires the stack as io::run_closed_loop does:
/// DetectionPipeline -> tracker -> end of row -> Navigator (controller inside) -> apply_limits,
/// with the odometry pose interpolated at the frame stamp.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rownav/control/controller.hpp"
#include "rownav/detect/pipeline.hpp"
#include "rownav/navigate/end_of_row.hpp"
#include "rownav/navigate/navigator.hpp"
#include "rownav/track/row_tracker.hpp"
#include "rownav_ros/conversions.hpp"
#include "rownav_ros/node_config.hpp"
#include "rownav_ros/odom_buffer.hpp"

namespace rownav::ros_bridge {

/// The answer for one LiDAR frame.
struct FrameResult {
  bool ok = false;     ///< false: `error` says why, cmd is zero, nothing else is meaningful
  std::string error;   ///< one line
  double stamp = 0.0;  ///< [s] frame stamp
  core::Twist2 cmd;    ///< limited command (zero on error or in a terminal state)
  track::RowTracking tracking;
  navigate::NavState state = navigate::NavState::in_row;
  navigate::StopReason stop_reason = navigate::StopReason::none;
  std::vector<navigate::NavEvent> events;
  int corridor = -1;  ///< corridor of the plan being served
};

/// Per-frame processing of rownav_node. Not thread-safe (call from one callback queue).
/// Frame and odometry handlers never throw.
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
  /// Gyro yaw rate (used when NodeConfig::use_imu).
  void on_imu(const sensor_msgs::Imu& msg);

  const StackSetup& setup() const { return setup_; }
  const navigate::Navigator& navigator() const { return *navigator_; }
  /// Points handed to the detector in the last frame (base frame).
  const std::vector<Eigen::Vector2f>& last_points() const;

 private:
  FrameResult step(const core::RowObservation& obs);
  FrameResult fail(double stamp, std::string why);
  core::Twist2 limit(const core::Twist2& cmd, double stamp);

  StackSetup setup_;
  std::unique_ptr<detect::DetectionPipeline> pipeline_;
  std::unique_ptr<track::RowTracker> tracker_;
  std::unique_ptr<control::PathController> controller_;
  std::unique_ptr<navigate::EndOfRowDetector> end_of_row_;
  std::unique_ptr<navigate::Navigator> navigator_;
  OdomBuffer odom_;
  bool mount_set_ = false, started_ = false;
  std::optional<core::ImuSample> imu_;
  core::Twist2 last_cmd_;
  std::optional<double> last_cmd_stamp_;
};

}  // namespace rownav::ros_bridge
