#pragma once
/// @file nav_stack_setup.hpp The robot-file part of navigate::NavStackConfig, shared by
/// `rownav run` (the simulator runner) and the ROS node, so both derive it the same way.
#include "rownav/navigate/nav_stack_config.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::io {

/// NavStackConfig::robot, limits and localizer of a simulated robot: its footprint, limits and
/// the NOMINAL kinematics its firmware assumes (io::localizer_config_for); the stack's sweep
/// period from the LiDAR rate.
void nav_stack_robot(navigate::NavStackConfig& nav, const sim::RobotConfig& robot,
                     const sim::SimConfig& sensors);

}  // namespace rownav::io
