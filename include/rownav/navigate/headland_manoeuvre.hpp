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
#include <optional>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/navigate/mission_plan.hpp"
#include "rownav/navigate/turn_choice.hpp"
#include "rownav/navigate/turn_planner.hpp"

namespace rownav::navigate {

/// Parameters of the headland manoeuvres.
struct ManoeuvreConfig {
  double turn_speed = 0.5;             ///< [m/s] along arcs and the headland (003 sec. III: <= 1)
  double rotate_rate = 0.8;            ///< [rad/s] in-place yaw rate
  double heading_tolerance_deg = 2.0;  ///< [deg] rotation done within this of 90 deg (003)
  double lookahead = 0.6;              ///< [m] pure-pursuit look-ahead on the odometry pose
  double anchor_gate = 0.3;  ///< [-] x spacing: a row end within this of its expected place counts
  double pole_band = 1.5;    ///< [m] row ends taken within this of the row-end line (turn x = 0)
  /// [-] row ends (each seen in two frames or more) from which their own centre-to-centre spacing
  /// replaces the in-row estimate in the re-anchoring gate: seen from the headland a row end
  /// shows its canopy's full width, while the in-row spacing of an opaque canopy seen from
  /// inside its corridor can be 15 % short (BENCHMARK.md, issue 10; rownav)
  int spacing_poles = 3;
  /// [-] row ends closer together than the in-row spacing: their spacing is used down to the
  /// in-row one / (1 + this). Clutter on the row-end line (a weed, a post, a canopy seen as two
  /// ends) adds row ends and shortens their spacing, so the short side is the suspect one
  /// (zoo:1:60, 1:91: 1.0 and 1.44 m from row ends for 1.55 and 2.18 m rows; rownav)
  double spacing_tolerance = 0.3;
  /// [-] row ends farther apart than the in-row spacing: their spacing is used up to the in-row
  /// one x (1 + this). It must pass the in-row estimate's own short bias (two corridor rows whose
  /// canopy tops stand above the sensor show their inner top edges: zoo:1:76 measured 1.99 m in
  /// the row for 2.94 m rows, a ratio 1.48) and refuse every other row end missed, or another
  /// block's rows (a ratio 2) (BENCHMARK.md, issue 10; rownav)
  double spacing_tolerance_long = 0.6;
  /// [-] a row end counts (flanks, spacing) once seen in two frames and in this share of the
  /// frames of the most-seen row end: a weed or a post glimpsed in a few frames is none
  /// (zoo:1:70: one seen twice among row ends seen 30-60 times spoilt their spacing; rownav)
  double pole_share = 0.1;
  /// [-] x spacing: a row end this close to a whole number of spacings from another supports
  /// that spacing (the row ends' spacing is the lattice the most of them lie on). Half the
  /// anchor gate: a row end's across position scatters by a few centimetres over the frames,
  /// and a thing midway between two rows (zoo:1:61) is half a spacing off (rownav)
  double lattice_gate = 0.15;
  /// [-] a row end off the lattice, or a lattice point with no row end, between the lattice's
  /// first and last row end costs this many (its, a mean row end's) weights: 2 puts a half or a
  /// double of the true spacing below zero from four row ends on, and keeps one missing row end
  /// (a dead plant at the end) within the lattice (rownav)
  double lattice_penalty = 2.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("turn_speed", s.turn_speed);
    v("rotate_rate", s.rotate_rate);
    v("heading_tolerance_deg", s.heading_tolerance_deg);
    v("lookahead", s.lookahead);
    v("anchor_gate", s.anchor_gate);
    v("pole_band", s.pole_band);
    v("spacing_poles", s.spacing_poles);
    v("spacing_tolerance", s.spacing_tolerance);
    v("spacing_tolerance_long", s.spacing_tolerance_long);
    v("pole_share", s.pole_share);
    v("lattice_gate", s.lattice_gate);
    v("lattice_penalty", s.lattice_penalty);
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
  /// [m] centre-to-centre spacing of the row ends seen so far (spacing_poles of them), else the
  /// in-row spacing the turn was planned with.
  double pole_spacing() const;
  const core::Pose2& T_odom_turn() const { return T_odom_turn_; }
  /// Planned path in odom (for reports).
  std::vector<Eigen::Vector2d> path_odom() const;
  /// [m] length of the planned paths and [s] the time they take at the configured turn speed
  /// and rotation rate (the watchdog's budget of the manoeuvre).
  double planned_distance() const;
  double planned_time() const;

 private:
  void reanchor(const std::vector<Eigen::Vector2d>& ends_turn, const Eigen::Vector2d& robot);
  core::Twist2 follow(const TurnPrimitive& p, const core::Pose2& T_turn_base);

  struct Pole {
    double y = 0.0;  // turn frame
    int n = 0;       // frames merged
  };
  /// A row end seen often enough to count (pole_share).
  bool counted(const Pole& p) const;
  ManoeuvreConfig config_;
  TurnPlan plan_;
  std::vector<Pole> poles_;
  int most_seen_ = 0;  // frames of the most-seen row end
  double exit_x_ = 0.0;
  core::Pose2 T_odom_turn_;
  int side_ = 1, shift_ = 1;
  double spacing_ = 1.0, target_y_ = 0.0, planned_y_ = 0.0;
  std::vector<TurnPrimitive> primitives_;
  std::size_t index_ = 0, cursor_ = 0;
  int rows_passed_ = 0;
};

}  // namespace rownav::navigate
