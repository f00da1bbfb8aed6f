#pragma once
/// @file swept_box.hpp The stop box swept along the arc the robot drives (issue 13 follow-up).
///
/// The obstacle stop checks a box ahead of the footprint. While the robot turns (a headland
/// bulb, an entry arc) a straight box points off the path: it holds the row ends the arc passes
/// beside, and the robot stopped for them (car-like skip-row turn, BENCHMARK.md). As Nav2's
/// regulated pure pursuit checks collisions along the commanded arc, the box here follows the
/// arc of the current curvature: arc length from the base in [s_min, s_max], distance from the
/// arc below half the footprint width.
#include <Eigen/Core>

namespace rownav::navigate {

/// True when `p` (base frame, x forward, y left) lies in the box swept along the arc of
/// `curvature` [1/m] (left +) from arc length s_min to s_max [m] ahead of the base, within
/// `half_width` [m] of the arc. |curvature| below 1e-3: the straight box. NaN: false.
bool in_swept_box(const Eigen::Vector2d& p, double curvature, double s_min, double s_max,
                  double half_width);

}  // namespace rownav::navigate
