#pragma once
/// @file headland_manoeuvre.hpp Headland turns from one corridor into another, as small state
/// machines closed on the odometry pose and re-anchored on the row ends the LiDAR sees.
///
/// Three families:
///  - in_place: Bertoglio 2023 (003_25dc0df51a1e5faf.txt sec. II-B/C): exit by a fixed distance,
///    rotate 90 deg in place (closed on odometry yaw), drive parallel to the row-end line while
///    counting the row ends passed, stop in the middle of the target corridor, rotate 90 deg;
///  - u_turn: fixed radius = spacing / 2 into the adjacent corridor (Lan 2021,
///    001_b5f4b55a1b95775a.txt sec. 3.3), generalised to arc - straight - arc for k > 1;
///  - bulb: omega turn for car-like robots whose min turn radius exceeds half the lateral shift.
/// Dead-reckoning turns often enter the wrong row (Malavazi 2018, 004_1bee156ef8a2b3f7.txt
/// sec. 4): the target corridor centre is re-anchored between the two row ends that flank it.
///
/// Turn frame: origin on the exit corridor's centre line at the row ends, x along the exit
/// direction, y to the left. The target corridor centre starts at y = side * shift * spacing.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/navigate/mission_plan.hpp"

namespace rownav::navigate {

/// Manoeuvre requested in the configuration.
enum class ManoeuvreChoice : std::uint8_t { automatic, in_place, u_turn, skip, three_point };
/// Manoeuvre actually driven.
enum class TurnKind : std::uint8_t { in_place, u_turn, bulb };

/// What a robot can do, for choosing a turn.
struct TurnAbility {
  bool can_turn_in_place = true;
  double min_turn_radius = 0.0;  ///< [m]
};

/// The chosen turn and its radius.
struct TurnPlan {
  TurnKind kind = TurnKind::in_place;
  double radius = 0.0;  ///< [m] arcs (u_turn, bulb)
  /// The robot can rotate in place; when not (car-like), it backs up along the pursuit arc when
  /// the look-ahead point falls behind it (a three-point correction) instead of rotating.
  bool can_rotate = true;
};

/// Turn for `shift` corridors across at `spacing` [m]: in_place for robots that can (automatic,
/// in_place); u_turn with radius r = max(spacing / 2, 1.25 r_min) when shift * spacing >= 2 r
/// (Lan 2021: radius = spacing / 2; the 25 % margin lets a car-like robot whose steering lags
/// come back onto the arc); otherwise a bulb of radius r. Never throws.
TurnPlan choose_turn(ManoeuvreChoice choice, int shift, double spacing, const TurnAbility& robot);

/// Smallest shift k (corridors) a U-turn of the robot can make at `spacing`:
/// k * spacing >= 2 * 1.25 r_min (choose_turn's radius margin; at least 1).
int min_feasible_shift(double spacing, double min_turn_radius);

/// Parameters of the headland manoeuvres.
struct ManoeuvreConfig {
  double turn_speed = 0.5;             ///< [m/s] along arcs and the headland (003 sec. III: <= 1)
  double rotate_rate = 0.8;            ///< [rad/s] in-place yaw rate
  double heading_tolerance_deg = 2.0;  ///< [deg] rotation done within this of 90 deg (003)
  double lookahead = 0.6;              ///< [m] pure-pursuit look-ahead on the odometry pose
  double anchor_gate = 0.3;  ///< [-] x spacing: a row end within this of its expected place counts
  double pole_band = 1.5;    ///< [m] row ends taken within this of the row-end line (turn x = 0)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("turn_speed", s.turn_speed);
    v("rotate_rate", s.rotate_rate);
    v("heading_tolerance_deg", s.heading_tolerance_deg);
    v("lookahead", s.lookahead);
    v("anchor_gate", s.anchor_gate);
    v("pole_band", s.pole_band);
  }
  void validate() const;
};

/// Phase of a manoeuvre, for the navigator's state.
enum class ManoeuvrePhase : std::uint8_t { turning, headland, done };

/// One control step of a manoeuvre.
struct ManoeuvreStep {
  core::Twist2 cmd;
  ManoeuvrePhase phase = ManoeuvrePhase::turning;
  bool row_passed = false;  ///< a row end passed abeam this step
  bool reanchored = false;  ///< the target was moved onto the row ends this step
};

/// A headland turn being driven. step() never throws.
class HeadlandManoeuvre {
 public:
  /// @param T_odom_turn turn frame in odom; @param exit_distance [m] beyond the row ends (x) at
  /// which the turn starts; shift >= 1, spacing > 0.
  HeadlandManoeuvre(const ManoeuvreConfig& config, const TurnPlan& plan,
                    const core::Pose2& T_odom_turn, int shift, TurnSide side, double spacing,
                    double exit_distance);

  /// One control step from the odometry pose and the row-end points seen (odom frame).
  ManoeuvreStep step(const core::Pose2& T_odom_base, const std::vector<Eigen::Vector2d>& ends);
  bool done() const { return index_ >= primitives_.size(); }
  /// Target corridor centre line in odom, oriented into the corridor (turn -x).
  core::Line2 entry_line_odom() const;
  /// [m] target corridor centre in turn y (after re-anchoring).
  double target_y() const { return target_y_; }
  int rows_passed() const { return rows_passed_; }
  const core::Pose2& T_odom_turn() const { return T_odom_turn_; }
  /// Planned path in odom (for reports).
  std::vector<Eigen::Vector2d> path_odom() const;

 private:
  struct Primitive {
    bool rotate = false;
    double heading = 0.0;               // rotate: target heading (turn frame)
    std::vector<Eigen::Vector2d> path;  // follow: points (turn frame)
    std::vector<double> anchor;         // follow: weight of the target correction per point
    bool headland = false;
    bool reverse_side = false;
  };
  void build_in_place(double e);
  void build_u_turn(double e, double r);
  void build_bulb(double e, double r);
  void reanchor(const std::vector<Eigen::Vector2d>& ends_turn, const Eigen::Vector2d& robot);
  core::Twist2 follow(Primitive& p, const core::Pose2& T_turn_base);

  struct Pole {
    double y = 0.0;  // turn frame
    int n = 0;       // frames merged
  };
  ManoeuvreConfig config_;
  TurnPlan plan_;
  std::vector<Pole> poles_;
  double exit_x_ = 0.0;
  core::Pose2 T_odom_turn_;
  int side_ = 1, shift_ = 1;
  double spacing_ = 1.0, target_y_ = 0.0, planned_y_ = 0.0;
  std::vector<Primitive> primitives_;
  std::size_t index_ = 0, cursor_ = 0;
  int rows_passed_ = 0;
};

}  // namespace rownav::navigate

template <>
struct rownav::core::EnumNames<rownav::navigate::ManoeuvreChoice> {
  using E = rownav::navigate::ManoeuvreChoice;
  static constexpr std::array<std::pair<E, std::string_view>, 5> values{
      {{E::automatic, "auto"},
       {E::in_place, "in_place"},
       {E::u_turn, "u_turn"},
       {E::skip, "skip"},
       {E::three_point, "three_point"}}};
};

template <>
struct rownav::core::EnumNames<rownav::navigate::TurnKind> {
  using E = rownav::navigate::TurnKind;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::in_place, "in_place"}, {E::u_turn, "u_turn"}, {E::bulb, "bulb"}}};
};
