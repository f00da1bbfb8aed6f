#pragma once
/// @file key_location.hpp Key locations: lane ends projected from the row clusters, left / right
/// fused into middle, and the validity rules (Emmi 2021, 002_806e72d300173f73.txt, sec. "Row
/// identification and key location estimation", eq. (2)-(3), Fig. 3).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/map/labelled_clusters.hpp"

namespace rownav::map {

/// Entry (estimated from the headland: nearest plants) or exit (from a lane / alley: furthest).
enum class KeyType : std::uint8_t { entry, exit };
/// Side of the robot the key location was estimated from; middle = left and right fused.
enum class KeySide : std::uint8_t { left, right, middle };

/// A key location Kloc_t^s(p, v) (Emmi 2021 sec. "The field model").
struct KeyLocation {
  KeyType type = KeyType::exit;
  KeySide side = KeySide::middle;
  Eigen::Vector2d p = Eigen::Vector2d::Zero();  ///< [m] lane centre at the row end, frame of use
  Eigen::Vector2d v = Eigen::Vector2d::UnitX();  ///< unit row direction, along the robot heading
  double half_width = 0.0;  ///< [m] d used for the projection (half the lane width)
};

/// Configuration of key location estimation and validation.
struct KeyLocationConfig {
  /// [m] a priori lane width; d starts at half of it and is reset to it at every transition
  /// (Emmi 2021: "distance d is first defined by the user")
  double lane_width = 1.0;
  double min_width_ratio = 0.6;  ///< [-] d updated from the centroids stays >= ratio * a priori
  double max_width_ratio = 1.6;  ///< [-] ... and <= ratio * a priori (rownav guard)
  /// [-] rows farther from the robot's line than ratio * lane width are not its left / right rows
  double max_lateral_ratio = 1.0;
  double side_max_angle_deg = 30.0;  ///< [deg] rows more oblique than this are not beside the robot
  double max_distance = 6.0;  ///< [m] rule (ii): farther than the headland length is invalid
  double max_orientation_deg = 10.0;  ///< [deg] rules (iii)-(iv): orientation gate (Emmi 2021)
  double max_alignment = 0.4;         ///< [m] rules (iii)-(iv): alignment gate (Emmi 2021)
  /// [m] a new key location this close to the previous valid one of its type is the same one
  /// and must agree with it in orientation and alignment, rule (iii) (rownav)
  double same_radius = 1.0;
  /// [m] left and right farther apart than this are not fused; one is dropped (Emmi 2021: "half
  /// the distance of the field of view")
  double max_side_separation = 2.0;
  /// apply rule (iv) (aligned with the robot) to entry key locations too; the paper applies it
  /// to exits only (rownav: keeps a headland turn's oblique views out of the entries)
  bool gate_entry_by_robot = true;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("lane_width", s.lane_width);
    v("min_width_ratio", s.min_width_ratio);
    v("max_width_ratio", s.max_width_ratio);
    v("max_lateral_ratio", s.max_lateral_ratio);
    v("side_max_angle_deg", s.side_max_angle_deg);
    v("max_distance", s.max_distance);
    v("max_orientation_deg", s.max_orientation_deg);
    v("max_alignment", s.max_alignment);
    v("same_radius", s.same_radius);
    v("max_side_separation", s.max_side_separation);
    v("gate_entry_by_robot", s.gate_entry_by_robot);
  }
  void validate() const;
};

/// The nearest row on each side of the robot (rows roughly parallel to its heading).
struct SideRows {
  const RowCluster* left = nullptr;
  const RowCluster* right = nullptr;
  double left_lateral = 0.0;   ///< [m] distance from the robot's line to the left row (> 0)
  double right_lateral = 0.0;  ///< [m] to the right row (> 0)
};

/// [m] signed distance (left +) of a row's line from the robot; nullopt when the row is more
/// oblique than side_max_angle_deg or farther than max_lateral_ratio * 2 d.
std::optional<double> side_lateral(const RowCluster& row, const core::Pose2& T_local_base,
                                   double half_width, const KeyLocationConfig& config);

/// Finds the robot's left and right rows (nearest within max_lateral_ratio * 2 d).
SideRows find_side_rows(const std::vector<RowCluster>& rows, const core::Pose2& T_local_base,
                        double half_width, const KeyLocationConfig& config);

/// Why a candidate key location was rejected (or `valid`).
/// `beyond_entry`: an entry further into the lane of the last valid entry (a lane has one
/// start; a part of a row seen ahead is not it).
enum class KeyVerdict : std::uint8_t {
  valid,
  behind,
  too_far,
  misoriented,
  misaligned,
  jump,
  beyond_entry
};

/// Key location estimation over frames, in F_l. Stateful (d, the last valid key locations);
/// never throws after construction.
class KeyLocator {
 public:
  explicit KeyLocator(const KeyLocationConfig& config = {});
  /// One frame: candidates of both types from the rows (Fig. 3), d updated, validity rules
  /// applied; returns the candidates that became valid this frame (middle preferred).
  std::vector<KeyLocation> update(const std::vector<RowCluster>& rows,
                                  const core::Pose2& T_local_base);
  /// Validity rules (i)-(iv) of a candidate against the robot and the last valid one.
  KeyVerdict check(const KeyLocation& k, const core::Pose2& T_local_base) const;
  /// Last valid key location of a type, F_l (none after reset()).
  const std::optional<KeyLocation>& last(KeyType t) const {
    return last_[static_cast<std::size_t>(t)];
  }
  double half_width() const { return d_; }
  /// Replaces the a priori lane width (e.g. by a measured row spacing): d is scaled by the
  /// ratio and kept within the new bounds. False (nothing changed) unless finite and > 0.
  bool set_lane_width(double lane_width);
  /// New local frame: forget the valid key locations, d back to the a priori value.
  void reset();
  const KeyLocationConfig& config() const { return config_; }

 private:
  void update_width(const SideRows& sides, const core::Pose2& T);

  KeyLocationConfig config_;
  double d_ = 0.5;
  std::array<std::optional<KeyLocation>, 2> last_;
};

}  // namespace rownav::map

template <>
struct rownav::core::EnumNames<rownav::map::KeyType> {
  using E = rownav::map::KeyType;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::entry, "entry"}, {E::exit, "exit"}}};
};

template <>
struct rownav::core::EnumNames<rownav::map::KeySide> {
  using E = rownav::map::KeySide;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::left, "left"}, {E::right, "right"}, {E::middle, "middle"}}};
};
