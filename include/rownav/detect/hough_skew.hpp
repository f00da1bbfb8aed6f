#pragma once
/// @file hough_skew.hpp Row detection by a Hough transform searched with iterative skewing
/// (Nehme 2021, 000_0dc267f189bd9473.txt sec. 3.2): the heading is the Hough column of maximum
/// variance, the rows are the mean-threshold segments of that column.
///
/// rownav refinements over the paper (each behind a flag, on by default): a coarse-to-fine heading
/// search, and a joint total-least-squares fit of parallel lines to the points around each
/// segment, which removes the 8 cm bin and the 1 deg heading discretisation.
///
/// Presets: the defaults are the paper's vineyard settings (y in [-4, 4] m, 100 bins). For row
/// crops (maize / corn, rows ~0.75 m apart) use `HoughSkewConfig::row_crop()`: y in [-1.2, 1.2] m,
/// 60 bins (4 cm), narrower bands; tested on the real corn data (corn_rows_2d).
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/nearest_row.hpp"
#include "rownav/detect/row_detector.hpp"
#include "rownav/detect/trunk_offset.hpp"

namespace rownav::detect {

/// Parameters of HoughSkewDetector. Defaults: vineyard (Nehme 2021 sec. 4).
struct HoughSkewConfig {
  double heading_min_deg = -20.0;  ///< [deg] smallest heading searched (Nehme 2021 Fig. 6)
  double heading_max_deg = 20.0;   ///< [deg] largest heading searched (Nehme 2021 Fig. 6)
  double heading_step_deg = 1.0;   ///< [deg] Hough column spacing of the (coarse) search (rownav)
  bool refine_heading = true;      ///< rownav: second pass around the best column
  double fine_step_deg = 0.1;      ///< [deg] column spacing of the fine pass, +- one coarse step
  double y_min = -4.0;             ///< [m] y_rot range of the accumulator (Nehme 2021 sec. 4)
  double y_max = 4.0;              ///< [m]
  int bins = 100;                  ///< [-] y_rot bins over [y_min, y_max] (Nehme 2021 sec. 4)
  bool use_cloud = true;           ///< vote with the 3D cloud's x, y when given (Nehme 2021)
  int min_points = 10;             ///< [-] fewer valid points: no_rows
  /// [-] the heading search votes with at most this many points (even stride); segmentation and
  /// fit use all (rownav: bounds the cost of dense clouds)
  int max_vote_points = 4000;
  /// [-] best column variance / mean must exceed this (a uniform, row-less field gives ~1 with
  /// count histograms, Poisson); rownav guard against open fields.
  double min_dispersion = 3.0;
  int min_segment_bins = 2;        ///< [-] narrower segments are noise (rownav)
  int min_segment_points = 8;      ///< [-] fewer votes in a segment: rejected (rownav)
  double max_segment_width = 1.5;  ///< [m] wider segments are not one row (walls, merged rows)
  bool split_segments = true;      ///< rownav: cut segments at deep valleys (rows joined by weeds)
  double valley_ratio = 0.5;       ///< [-] a valley below this x the lower neighbouring peak cuts
  /// [-] segments with fewer votes than this x the strongest segment's are dropped (weed strips
  /// between rows; far, sparsely hit rows) (rownav)
  double min_relative_support = 0.2;
  /// [-] a segment's mean votes per bin must exceed this x the lower quartile of the occupied
  /// bins (the background between rows); a uniform open field gives ~1.3 (rownav)
  double min_contrast = 2.5;
  bool refine_rows = true;         ///< rownav: joint TLS fit of parallel lines to the bands
  /// [m] half width of the band of points around a segment's position used by the fit; also
  /// capped at 0.45 x the distance to the neighbouring segment (keeps weeds out).
  double band_half_width = 0.35;
  int refine_iterations = 3;       ///< [-] re-banding + fit passes
  double trim_sigma = 2.0;         ///< [-] drop points beyond this many rms from their line, refit
  bool common_heading = true;      ///< true: rows share one direction; false: one TLS line each
  double min_row_length = 0.5;     ///< [m] rows whose support spans less along x are dropped
  /// [m] rows whose band points spread more (RMS across the line) are dropped: a 0.5 m vine canopy
  /// gives ~0.15 m, a weed strip filling the band ~0.2 m (rownav)
  double max_row_rms = 0.17;
  /// rownav: row offsets re-estimated from the trunk band behind the canopy faces (3D cloud only;
  /// the canopy fit alone puts vineyard rows up to a canopy half width too close to the robot)
  TrunkOffsetConfig trunk_offset;
  /// 2D scans: a row band between the robot and a corridor row becomes that side's row (issue 11)
  NearestRowConfig nearest_row;

  /// Row crop preset (maize, corn; rows 0.7-0.8 m apart, 2D scanner): chosen for the crop type,
  /// not for one data set. Validated on corn_rows_2d (see tests/detect/hough_skew_test.cpp).
  static HoughSkewConfig row_crop() {
    HoughSkewConfig c;
    c.y_min = -1.2;
    c.y_max = 1.2;
    c.bins = 60;
    c.min_segment_points = 4;
    c.max_segment_width = 0.6;
    c.band_half_width = 0.2;
    c.min_row_length = 0.3;
    c.trunk_offset.enabled = false;  // no trunk band: maize stems and leaves mix at every height
    c.nearest_row.enabled = false;   // leaves cross the corridors: corn_rows_2d got worse (issue 11)
    return c;
  }

  /// Crown faces of free-standing trees (orchards: rows 3-7 m apart, crowns 1-4 m wide), the
  /// fallback of detect::TrunkLinesDetector: a wide window, wide segments, and a row RMS that
  /// an irregular crown face passes (vine 0.17 m dropped 61 % of crown rows, issue 10).
  static HoughSkewConfig crowns() {
    HoughSkewConfig c;
    c.y_min = -8.0;
    c.y_max = 8.0;
    c.bins = 160;
    c.max_segment_width = 3.0;
    c.band_half_width = 0.6;
    c.max_row_rms = 0.5;
    c.trunk_offset.enabled = false;  // the trunk lines are TrunkLinesDetector's own
    return c;
  }

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("heading_min_deg", s.heading_min_deg);
    v("heading_max_deg", s.heading_max_deg);
    v("heading_step_deg", s.heading_step_deg);
    v("refine_heading", s.refine_heading);
    v("fine_step_deg", s.fine_step_deg);
    v("y_min", s.y_min);
    v("y_max", s.y_max);
    v("bins", s.bins);
    v("use_cloud", s.use_cloud);
    v("min_points", s.min_points);
    v("max_vote_points", s.max_vote_points);
    v("min_dispersion", s.min_dispersion);
    v("min_segment_bins", s.min_segment_bins);
    v("min_segment_points", s.min_segment_points);
    v("max_segment_width", s.max_segment_width);
    v("split_segments", s.split_segments);
    v("valley_ratio", s.valley_ratio);
    v("min_relative_support", s.min_relative_support);
    v("min_contrast", s.min_contrast);
    v("refine_rows", s.refine_rows);
    v("band_half_width", s.band_half_width);
    v("refine_iterations", s.refine_iterations);
    v("trim_sigma", s.trim_sigma);
    v("common_heading", s.common_heading);
    v("min_row_length", s.min_row_length);
    v("max_row_rms", s.max_row_rms);
    v("trunk_offset", s.trunk_offset);
    v("nearest_row", s.nearest_row);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Hough / iterative-skewing row detector (Nehme 2021 sec. 3.2) with rownav refinements.
class HoughSkewDetector : public RowDetector {
 public:
  /// Validates the config (throws std::invalid_argument) and precomputes the sin / cos tables.
  explicit HoughSkewDetector(const HoughSkewConfig& config = {});
  std::string_view name() const override { return "hough_skew"; }
  core::RowObservation detect(const DetectorInput& input) override;
  const HoughSkewConfig& config() const { return config_; }

 private:
  /// Row position estimate from a histogram segment, before refinement.
  struct Segment {
    double position = 0.0;  ///< [m] count-weighted mean y_rot
    double lo = 0.0, hi = 0.0;  ///< [m] y_rot extent of the segment's bins
    int votes = 0;
  };
  /// y_rot histogram of pts at heading angle gamma (sin, cos given) into hist_; returns variance.
  double column(const std::vector<Eigen::Vector2f>& pts, double s, double c);
  /// Coarse (and fine) search; returns gamma of the maximum-variance column, hist_ filled there.
  double best_gamma(double& variance);
  /// Mean-threshold segmentation of hist_ (Nehme 2021 sec. 3.2.3) with rownav rejections.
  void segment();
  /// Cuts the run [from, to) of bins at deep valleys, recursively (rownav).
  void split(int from, int to, int depth);
  /// Adds the bins [from, to) as a segment when it passes the support / width checks.
  void accept(int from, int to);
  /// Lower quartile of hist_ between its first and last occupied bins.
  double lower_quartile();
  /// Joint parallel-line fit of the points around each segment (rownav), then the trunk-line
  /// offsets from `cloud` when given; fills obs rows.
  void fit_rows(double gamma, const core::PointCloud* cloud, core::RowObservation& obs);

  HoughSkewConfig config_;
  TrunkOffset trunks_;
  std::vector<double> coarse_gamma_, coarse_sin_, coarse_cos_;  // precomputed tables
  // Per-frame buffers, reused.
  std::vector<Eigen::Vector2f> pts_, subset_;
  std::vector<int> hist_, quartile_;
  std::vector<Segment> segments_;
  double threshold_ = 0.0;  // column mean of the current histogram
  std::vector<std::vector<Eigen::Vector2f>> bands_;
};

}  // namespace rownav::detect
