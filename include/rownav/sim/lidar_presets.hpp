#pragma once
/// @file lidar_presets.hpp Named LiDAR configurations of real sensors (datasheet values).
///
/// Included by lidar.hpp, and includes it, so either header gives both the presets and the
/// complete LidarConfig.
#include <string>
#include <string_view>
#include <vector>

namespace rownav::sim {

struct LidarConfig;

/// Configuration of a real sensor by name:
/// - "os1_16": Ouster OS1-16, 1024 columns, 10 Hz, 16 rings over -16.6..16.6 deg, 0.3-120 m;
/// - "os1_64": Ouster OS1-64, 1024 columns, 10 Hz, 64 rings over -22.5..22.5 deg, 0.3-120 m;
/// - "vlp16": Velodyne VLP-16, 16 rings -15..15 every 2 deg, 0.2 deg azimuth at 10 Hz
///   (1800 columns), 100 m, noise 0.03 m;
/// - "sick_tim571": 2D, 270 deg at 0.33 deg (811 beams), 0.05-25 m, 15 Hz;
/// - "sick_lms111": 2D, 270 deg at 0.5 deg (541 beams), 0.5-20 m, 25 Hz;
/// - "lms_1081": 2D, 270 deg at 0.25 deg (1081 beams), 0.05-10 m, 25 Hz (the Oz robot and the
///   real corn data set).
/// Throws std::invalid_argument listing the valid names when `name` is unknown.
LidarConfig lidar_preset(std::string_view name);

/// Names accepted by lidar_preset, in a fixed order.
std::vector<std::string> lidar_preset_names();

}  // namespace rownav::sim

#include "rownav/sim/lidar.hpp"
