#pragma once
/// @file recording_replay.hpp A recording played into navigate::NavStack the way a robot's
/// drivers would deliver it: every sample in time order, each LiDAR frame handed over when its
/// sweep is complete (stamp + sweep period) and answered by NavStack::command at that instant.
/// `rownav track` and `rownav detect` on a recording are this replay and nothing else.
#include <functional>

#include "rownav/io/recording.hpp"
#include "rownav/navigate/nav_stack.hpp"

namespace rownav::io {

/// How a replay feeds the stack.
struct ReplayOptions {
  /// The recorded true poses as an external odometry (`--odometry truth`, analysis only; the
  /// stack must be configured with OdometryInput::external); else encoders, IMU and GNSS.
  bool truth_odometry = false;
};

/// [s] LiDAR period: the median interval between recorded frames (fallback when unknown).
double sweep_period(const Recording& rec, double fallback);

/// Plays `rec` into `stack`; `on_frame` receives the command answering each LiDAR frame (clouds
/// read lazily: InputError on a bad PCD file).
void replay_recording(const Recording& rec, navigate::NavStack& stack, const ReplayOptions& options,
                      const std::function<void(const navigate::NavCommand&)>& on_frame);

/// A live run's inputs in the order NavStack received them (`inputs.csv` of a recording made
/// with ClosedLoopSetup::record_inputs): `kind,index,stamp,v,omega,state` per call, kind one of
/// encoders, imu, gnss, cloud, scan (index into the recording's stream) or command (the stamp
/// and the command the live stack answered).
inline constexpr const char* kInputLog = "inputs.csv";

/// One command of a log replay: what the live run answered and what the replay answers.
struct ReplayedCommand {
  double stamp = 0.0;
  core::Twist2 live, replayed;
  std::string live_state, replayed_state;
};

/// Where a log replay's calls go: a NavStack as it is (the CLI), or an adapter that converts
/// each sample first (the ROS node's messages, tests/ros/cli_ros_equivalence_test.cpp).
class InputLogSink {
 public:
  virtual ~InputLogSink() = default;
  virtual void on_encoders(const core::WheelEncoderSample& s) = 0;
  virtual void on_imu(const core::ImuSample& s) = 0;
  virtual void on_gnss(const core::GnssFix& s) = 0;
  virtual void on_cloud(core::PointCloud cloud) = 0;
  virtual void on_scan(core::Scan2D scan) = 0;
  virtual navigate::NavCommand command(double stamp) = 0;
};

/// Replays `rec`'s input log into `sink` call by call. InputError on a malformed log or an
/// index outside its stream.
std::vector<ReplayedCommand> replay_input_log(const Recording& rec, InputLogSink& sink);
/// The same into `stack` as it is.
std::vector<ReplayedCommand> replay_input_log(const Recording& rec, navigate::NavStack& stack);

}  // namespace rownav::io
