#pragma once
/// @file mission_io.hpp Loading a mission file (config/missions/*.yaml, navigate::MissionPlan keys)
/// strictly: unknown keys and bad values are one-line InputErrors "file:line:col: key: reason".
#include <filesystem>

#include "rownav/navigate/mission_plan.hpp"

namespace rownav::io {

/// Loads and validates a mission file.
navigate::MissionPlan load_mission(const std::filesystem::path& file);

}  // namespace rownav::io
