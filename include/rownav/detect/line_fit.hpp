#pragma once
/// @file line_fit.hpp Line fitting and the assembly of a RowObservation, shared by the detectors.
#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "rownav/core/row_observation.hpp"

namespace rownav::detect {

/// Total-least-squares (orthogonal) line through points; nullopt for < 2 points or when they
/// all coincide. The line is oriented towards +x.
std::optional<core::Line2> fit_line_tls(std::span<const Eigen::Vector2f> points);

/// Builds a RowLine from a line and its support points (offset, heading, extent, rms).
core::RowLine make_row_line(const core::Line2& line, std::span<const Eigen::Vector2f> support);

/// How finalize_observation pairs the corridor rows (issue 11).
struct CorridorPairConfig {
  /// [deg] the two corridor rows of one frame are parallel within this angle. A line crossing
  /// the corridor (the scan plane meeting the ground ahead, a headland edge) that happens to be
  /// the nearest line on one side is no corridor row: on the 2D frames of
  /// tests/detect/nearest_row_2d_test.cpp such lines stand 35-40 deg off the rows, true pairs
  /// (robot yawed up to 10 deg, rows fitted on 1 m of returns) within about 10 deg.
  double max_skew_deg = 20.0;
};

/// Completes an observation from its rows: sorts them right to left, picks the nearest row on
/// each side (by offset at x = `lookahead`), fills the corridor, the common heading (support-
/// weighted mean when `heading` is NaN) and the status (ok with both sides, degraded with one,
/// no_rows with none). `confidence` is left to the caller when already > 0, otherwise derived
/// from the support and fit of the corridor rows. When the nearest rows on the two sides are not
/// parallel (`pair`), the one fewer other rows agree with (then: the one whose returns start
/// farther from the robot) gives way to the nearest row on its side parallel to the other, if any.
void finalize_observation(core::RowObservation& obs, double lookahead = 0.0,
                          const CorridorPairConfig& pair = {});

}  // namespace rownav::detect
