#pragma once
/// @file odom_buffer.hpp The node's odometry history: localize::PoseHistory of the core.
#include "rownav/localize/pose_history.hpp"

namespace rownav::ros_bridge {

using OdomState = localize::StampedPose;
using OdomBuffer = localize::PoseHistory;

}  // namespace rownav::ros_bridge
