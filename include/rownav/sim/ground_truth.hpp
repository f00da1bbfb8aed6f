#pragma once
/// @file ground_truth.hpp What the simulator knows at every step and a robot does not.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::sim {

/// Semantic place of the robot (Emmi 2021, 002_806e72d300173f73.txt eq. (1)).
enum class Place : std::uint8_t { headland, lane, alley, outside };

/// A row as seen from the robot: its local tangent line in the base frame and its ends.
struct RowTruth {
  int row = -1;               ///< index in Field::rows
  core::Line2 line_base;      ///< tangent at the robot's abscissa, base frame, oriented forward
  double lateral = 0.0;       ///< [m] signed distance of the base origin's projection (y, left +)
  Eigen::Vector2d start_base = Eigen::Vector2d::Zero();  ///< [m] first plant / post, base frame
  Eigen::Vector2d end_base = Eigen::Vector2d::Zero();    ///< [m] last plant / post, base frame
};

/// Ground truth at one instant.
struct GroundTruth {
  double stamp = 0.0;  ///< [s]
  core::Pose2 T_world_base;  ///< true planar pose
  double z = 0.0;            ///< [m] base height on the terrain
  double roll = 0.0;         ///< [rad] from the terrain normal
  double pitch = 0.0;        ///< [rad]
  core::Twist2 twist;        ///< true body velocity
  Place place = Place::outside;
  int block = -1;     ///< block of the nearest rows
  int corridor = -1;  ///< lane index k (between rows k and k+1) when place == lane, else -1
  int left_row = -1;  ///< nearest row on the left (index in Field::rows), -1 if none
  int right_row = -1; ///< nearest row on the right
  /// Corridor centre line in the base frame, oriented along the robot's heading; present in a
  /// lane and in the headland next to one.
  std::optional<core::Line2> corridor_centre_base;
  double lateral_error = 0.0;  ///< [m] signed offset of the base from the corridor centre (left +)
  double heading_error = 0.0;  ///< [rad] robot heading minus the corridor heading
  std::vector<RowTruth> rows;  ///< rows within the LiDAR's reach, nearest first
  int plants_crushed = 0;      ///< cumulative count of plants the footprint has run over
  /// [m] from the footprint to the walking person of the faults (sim/faults.hpp); 0: contact
  /// (a collision), infinity: no person
  double obstacle_clearance = std::numeric_limits<double>::infinity();
};

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::Place> {
  using E = rownav::sim::Place;
  static constexpr std::array<std::pair<E, std::string_view>, 4> values{
      {{E::headland, "headland"}, {E::lane, "lane"}, {E::alley, "alley"}, {E::outside, "outside"}}};
};
