#pragma once
/// @file row_end_poles.hpp Row ends ("poles") from the points around the robot, and the point
/// the robot aims at from them (003_25dc0df51a1e5faf.txt sec. II-C).
///
/// CONTRACT (signatures) shared by navigate/ and the closed-loop runner. Points near the row ends
/// are Euclidean-clustered; each cluster is a pole candidate; the row ends are chosen by the
/// Nearest policy or the Line-fitting policy (RANSAC, 100 iterations, 0.1 m threshold).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"

namespace rownav::navigate {

/// Where each cluster's row end (its end point) is taken (003 sec. II-C).
enum class RowEndPolicy : std::uint8_t {
  /// 003's Nearest: the cluster's point nearest the robot with nearest_min_neighbours points
  /// within nearest_radius (the row end's face towards the robot)
  nearest,
  /// 003's Line fitting: that point projected onto a RANSAC line fitted to the cluster (onto the
  /// row's axis for a row end seen from the headland)
  line_fitting,
  /// rownav: the centroid of the cluster's end slice (end_slice deep along the rows, at its
  /// extreme nearest the robot): the middle of the row end across the row
  end_slice
};

/// Configuration of the row-end estimator (the implementation owns and may extend the fields).
struct RowEndConfig {
  /// Each cluster's end point (003 sec. II-C; end_slice: rownav, the row ends every earlier
  /// release used). All but nearest also keep only the clusters on one line across the rows as
  /// the followed rows' ends (left_end / right_end)
  RowEndPolicy policy = RowEndPolicy::end_slice;
  double cluster_tolerance = 0.3;  ///< [m] Euclidean clustering distance
  int min_cluster_points = 3;      ///< [points] smaller clusters are ignored
  int ransac_iterations = 100;     ///< [-] 003 sec. II-C
  double ransac_threshold = 0.1;   ///< [m] 003 sec. II-C
  std::uint64_t seed = 1;          ///< RANSAC seed
  /// [m] depth of a cluster's end slice (along the rows, at its extreme nearest the robot) whose
  /// centroid is the pole candidate (rownav: a row seen from its end is one long cluster)
  double end_slice = 0.1;
  /// [deg] the end line may deviate this much from perpendicular to the rows
  double max_line_angle_deg = 30.0;
  /// [m] Nearest policy: the neighbourhood radius around a candidate end point. 003 names the
  /// parameter without a value: about three returns of a post 2 m away on a 1024-column scan
  double nearest_radius = 0.1;
  /// [-] Nearest policy: cluster points a candidate needs within nearest_radius (003: configured;
  /// 2 rejects a lone return touching the cluster)
  int nearest_min_neighbours = 2;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("policy", s.policy);
    v("cluster_tolerance", s.cluster_tolerance);
    v("min_cluster_points", s.min_cluster_points);
    v("ransac_iterations", s.ransac_iterations);
    v("ransac_threshold", s.ransac_threshold);
    v("seed", s.seed);
    v("end_slice", s.end_slice);
    v("max_line_angle_deg", s.max_line_angle_deg);
    v("nearest_radius", s.nearest_radius);
    v("nearest_min_neighbours", s.nearest_min_neighbours);
  }
  void validate() const;
};

/// Row ends seen in one frame, base frame.
struct RowEnds {
  /// every pole candidate: centroid of a cluster's end slice (a lone pole: its centroid)
  std::vector<Eigen::Vector2d> poles;
  std::optional<Eigen::Vector2d> left_end;   ///< end of the row on the left of the corridor
  std::optional<Eigen::Vector2d> right_end;  ///< end of the row on the right
  /// Line through the row ends of the block (line_fitting policy), oriented left to right
  /// across the rows; the headland navigation runs parallel to it.
  std::optional<core::Line2> end_line;
};

/// Estimates row ends from 2D points in the base frame. `row_heading` [rad] is the rows'
/// direction in the base frame (from the tracker), `spacing` [m] their spacing (0: unknown).
/// Never throws.
RowEnds estimate_row_ends(std::span<const Eigen::Vector2f> points_base, double row_heading,
                          double spacing, const RowEndConfig& config);

}  // namespace rownav::navigate

template <>
struct rownav::core::EnumNames<rownav::navigate::RowEndPolicy> {
  using E = rownav::navigate::RowEndPolicy;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::nearest, "nearest"}, {E::line_fitting, "line_fitting"}, {E::end_slice, "end_slice"}}};
};
