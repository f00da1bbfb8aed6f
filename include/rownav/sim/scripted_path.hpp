#pragma once
/// @file scripted_path.hpp The path a scripted simulated drive follows (the simulator's driver,
/// not the navigation stack): corridor centre lines joined by headland turns, and a pure-pursuit
/// follower on the true pose.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/robot.hpp"

namespace rownav::sim {

/// Headland turn manoeuvre.
/// u_turn: arcs of radius max(spacing / 2, min turn radius) (a semicircle between adjacent
/// lanes); falls back to bulb when the robot's min turn radius exceeds half the lateral offset.
/// in_place: stop, rotate 90 deg, drive across, rotate 90 deg (differential / skid-steer only).
/// bulb: omega-shaped turn for car-like robots whose min radius exceeds spacing / 2.
enum class TurnStyle : std::uint8_t { u_turn, in_place, bulb };

/// What the scripted drive does.
struct PathConfig {
  int block = 0;                           ///< block whose corridors are driven
  std::vector<int> corridors = {0, 1};     ///< lanes to drive in order (direction alternates)
  double speed = 1.0;                      ///< [m/s] in the lanes and lead-in / lead-out
  double turn_speed = 0.5;                 ///< [m/s] in headland turns
  double lead_in = 2.0;                    ///< [m] start before the first lane entry
  double lead_out = 1.5;                   ///< [m] straight past each exit before turning
  TurnStyle turn = TurnStyle::u_turn;      ///< headland turn manoeuvre
  std::vector<Eigen::Vector2d> waypoints;  ///< [m] world; when non-empty, corridors are ignored

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("block", s.block);
    v("corridors", s.corridors);
    v("speed", s.speed);
    v("turn_speed", s.turn_speed);
    v("lead_in", s.lead_in);
    v("lead_out", s.lead_out);
    v("turn", s.turn);
    v("waypoints", s.waypoints);
  }
  void validate() const;
};

/// One point of a dense path.
struct PathPoint {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();  ///< [m] world
  double speed = 0.0;   ///< [m/s] target speed; 0 marks a stop (rotate in place, or the end)
  bool in_row = false;  ///< on a corridor centre line between the row ends
};

/// Dense polyline (~0.05 m spacing) through the corridors' centre lines joined by headland turns
/// of the configured style, or through the explicit waypoints. Throws std::invalid_argument with
/// the reason ("corridors[2]: corridor 99 does not exist in block 0 (0..8)") when a corridor or
/// block does not exist, the turn style does not suit the robot, or the path leaves the field
/// area (row bounds grown by headland_width).
std::vector<PathPoint> build_path(const FieldTruth& truth, const PathConfig& config,
                                  const RobotConfig& robot);

/// Pure pursuit on the true pose: speed from the path, slowing before turns and stops, rotating
/// in place at stop points, stopping at the end.
class PathFollower {
 public:
  /// `lookahead` [m] pure-pursuit look-ahead distance (0.8 m keeps a slipping skid-steer at 1 m/s
  /// within 5 cm of a lane centre; 1 m lets it wander to ~6 cm).
  explicit PathFollower(std::vector<PathPoint> path, double lookahead = 0.8);
  /// Twist command for the current true pose (zero when done). Never throws.
  core::Twist2 command(const core::Pose2& T_world_base);
  bool done() const { return done_; }
  /// [0, 1] fraction of the path length behind the robot.
  double progress() const;
  const std::vector<PathPoint>& path() const { return path_; }

 private:
  std::size_t advance(std::size_t from, double distance, std::size_t limit) const;
  std::size_t next_stop(std::size_t from) const;

  std::vector<PathPoint> path_;
  std::vector<double> arc_;         // [m] cumulative length
  std::vector<std::size_t> stops_;  // indices of points with speed 0, ascending (last included)
  double lookahead_;
  std::size_t index_ = 0;  // closest path point so far (monotonic)
  bool aligning_ = false;  // rotating in place after a stop point
  bool done_ = false;
};

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::TurnStyle> {
  using E = rownav::sim::TurnStyle;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::u_turn, "u_turn"}, {E::in_place, "in_place"}, {E::bulb, "bulb"}}};
};
