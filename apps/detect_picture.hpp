#pragma once
/// @file detect_picture.hpp The picture of one detected frame (`rownav detect --svg`).
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "rownav/core/row_observation.hpp"

namespace rownav::app {

/// Robot view of one frame, base frame with x forward drawn up and y left drawn left: the points
/// given to the detector, every detected row over its support, the left / right rows and the
/// corridor centre highlighted, the robot at the origin. PNG, SVG or PDF by extension.
void write_detection_picture(const std::filesystem::path& out,
                             const std::vector<Eigen::Vector2f>& points_base,
                             const core::RowObservation& obs, const std::string& title);

}  // namespace rownav::app
