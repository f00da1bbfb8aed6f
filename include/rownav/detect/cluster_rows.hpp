#pragma once
/// @file cluster_rows.hpp Row detection by density clustering, per-cluster line regression and
/// merging of the clusters of one row (Emmi 2021, 002_806e72d300173f73.txt, "Perception system:
/// data acquisition, labeling and clustering": DBSCAN isolates each row or part of a row, a
/// linear regression per cluster decides whether two clusters belong to the same row, and those
/// are merged). Any number of rows, no assumed row spacing.
#include <string_view>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/dbscan.hpp"
#include "rownav/detect/nearest_row.hpp"
#include "rownav/detect/row_detector.hpp"

namespace rownav::detect {

/// Parameters of ClusterRowsDetector. The defaults suit vineyards (rows 1.5-3 m apart, canopy
/// 0.3-0.6 m wide) on 2D points after a 0.15 m voxel grid; row_crop() and orchard() give the
/// documented presets of the other crop types.
struct ClusterRowsConfig {
  /// [m] DBSCAN neighbourhood radius (Emmi 2021 uses DBSCAN after Schubert 2017, no value given).
  /// Below half the free space between rows, above the along-row point spacing.
  double eps = 0.35;
  /// [-] DBSCAN: neighbours within eps (the point included) that make a core point.
  int min_pts = 4;
  NeighbourSearch neighbour_search = NeighbourSearch::grid;  ///< neighbour search structure
  /// [-] clusters with fewer points are noise (not regressed).
  int min_cluster_points = 5;
  /// [m] a cluster is a row seed (its regression trusted for merging) when its extent along its
  /// principal axis is at least this.
  double min_seed_length = 0.8;
  /// [-] and sqrt(minor / major covariance eigenvalue) at most this ("too round" otherwise).
  double max_seed_roundness = 0.4;
  /// [deg] two clusters lie on one row when their regression lines differ by at most this
  /// (Emmi 2021 merges clusters of one row split by gaps; threshold ours).
  double merge_angle_deg = 8.0;
  /// [m] and each centroid lies within this of the other's line (about half the canopy width).
  double merge_offset = 0.25;
  /// [m] a merged row is kept when its points span at least this along the row.
  double min_row_length = 1.5;
  /// [-] and sqrt(minor / major eigenvalue) of its points is at most this.
  double max_row_roundness = 0.3;
  /// [deg] rows more than this from the robot's x axis are not rows to follow (walls ahead,
  /// headland borders): rejected.
  double max_row_angle_deg = 50.0;
  /// [m] x at which rows are sorted and the corridor rows picked (finalize_observation).
  double lookahead = 0.0;
  /// 2D scans: a row band between the robot and a corridor row becomes that side's row (issue 11)
  NearestRowConfig nearest_row;

  /// Row crops (maize, corn; rows 0.5-0.9 m apart, narrow plants): smaller eps so that the
  /// ~0.3-0.4 m between rows separates them; shorter seeds. Used for corn_rows_2d.
  static ClusterRowsConfig row_crop();
  /// Orchards (trees 3.5-6 m apart in rows 3.5-6 m apart): eps spans the gaps between crowns.
  static ClusterRowsConfig orchard();

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("eps", s.eps);
    v("min_pts", s.min_pts);
    v("neighbour_search", s.neighbour_search);
    v("min_cluster_points", s.min_cluster_points);
    v("min_seed_length", s.min_seed_length);
    v("max_seed_roundness", s.max_seed_roundness);
    v("merge_angle_deg", s.merge_angle_deg);
    v("merge_offset", s.merge_offset);
    v("min_row_length", s.min_row_length);
    v("max_row_roundness", s.max_row_roundness);
    v("max_row_angle_deg", s.max_row_angle_deg);
    v("lookahead", s.lookahead);
    v("nearest_row", s.nearest_row);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// DBSCAN -> regression per cluster -> merge clusters on one line -> reject non-row shapes.
class ClusterRowsDetector : public RowDetector {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit ClusterRowsDetector(const ClusterRowsConfig& config = {});
  std::string_view name() const override { return "cluster_rows"; }
  /// Rows sorted right to left, corridor between the nearest ones; never throws.
  core::RowObservation detect(const DetectorInput& input) override;
  const ClusterRowsConfig& config() const { return config_; }

 private:
  ClusterRowsConfig config_;
  Dbscan dbscan_;
};

}  // namespace rownav::detect
