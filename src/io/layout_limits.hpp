#pragma once
// Private to rownav_io: the bounds sim::LayoutLimits puts on a layout file, checked by the
// layout reader before anything is dressed (nlohmann_json stays a private dependency).
#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "rownav/sim/field_config.hpp"

namespace rownav::io::detail {

/// A layout point in the local frame [m] and where it is in the file ("feature 3", "line 7").
struct LocatedPoint {
  Eigen::Vector2d p;
  const std::string* where;
};

/// Parses JSON text, refusing arrays / objects nested deeper than `max_depth`.
/// @throws InputError "<file>:byte N: invalid JSON" or "...: nested deeper than ..."
nlohmann::json parse_json_limited(const std::string& text, int max_depth, const std::string& file);

/// Throws InputError at the point farthest from the median point when the box around `points`
/// has a side longer than limits.max_extent (one mistyped coordinate is the usual cause).
void check_layout_extent(const std::vector<LocatedPoint>& points, const sim::LayoutLimits& limits,
                         const std::string& file);

}  // namespace rownav::io::detail
