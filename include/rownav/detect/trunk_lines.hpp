#pragma once
/// @file trunk_lines.hpp Orchard (and any trunked crop) rows as lines through the trunk centres,
/// fused with the crown faces (issue 10).
///
/// A LiDAR inside an orchard corridor sees the corridor-side faces of the crowns, 0.5-2 m in
/// front of the trunks, irregular from tree to tree and gapped between them: a line fitted to
/// crown points is neither the row line nor stable (orchard detection rate 2-8 % for the crown
/// detectors, BENCHMARK.md). Under the crowns the trunks stand on the row line. As Lan 2021
/// (001_b5f4b55a1b95775a.txt Fig. 1) uses the trunks of a grape row, this detector
///  1. finds the trunk centres in a low height band (trunk_centres.hpp),
///  2. takes the common row heading as the direction along which most trunk pairs line up
///     (a Hough-like vote over headings, the trunks' analogue of Nehme 2021's skewing),
///  3. groups the trunks into rows across that heading and fits parallel lines with one shared
///     slope (Lan 2021's two parallel lines, here any number) by least squares,
///  4. keeps a row only with crown points above its line (a line of weeds has no crown), and
///  5. without any trunk row (a solid hedge to the ground, a long gap on both sides) gives the
///     crown detector's rows (HoughSkewDetector on every point): the row profile
///     (row_profile.hpp) then moves those face lines to the crowns' centre lines. Beside a trunk
///     row a crown face is not used: one trunk line gives the corridor (half a spacing from it).
/// Every distance that depends on the crop is either a trunk / planting fact (config) or scaled
/// by the row spacing measured in the frame.
#include <string_view>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/hough_skew.hpp"
#include "rownav/detect/row_detector.hpp"
#include "rownav/detect/trunk_centres.hpp"

namespace rownav::detect {

/// Parameters of TrunkLinesDetector. Defaults: orchards (rows 3-7 m apart, trees 1-6 m apart).
struct TrunkLinesConfig {
  TrunkCentresConfig trunks;       ///< trunk band and clustering
  double heading_min_deg = -20.0;  ///< [deg] smallest heading searched (as Nehme 2021 Fig. 6)
  double heading_max_deg = 20.0;   ///< [deg] largest heading searched
  double heading_step_deg = 0.5;   ///< [deg] coarse heading step of the vote
  double fine_step_deg = 0.05;     ///< [deg] fine step, +- one coarse step around the best
  /// [m] trunks of one row lie within this of its line: planting jitter (+-0.1-0.2 m) plus the
  /// trunk radius; also the kernel width of the heading vote
  double line_tolerance = 0.3;
  int min_trunks = 2;           ///< [-] fewer trunks on a line: not a row
  double min_row_length = 1.0;  ///< [m] along the row from first to last trunk (tree >= 1 m apart)
  /// [m] trunk pairs closer than this along the heading do not vote (no direction information)
  double min_pair_distance = 0.8;
  bool require_crown = true;  ///< a trunk row needs canopy points above its line
  /// [m] crown points within this of a trunk line count as its crown: crowns are >= 1 m wide
  double crown_window = 0.5;
  int min_crown_points = 5;    ///< [-] fewer: a line of weeds or posts, dropped
  bool crown_fallback = true;  ///< without trunk rows, the crown detector's rows
  /// the crown detector (fallback), on every point (preset HoughSkewConfig::crowns())
  HoughSkewConfig crowns = HoughSkewConfig::crowns();
  double lookahead = 0.0;  ///< [m] nearest row each side judged at this x (line_fit.hpp)
  /// [-] planar scans: a row that starts ahead of (or behind) the robot is at least this fraction
  /// of that distance long, as a row band of the nearest-row check (nearest_row.hpp
  /// min_length_per_start): the crown fallback's short pieces 5-10 m ahead (weeds, a post, the
  /// scan plane touching a bump) stood between the robot and a corridor row and won the pick
  /// (tests/detect/nearest_row_2d_test.cpp; issue 11)
  double planar_min_length_per_start = 0.5;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("trunks", s.trunks);
    v("heading_min_deg", s.heading_min_deg);
    v("heading_max_deg", s.heading_max_deg);
    v("heading_step_deg", s.heading_step_deg);
    v("fine_step_deg", s.fine_step_deg);
    v("line_tolerance", s.line_tolerance);
    v("min_trunks", s.min_trunks);
    v("min_row_length", s.min_row_length);
    v("min_pair_distance", s.min_pair_distance);
    v("require_crown", s.require_crown);
    v("crown_window", s.crown_window);
    v("min_crown_points", s.min_crown_points);
    v("crown_fallback", s.crown_fallback);
    v("crowns", s.crowns);
    v("lookahead", s.lookahead);
    v("planar_min_length_per_start", s.planar_min_length_per_start);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Trunk-line row detector fused with the crown faces (rownav, issue 10; after Lan 2021).
class TrunkLinesDetector : public RowDetector {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit TrunkLinesDetector(const TrunkLinesConfig& config = {});
  std::string_view name() const override { return "trunk_lines"; }
  core::RowObservation detect(const DetectorInput& input) override;
  const TrunkLinesConfig& config() const { return config_; }

 private:
  /// Rows through `trunks` (none when they give no line); obs.heading set when any.
  void trunk_rows(const std::vector<TrunkCentre>& trunks, const DetectorInput& input,
                  core::RowObservation& obs);
  /// The crown detector's rows when there is no trunk row.
  void add_crown_rows(const DetectorInput& input, core::RowObservation& obs);

  TrunkLinesConfig config_;
  TrunkCentres finder_;
  HoughSkewDetector crowns_;
};

}  // namespace rownav::detect
