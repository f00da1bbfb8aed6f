#pragma once
/// @file labelled_clusters.hpp Crop rows from labelled laser points accumulated in the local
/// frame F_l: DBSCAN, a line per cluster, clusters on one line merged (Emmi 2021,
/// 002_806e72d300173f73.txt, sec. "Perception").
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/detect/dbscan.hpp"
#include "rownav/map/point_labeller.hpp"

namespace rownav::map {

/// Configuration of the row clustering.
struct LabelledClustersConfig {
  double eps = 0.35;  ///< [m] DBSCAN radius (Emmi 2021 sec. "Perception": DBSCAN; rownav value)
  int min_pts = 3;    ///< [points] DBSCAN core threshold, the point itself included
  /// [m] accumulation grid: one stored point per cell, bounding memory over a long lane (rownav)
  double cell_size = 0.05;
  /// [m] stored points farther than this behind the robot are discarded (Emmi 2021: "laser
  /// points that are far behind the robot are also discarded to reduce the drift")
  double keep_behind = 3.0;
  double max_range = 12.0;  ///< [m] points farther from the robot are not stored (rownav)
  /// [deg] stored points are forgotten once the robot has turned this far since it saw them:
  /// odometry drifts most in rotation, and the row ends seen through a headland turn, stored
  /// in F_l, landed between the next corridor's rows (issue 12, zoo:1:10: the entry read as an
  /// alley; rownav, in the spirit of Emmi 2021's "points far behind are discarded")
  double keep_turn_deg = 45.0;
  int min_cluster_points = 4;    ///< [points] smaller clusters give no row line (rownav)
  double merge_angle_deg = 8.0;  ///< [deg] two cluster lines closer in angle may be one row
  double merge_offset = 0.15;    ///< [m] ... if each centroid is this close to the other line
  /// [m] ... and the gap between them along the line is at most this (Emmi 2021: "gaps can be
  /// found", a cluster is "a single crop row, or part of a row")
  double merge_gap = 2.5;
  /// [m] a cluster shorter than this (one plant: its line's direction means nothing) joins a
  /// longer row on the offset and gap tests alone (rownav)
  double short_length = 0.6;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("eps", s.eps);
    v("min_pts", s.min_pts);
    v("cell_size", s.cell_size);
    v("keep_behind", s.keep_behind);
    v("max_range", s.max_range);
    v("keep_turn_deg", s.keep_turn_deg);
    v("min_cluster_points", s.min_cluster_points);
    v("merge_angle_deg", s.merge_angle_deg);
    v("merge_offset", s.merge_offset);
    v("merge_gap", s.merge_gap);
    v("short_length", s.short_length);
  }
  void validate() const;
};

/// One crop row (or part of one) in F_l.
struct RowCluster {
  core::Line2 line;      ///< total-least-squares line, F_l, oriented towards +x of F_l
  double arc_min = 0.0;  ///< [m] extent of the support along `line` from line.point
  double arc_max = 0.0;  ///< [m]
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();  ///< [m] F_l
  int points = 0;                                      ///< support points
  int merged = 1;                                      ///< DBSCAN clusters joined into this row
};

/// Accumulates crop points in F_l and extracts the rows. Stateful; never throws after
/// construction (the constructor validates the config).
class LabelledClusters {
 public:
  explicit LabelledClusters(const LabelledClustersConfig& config = {});
  /// Stores the finite `crop` points of a frame (base frame, with T_local_base); other labels
  /// and NaN / Inf points are dropped. Returns the number of points stored.
  int add(const std::vector<Eigen::Vector3f>& points_base, const std::vector<PointLabel>& labels,
          const core::Pose2& T_local_base);
  /// Forgets the points behind / too far from the robot (or seen before it turned), clusters the
  /// rest and returns the rows.
  const std::vector<RowCluster>& update(const core::Pose2& T_local_base);
  /// Flushes every stored point (new local frame, Emmi 2021 sec. "The field model").
  void reset();
  const std::vector<RowCluster>& rows() const { return rows_; }
  std::size_t stored_points() const { return cells_.size(); }
  const LabelledClustersConfig& config() const { return config_; }

 private:
  void prune(const core::Pose2& T_local_base);
  void merge_rows(std::vector<std::vector<int>>& members);

  LabelledClustersConfig config_;
  /// One stored point per cell, with the robot heading [rad] when it was stored (keep_turn_deg).
  struct Stored {
    Eigen::Vector2f p;
    double heading = 0.0;
  };
  std::unordered_map<std::int64_t, Stored> cells_;
  std::vector<Eigen::Vector2f> points_;
  std::vector<RowCluster> rows_;
  detect::Dbscan dbscan_;
};

}  // namespace rownav::map
