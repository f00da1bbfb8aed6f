#pragma once
/// @file field_truth.hpp Ground truth of a field: place, corridor, rows in view, crushed plants.
///
/// Places follow Emmi 2021 (002_806e72d300173f73.txt, Fig. 1): a lane lies between two adjacent
/// rows of a block, an alley beside the outermost row of a block, the headland beyond the row
/// ends; everything else is outside.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

#include "rownav/core/pose2.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/ground_truth.hpp"

namespace rownav::sim {

/// Closest point of a polyline to a query point, with extended-end coordinates.
struct PolylineProjection {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();     ///< [m] closest point on the polyline
  Eigen::Vector2d tangent = Eigen::Vector2d::UnitX();  ///< unit direction there (start -> end)
  int segment = 0;                                     ///< index of the segment holding `point`
  double distance = 0.0;                               ///< [m] Euclidean distance to `point`
  /// [m] arc length of the projection; < 0 before the start, > length after the end (measured
  /// along the first / last segment extended).
  double along = 0.0;
  /// [m] signed distance to the polyline, left of its direction positive; beyond the ends it
  /// is measured from the first / last segment extended.
  double lateral = 0.0;
  double length = 0.0;  ///< [m] polyline length

  /// [m] how far beyond the start or end the projection lies (0 between the ends).
  double beyond() const { return along < 0.0 ? -along : std::max(0.0, along - length); }
  /// Foot of the query point `p` on the polyline, its ends extended.
  Eigen::Vector2d foot(const Eigen::Vector2d& p) const {
    return p - lateral * Eigen::Vector2d(-tangent.y(), tangent.x());
  }
};

/// Projects p on a polyline of >= 2 points (a single point gives distance only).
PolylineProjection project_on_polyline(const std::vector<Eigen::Vector2d>& line,
                                       const Eigen::Vector2d& p);

/// Ground truth queries on a field. Keeps a reference: `field` must outlive it.
class FieldTruth {
 public:
  /// Precomputes per-block row order, corridor centre polylines (midline of rows k and k+1,
  /// sampled every 0.25 m along row k) and row ends.
  explicit FieldTruth(const Field& field);

  /// Ground truth for a planar pose: place, block, corridor (lane only), nearest left / right
  /// rows, corridor centre line in the base frame (lane and the headland next to one, oriented
  /// along the robot's heading), lateral (left +) and heading error, rows within `reach` [m]
  /// nearest first. z / roll / pitch / twist / plants_crushed are left for the caller.
  GroundTruth at(const core::Pose2& T_world_base, double stamp, double reach = 10.0) const;

  /// Centre polyline of corridor k of a block (start -> end like row k); empty if none.
  const std::vector<Eigen::Vector2d>& corridor_centre(int block, int k) const;
  /// Number of corridors (rows - 1) of a block; 0 for an unknown block.
  int corridor_count(int block) const;
  /// Block ids present in the field, ascending.
  std::vector<int> blocks() const;
  /// Row indices of a block in lateral order.
  const std::vector<int>& block_rows(int block) const;
  const Field& field() const { return *field_; }

 private:
  struct Block {
    int id = 0;
    std::vector<int> rows;
    std::vector<std::vector<Eigen::Vector2d>> corridors;
  };
  const Block* find_block(int id) const;
  void fill_place(const Block& b, const core::Pose2& T, const std::vector<PolylineProjection>& proj,
                  GroundTruth& gt) const;
  void fill_rows(const core::Pose2& T, double reach, const std::vector<PolylineProjection>& proj,
                 GroundTruth& gt) const;

  const Field* field_;
  std::vector<Block> blocks_;
};

/// Counts plants (vine / tree / crop) whose footprint circle intersects the robot footprint
/// polygon; each plant is counted once per run. A uniform grid keeps queries local.
class CrushCounter {
 public:
  explicit CrushCounter(const Field& field);
  /// Adds the plants newly touched by the footprint (convex, world frame); returns how many.
  int update(const std::array<Eigen::Vector2d, 4>& footprint_world);
  int total() const { return static_cast<int>(crushed_.size()); }
  /// Indices into Field::plants, in the order they were crushed.
  const std::vector<int>& crushed_indices() const { return crushed_; }

 private:
  std::vector<Eigen::Vector2d> centres_;
  std::vector<double> radii_;
  std::vector<int> plant_index_;
  std::vector<bool> done_;
  std::vector<int> cell_start_, cell_items_;  // CSR grid over the plants' bounds
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0, max_radius_ = 0.0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> crushed_;
};

}  // namespace rownav::sim
