#pragma once
/// @file nearest_row.hpp The nearest row on each side of a 2D scan (issue 11).
///
/// A planar scanner sees each row only at its own height: the beams meet the near row's canopy at
/// a shallow angle and many pass through its gaps to the rows behind. Close to the sensor the near
/// row's returns crowd into a few voxels, the rest of it is sparse, and the row one spacing out
/// (seen face-on through the gaps) can end up with more support and a longer extent. Detectors that
/// rank rows by support (RANSAC scores, Hough segment strength, PEARL label costs, the rectangles
/// of Bertoglio 2023 limited to a short window beside the robot) then report it as the corridor
/// row. Occlusion settles the question: nothing stands between the robot and the nearest row, so a
/// row-like band of returns between the robot and the reported row IS the nearest row. Lan 2021
/// sec. 3.3 ("closest trunk each side"), Bertoglio 2023 sec. II-B (rectangles grown outwards: the
/// first points met) and Malavazi 2018 sec. 2.3 (the data-filter boxes beside the robot) all take
/// the corridor rows as the nearest ones; this check restores that choice after the fit.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::detect {

/// Parameters of the nearest-row check (rownav, issue 11).
struct NearestRowConfig {
  bool enabled = true;  ///< check the corridor rows against the returns between them and the robot
  /// Also on points that are not one planar scan (3D clouds projected to 2D, synthetic scenes;
  /// DetectorInput::planar_scan). Off: a projected cloud holds the weeds below the row canopy,
  /// and a weed strip mid-corridor sits exactly where a skipped row would (half the apparent
  /// width in); a planar scanner above the weeds does not see them.
  bool on_clouds = false;
  /// [m] half width of a row band, capped at band_fraction x the corridor width: half the
  /// 0.3-0.6 m canopy wall of a VSP vineyard (sim/vineyard.hpp canopy_width; Nehme 2021 sec. 4)
  double band_half_width = 0.2;
  double band_fraction = 0.15;  ///< [-] cap of the band half width, fraction of the corridor width
  /// [-] a candidate lies at least this fraction of the reported corridor width inside the
  /// reported row: a skipped row is at 1/2 of it; canopy faces and protruding shoots of the
  /// reported row itself are closer (thick canopy: 0.3 + 0.3 m at >= 1.5 m spacing, < 0.35 x 3 m)
  double min_gap_fraction = 0.35;
  int min_points = 5;       ///< [-] returns in the band (the detectors' own minimum: 5-8)
  double min_length = 1.0;  ///< [m] extent of the band along the rows (one vine, 1 m apart)
  /// [deg] the band's own line (total least squares) is this close to the rows' heading: the
  /// arc where the scan plane meets rising ground ahead crosses the corridor, a row does not
  double max_angle_deg = 10.0;
  /// [-] band density (per metre across) over the density of the rest of the corridor between
  /// the robot and the reported row: a row stands out of the empty corridor, scattered clutter
  /// (~1) does not
  double min_contrast = 3.0;
  /// [-] a band that starts ahead of (or behind) the robot is at least this fraction of that
  /// distance long: a row seen from the robot runs from where it comes into view to the range
  /// limit (a skipped near row under a thin canopy: 5.6-6.4 m from 2.9-4.3 m ahead), while the
  /// bands that are no row are short pieces far ahead (weeds, a post, the scan plane touching a
  /// bump: 1-2 m from 5.9-8.8 m ahead; tests/detect/nearest_row_2d_test.cpp frames)
  double min_length_per_start = 0.5;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("on_clouds", s.on_clouds);
    v("band_half_width", s.band_half_width);
    v("band_fraction", s.band_fraction);
    v("min_gap_fraction", s.min_gap_fraction);
    v("min_points", s.min_points);
    v("min_length", s.min_length);
    v("max_angle_deg", s.max_angle_deg);
    v("min_contrast", s.min_contrast);
    v("min_length_per_start", s.min_length_per_start);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// True when a stretch along the rows from `lo` to `hi` [m] (robot at 0) is shorter than
/// `fraction` x the distance at which it starts: a row seen from the robot runs from where it
/// comes into view to the range limit, a short piece far ahead is a local object
/// (NearestRowConfig::min_length_per_start). A stretch across the robot is never short for it.
inline bool short_for_its_start(double lo, double hi, double fraction) {
  const double start = lo * hi > 0.0 ? std::min(std::abs(lo), std::abs(hi)) : 0.0;
  return hi - lo < fraction * start;
}

/// A row band found between the robot and a reported corridor row.
struct NearBand {
  double offset = 0.0;  ///< [m] signed distance of the band's centre line from the robot (left +)
  double inner = 0.0;   ///< [m] signed distance of its inner edge (the nearest returns)
  std::vector<Eigen::Vector2f> points;  ///< the band's returns
};

/// For the left ([0]) and right ([1]) corridor row of `obs` (with `heading` the rows' common
/// direction in the robot frame), the nearest row band between it and the robot, if any.
/// `inner_points`: how many returns define a band's inner edge. Never throws.
std::array<std::optional<NearBand>, 2> find_nearer_rows(const core::RowObservation& obs,
                                                        std::span<const Eigen::Vector2f> points,
                                                        double heading,
                                                        const NearestRowConfig& config,
                                                        int inner_points = 1);

/// Applies find_nearer_rows to an observation of full rows: each band found becomes a row (a line
/// along the common heading through the band's returns) and the observation is finalized again
/// (finalize_observation with `lookahead`). `replace`: the band replaces the skipped row (two-row
/// detectors) instead of joining the rows. Returns the number of rows stepped in. Never throws.
int step_in_nearest_rows(core::RowObservation& obs, std::span<const Eigen::Vector2f> points,
                         const NearestRowConfig& config, bool not_planar, double lookahead = 0.0,
                         bool replace = false);

}  // namespace rownav::detect
