#pragma once
/// @file row_direction.hpp The rows' heading in a frame as the direction along which its returns
/// project most sharply (rownav, issue 11).
///
/// Parallel rows seen from inside a corridor are long lines of returns: projected across the
/// true row direction they pile up in a few narrow peaks, projected across any other direction
/// they smear. The heading whose across-row histogram has the largest sum of squared bin counts
/// (the number of return pairs sharing a bin) is the rows' heading; weeds, posts and scattered
/// clutter are equally sharp or equally smeared in every direction and do not move the maximum.
/// It is the projection principle of Hough-type row detectors (Nehme 2021 sec. 3.2: the heading
/// as the accumulator column of maximum variance) reduced to one angle. Detectors whose own
/// heading comes from a few returns (the cone of Bertoglio 2023 stops at the N-th return) use it
/// on planar scans, where a sparse near row leaves that heading tens of degrees off
/// (tests/detect/nearest_row_2d_test.cpp).
#include <Eigen/Core>
#include <optional>
#include <span>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::detect {

/// Parameters of the row-direction search (rownav, issue 11).
struct RowDirectionConfig {
  bool enabled = true;  ///< search the rows' heading in planar scans
  /// [deg] headings searched, +-this around the robot's x axis: a robot following a corridor is
  /// within a few tens of degrees of its rows (the 2D test yaws it by up to 10 deg)
  double max_angle_deg = 30.0;
  double step_deg = 0.5;  ///< [deg] search step (refined by a parabola through the best three)
  /// [-] a first pass steps coarse_factor x step_deg with coarse_factor x bin, the fine pass
  /// searches one coarse step each side of its best (4: 2.7x faster). 1: one fine sweep. The
  /// coarse bin must stay well under the row spacing: 4 (0.4 m bins) cost corn_rows_2d's 0.75 m
  /// rows a fifth of their cone_rect corridors (777 -> 616 frames, BENCHMARK.md issue 11)
  int coarse_factor = 1;
  /// [m] histogram bin across the rows: about a canopy half width (0.15-0.3 m walls), so one
  /// row's returns fill one or two bins
  double bin = 0.1;
  double max_range = 8.0;  ///< [m] returns farther from the robot are ignored (sparse, noisy)
  int min_points = 20;     ///< [-] fewer returns in range: no heading
  /// [-] the sharpest heading's score over the mean score of all headings: below it the frame
  /// holds no line structure (open field, a headland) and no heading is returned
  double min_contrast = 1.2;
  /// [deg] detectors that fit rows (PEARL, OPAL, RUBY) drop a fitted row whose heading is farther
  /// than this from the sharpest direction: a short fit a few degrees off the rows (a piece of
  /// the near row plus returns of the row behind) puts its offset at x = 0 0.3-0.7 m out and
  /// wins the corridor pick (tests/detect/nearest_row_2d_test.cpp); full-length row fits are
  /// within 1-3 deg of it on those frames
  double max_row_skew_deg = 5.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("max_angle_deg", s.max_angle_deg);
    v("step_deg", s.step_deg);
    v("coarse_factor", s.coarse_factor);
    v("bin", s.bin);
    v("max_range", s.max_range);
    v("min_points", s.min_points);
    v("min_contrast", s.min_contrast);
    v("max_row_skew_deg", s.max_row_skew_deg);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// The rows' heading [rad] in the robot frame (x forward, y left), within +-max_angle_deg;
/// nullopt when disabled, with too few returns or no sharp direction. Never throws; NaN / Inf
/// points are skipped.
std::optional<double> row_direction(std::span<const Eigen::Vector2f> points,
                                    const RowDirectionConfig& config);

/// Planar scans: drops the rows of `obs` whose heading is more than max_row_skew_deg off the
/// sharpest direction of `points` and picks the corridor again (finalize_observation with
/// `lookahead`); nothing changes when no direction is sharp. Returns the rows dropped. Never
/// throws.
int keep_rows_along_direction(core::RowObservation& obs, std::span<const Eigen::Vector2f> points,
                              const RowDirectionConfig& config, double lookahead = 0.0);

}  // namespace rownav::detect
