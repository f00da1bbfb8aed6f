#pragma once
/// @file ransac_lines.hpp Sequential RANSAC line extraction (Fischler & Bolles 1981), the
/// baseline of Malavazi 2018 (sec. 3, "RANSAC-based method for model fitting as described in
/// [8]"): find the best line, remove its inliers, repeat.
#include <cstdint>
#include <string_view>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/nearest_row.hpp"
#include "rownav/detect/row_detector.hpp"

namespace rownav::detect {

/// Parameters of sequential RANSAC. One row-crop / vineyard configuration, used unchanged on
/// the synthetic scenes, the simulated vineyard and corn_rows_2d.
struct RansacLinesConfig {
  int iterations = 100;           ///< [-] hypotheses per extracted line
  double inlier_distance = 0.15;  ///< [m] |point-to-line| below which a point is an inlier
                                  ///< (about the canopy half width)
  int min_inliers = 12;           ///< [-] a line needs this many inliers; fewer ends the search
  int max_lines = 6;              ///< [-] lines extracted at most
  double sample_min = 0.25;       ///< [m] the two sample points are at least this far apart
  /// [deg] lines heading farther than this from the robot's x axis are rejected (their inliers
  /// are still removed); 90 disables the check (rownav).
  double max_row_heading_deg = 60.0;
  double lookahead = 0.5;  ///< [m] x at which the corridor rows are picked (finalize_observation)
  /// 2D scans: a row band between the robot and a corridor row becomes that side's row (issue 11)
  NearestRowConfig nearest_row;
  std::uint64_t seed = 1;  ///< same seed, same result

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("iterations", s.iterations);
    v("inlier_distance", s.inlier_distance);
    v("min_inliers", s.min_inliers);
    v("max_lines", s.max_lines);
    v("sample_min", s.sample_min);
    v("max_row_heading_deg", s.max_row_heading_deg);
    v("lookahead", s.lookahead);
    v("seed", s.seed);
    v("nearest_row", s.nearest_row);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Sequential RANSAC as a RowDetector; every accepted line (TLS re-fit on its inliers) is a row.
class RansacLinesDetector : public RowDetector {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit RansacLinesDetector(const RansacLinesConfig& config = {});
  std::string_view name() const override { return "ransac_lines"; }
  core::RowObservation detect(const DetectorInput& input) override;
  const RansacLinesConfig& config() const { return config_; }

 private:
  RansacLinesConfig config_;
  std::vector<Eigen::Vector2f> pts_;  // remaining points, reused
  std::vector<Eigen::Vector2f> inliers_;
};

}  // namespace rownav::detect
