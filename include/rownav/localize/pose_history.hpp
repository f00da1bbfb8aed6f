#pragma once
/// @file pose_history.hpp A short history of odometry poses (an external odometry source: a
/// robot's own nav_msgs/Odometry), queried at LiDAR frame stamps.
#include <deque>
#include <optional>

#include "rownav/core/pose2.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::localize {

/// A stamped odometry pose and body velocity.
struct StampedPose {
  double stamp = 0.0;  ///< [s]
  core::Pose2 T_odom_base;
  core::Twist2 twist;
};

/// Poses of the last `history` seconds. Queries interpolate (core::interpolate) between the two
/// neighbours, and extrapolate the newest pose with its twist up to `max_extrapolation` past
/// it. Never throws.
class PoseHistory {
 public:
  PoseHistory(double history, double max_extrapolation)
      : history_(history), max_extrapolation_(max_extrapolation) {}
  /// Adds a sample; returns false (and ignores it) when it is not newer than the newest one or
  /// holds non-finite values.
  bool push(const StampedPose& s);
  /// Pose at `stamp`; nullopt before the oldest sample, beyond the extrapolation limit, or
  /// when empty.
  std::optional<core::Pose2> at(double stamp) const;
  /// Newest sample (nullopt when empty).
  std::optional<StampedPose> latest() const;
  void clear() { samples_.clear(); }
  std::size_t size() const { return samples_.size(); }

 private:
  double history_, max_extrapolation_;
  std::deque<StampedPose> samples_;
};

}  // namespace rownav::localize
