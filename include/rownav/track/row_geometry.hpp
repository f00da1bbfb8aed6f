#pragma once
/// @file row_geometry.hpp Small geometry shared by the row trackers: row lines as y = a x + b in
/// a base frame, moving them between base frames by odometry, and the corridor deviations of a
/// pair of followed rows.
#include <optional>
#include <vector>

#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"

namespace rownav::track {

/// A row line y = a x + b (Lan 2021 eq. (23); Malavazi 2018 sec. 2.3.3).
struct SlopeIntercept {
  double a = 0.0;  ///< [-] slope dy / dx
  double b = 0.0;  ///< [m] y at x = 0
};

/// Slope / intercept of a line that is not parallel to y (|direction.x| > 1e-9 assumed; a
/// vertical line yields a huge but finite slope).
SlopeIntercept slope_intercept(const core::Line2& line);

/// Line y = a x + b oriented towards +x.
core::Line2 line_of(const SlopeIntercept& si);

/// A line given in the previous base frame, expressed in the current one, where T_prev_now is
/// the odometry increment T_odom_base(prev)^-1 * T_odom_base(now). Keeps the +x orientation.
core::Line2 move_line(const core::Line2& line_prev, const core::Pose2& T_prev_now);

/// Slope / intercept moved like move_line.
SlopeIntercept move_line(const SlopeIntercept& si_prev, const core::Pose2& T_prev_now);

/// Deviations of the robot from a corridor centre line given in its base frame.
struct Deviation {
  double lateral = 0.0;  ///< [m] signed distance of the base origin from the centre line, left +
  double heading = 0.0;  ///< [rad] robot heading minus the centre line heading
};

/// Deviation of the base origin from `centre_base` (oriented forward).
Deviation deviation(const core::Line2& centre_base);

/// Corridor centre line between a left and a right row line (base frame, both oriented
/// forward): the bisector through the mid point of their points at x = 0.
core::Line2 centre_between(const core::Line2& left, const core::Line2& right);

/// Centre line half a spacing to the right (`row_is_left`) or left of a single row.
core::Line2 centre_from_one(const core::Line2& row, bool row_is_left, double spacing);

/// Perpendicular distance between two near-parallel lines, measured at x = 0 of the first.
double spacing_between(const core::Line2& left, const core::Line2& right);

/// [m] row spacing from row centre offsets (any order; issue 10): every difference of adjacent
/// centres counts, a difference spanning k spacings (a row missing, undetected or hidden) as k
/// of them, k = its ratio to the lower median difference rounded; the median of the normalised
/// differences. 0 with fewer than two centres.
double robust_spacing(std::vector<double> centres);

/// True when every coordinate of the pose is finite.
bool finite(const core::Pose2& p);

}  // namespace rownav::track
