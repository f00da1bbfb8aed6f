#pragma once
/// @file nav_stack_setup.hpp The robot-file part of navigate::NavStackConfig, shared by
/// `rownav run` (the simulator runner) and the ROS node, so both derive it the same way; and the
/// robot file read as the stack knows it (core::RobotSpec), without the simulator.
#include <array>
#include <filesystem>
#include <string_view>

#include "rownav/core/robot_spec.hpp"
#include "rownav/navigate/nav_stack_config.hpp"

namespace rownav::io {

/// The keys a robot file may hold for the simulator's true kinematics (sim::RobotConfig's
/// simulation_fields); load_robot_spec skips them. A test keeps the two lists equal.
inline constexpr std::array<std::string_view, 4> kSimulatorRobotKeys{
    "x_icr", "alpha", "slip_noise", "slip_time_constant"};

/// Reads a robot file (config/robots/*.yaml) strictly as core::RobotSpec, skipping the
/// simulator's keys; throws InputError with file:line:col.
core::RobotSpec load_robot_spec(const std::filesystem::path& file);

/// NavStackConfig::robot and limits: the robot's footprint and turning ability, and its limits,
/// applied to every command as a base controller would.
void nav_stack_robot_limits(navigate::NavStackConfig& nav, const core::RobotSpec& robot);

/// nav_stack_robot_limits, plus the localizer with the NOMINAL kinematics the robot's firmware
/// assumes (io::localizer_config_for, encoders of `ticks_per_rev`) and the stack's sweep period
/// from the LiDAR rate [Hz].
void nav_stack_robot(navigate::NavStackConfig& nav, const core::RobotSpec& robot,
                     int ticks_per_rev, double lidar_rate_hz);

}  // namespace rownav::io
