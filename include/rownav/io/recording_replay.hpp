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

}  // namespace rownav::io
