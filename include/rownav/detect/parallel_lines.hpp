#pragma once
/// @file parallel_lines.hpp The corridor as two parallel lines y = a x + b_l and y = a x + b_r
/// (Lan 2022, 001_b5f4b55a1b95775a.txt sec. 3.3, eq. (23)): RANSAC over two-line hypotheses, then
/// least squares on the joint residual, plus the nearest trunk centre on each side (Fig. 1,
/// X_l and X_r) from the 3D cloud.
///
/// By design of the paper only the two corridor rows are reported. rownav additions: hypotheses
/// must straddle the robot and their score subtracts the points lying between the two lines, so
/// that a pair skipping a row (or two rows of the same side) never wins.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/nearest_row.hpp"
#include "rownav/detect/row_detector.hpp"
#include "rownav/detect/trunk_offset.hpp"

namespace rownav::detect {

/// Parameters of ParallelLinesDetector.
struct ParallelLinesConfig {
  int iterations = 500;           ///< [-] RANSAC hypotheses (rownav; the paper gives none)
  double inlier_distance = 0.2;   ///< [m] perpendicular distance to a line for an inlier
  std::uint64_t seed = 1;         ///< RANSAC random seed (same seed, same answer)
  int score_points = 400;         ///< [-] hypotheses are scored on at most this many points
  double min_sample_dx = 1.0;     ///< [m] two points defining the slope are this far apart in x
  double max_heading_deg = 30.0;  ///< [deg] steeper hypotheses are rejected
  double min_width = 0.4;         ///< [m] smallest corridor width b_l - b_r (at x = 0)
  double max_width = 4.0;         ///< [m] largest corridor width
  double between_penalty = 1.0;   ///< [-] score = inliers - penalty x points between the lines
  /// [-] a side moves to a parallel line farther out with this x more support (weed strips in
  /// the corridor; rownav); 0 = off
  double step_out_ratio = 2.0;
  int refine_iterations = 3;      ///< [-] inlier re-selection + joint least squares passes
  /// [-] a side's inlier density (per metre across) must exceed this x the density between the
  /// lines; a uniform open field gives ~1 (rownav guard).
  double min_contrast = 2.0;
  int min_inliers = 8;            ///< [-] fewer inliers on a side: that side is not reported
  double min_row_length = 0.5;    ///< [m] support shorter along x: the side is not reported
  bool detect_trunks = true;      ///< find the nearest trunk on each side (Lan 2022 Fig. 1)
  double trunk_z_min = 0.1;  ///< [m] trunk band above the ground (flat ground, base z = 0)
  /// [m] top of the trunk band: below the lowest cordon / wire (vineyards: 0.3 m and up), where
  /// only trunks and posts stand (Lan 2022 keeps trunks out of its 0.5 m line-fitting cut)
  double trunk_z_max = 0.3;
  double trunk_cluster_radius = 0.15;   ///< [m] points closer than this join one cluster
  int trunk_min_points = 3;             ///< [-] smaller clusters are ignored
  double trunk_max_size = 0.3;          ///< [m] larger clusters (bounding-box diagonal) are not trunks
  double trunk_max_line_distance = 0.4; ///< [m] a trunk lies this close to its row line
  double trunk_max_range = 5.0;         ///< [m] trunks farther from the robot are ignored
  /// Row offsets re-estimated from the trunk band behind the fitted canopy faces (3D cloud only)
  TrunkOffsetConfig trunk_offset;
  /// 2D scans: a row band between the robot and a fitted line replaces it (issue 11)
  NearestRowConfig nearest_row;

  /// Defaults: vineyards / orchards (rows 1.5-3 m apart). Row crop preset (maize, corn; rows
  /// 0.7-0.8 m apart, 2D scanner): chosen for the crop type, not for one data set; validated on
  /// corn_rows_2d (tests/detect/parallel_lines_test.cpp).
  static ParallelLinesConfig row_crop() {
    ParallelLinesConfig c;
    c.inlier_distance = 0.1;
    c.min_width = 0.3;
    c.max_width = 1.5;
    c.min_sample_dx = 0.5;
    c.min_row_length = 0.3;
    c.min_contrast = 1.2;  // leaves reach into narrow corridors: less empty space between rows
    c.trunk_offset.enabled = false;  // no trunk band: maize stems and leaves mix at every height
    c.nearest_row.enabled = false;   // leaves cross the corridors: corn_rows_2d got worse (issue 11)
    return c;
  }

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("iterations", s.iterations);
    v("inlier_distance", s.inlier_distance);
    v("seed", s.seed);
    v("score_points", s.score_points);
    v("min_sample_dx", s.min_sample_dx);
    v("max_heading_deg", s.max_heading_deg);
    v("min_width", s.min_width);
    v("max_width", s.max_width);
    v("between_penalty", s.between_penalty);
    v("step_out_ratio", s.step_out_ratio);
    v("refine_iterations", s.refine_iterations);
    v("min_contrast", s.min_contrast);
    v("min_inliers", s.min_inliers);
    v("min_row_length", s.min_row_length);
    v("detect_trunks", s.detect_trunks);
    v("trunk_z_min", s.trunk_z_min);
    v("trunk_z_max", s.trunk_z_max);
    v("trunk_cluster_radius", s.trunk_cluster_radius);
    v("trunk_min_points", s.trunk_min_points);
    v("trunk_max_size", s.trunk_max_size);
    v("trunk_max_line_distance", s.trunk_max_line_distance);
    v("trunk_max_range", s.trunk_max_range);
    v("trunk_offset", s.trunk_offset);
    v("nearest_row", s.nearest_row);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Centre of the nearest trunk on one side (Lan 2022 Fig. 1: X_l, X_r), base frame.
struct TrunkObservation {
  bool found = false;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< [m]
};

/// Two-parallel-line RANSAC + joint least squares corridor detector (Lan 2022 sec. 3.3).
class ParallelLinesDetector : public RowDetector {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit ParallelLinesDetector(const ParallelLinesConfig& config = {});
  std::string_view name() const override { return "parallel_lines"; }
  core::RowObservation detect(const DetectorInput& input) override;
  /// Nearest trunk of the last frame: [0] left, [1] right (found = false without a 3D cloud).
  const std::array<TrunkObservation, 2>& last_trunks() const { return trunks_; }
  const ParallelLinesConfig& config() const { return config_; }

 private:
  struct Model {
    double a = 0.0, bl = 0.0, br = 0.0;
  };
  /// RANSAC over two-line hypotheses; false when none is valid.
  bool ransac(Model& best);
  /// Score of a hypothesis on the scoring subset.
  double score(const Model& m) const;
  /// Joint least squares of (a, b_l, b_r) on the inliers, repeated (Lan 2022 eq. (23)).
  void refine(Model& m);
  /// Moves a side outwards to a much better supported parallel line (rownav); true if moved.
  bool step_out(Model& m);
  void find_trunks(const core::PointCloud& cloud, const Model& m, bool has_l, bool has_r);

  ParallelLinesConfig config_;
  TrunkOffset offsets_;
  std::array<TrunkObservation, 2> trunks_{};
  // Per-frame buffers, reused.
  std::vector<Eigen::Vector2f> pts_, scoring_, left_, right_;
  std::vector<Eigen::Vector2f> band_;
  std::vector<int> label_;
  std::vector<double> residuals_;
};

}  // namespace rownav::detect
