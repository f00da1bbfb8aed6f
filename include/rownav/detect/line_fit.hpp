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

/// Completes an observation from its rows: sorts them right to left, picks the nearest row on
/// each side (by offset at x = `lookahead`), fills the corridor, the common heading (support-
/// weighted mean when `heading` is NaN) and the status (ok with both sides, degraded with one,
/// no_rows with none). `confidence` is left to the caller when already > 0, otherwise derived
/// from the support and fit of the corridor rows.
void finalize_observation(core::RowObservation& obs, double lookahead = 0.0);

}  // namespace rownav::detect
