#pragma once
/// @file localize_setup.hpp Localizer configuration for a robot and from YAML.
#include <filesystem>

#include "rownav/core/robot_spec.hpp"
#include "rownav/localize/localizer.hpp"

namespace rownav::io {

/// The NOMINAL parameters the robot's firmware would assume: drive model from the robot's drive
/// kind, geometry from the robot, `ticks_per_rev` of its encoders, x_icr = track_width / 2 and
/// alpha = 1 (a simulated robot's true x_icr / alpha are unknown to a real user). The rest:
/// defaults.
localize::LocalizerConfig localizer_config_for(const core::RobotSpec& robot, int ticks_per_rev);

/// Loads a LocalizerConfig YAML file strictly (see io::load_config); throws InputError with
/// file:line:col.
localize::LocalizerConfig load_localizer_config(const std::filesystem::path& file);

}  // namespace rownav::io
