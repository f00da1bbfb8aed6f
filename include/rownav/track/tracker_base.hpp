#pragma once
/// @file tracker_base.hpp What every row tracker shares: the common config (coasting time,
/// odometry plausibility, implement target row) and the frame driver that gates time and
/// odometry, carries the models by odometry, decides tracking / coasting / lost and turns the two
/// followed rows into corridor deviations.
#include <array>
#include <optional>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/track/row_geometry.hpp"
#include "rownav/track/row_spacing.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::track {

/// Which followed row an implement is referenced to (RowTracking::target_lateral_error).
enum class TargetRow : std::uint8_t { none, left, right };

/// Parameters shared by every tracker (rownav; the papers leave them to the integrator).
struct TrackerConfig {
  /// [s] coasting on odometry longer than this without an observation: lost, models dropped.
  /// Must exceed the longest gap to bridge (a 2 s detector blackout, 3 missing vines at 1 m/s).
  double max_coast_time = 3.0;
  double max_speed = 3.0;           ///< [m/s] faster odometry increments are jumps (ignored)
  double max_yaw_rate_deg = 120.0;  ///< [deg/s] faster odometry rotations are jumps (ignored)
  /// [m] spacing assumed until two rows are seen; the corridor centre of a single row lies half
  /// of it away (Malavazi 2018 sec. 2.3.3 "a default distance"). 2 m: vineyards.
  double default_row_spacing = 2.0;
  /// [frames] row spacing (centre to centre, every row seen) and the followed rows' centre
  /// shifts are medians over the latest this many usable frames (~5 s at 10 Hz; issue 10)
  int spacing_window = 50;
  /// [-] of the row spacing: a frame whose two rows stand this much further apart than the
  /// followed rows did sees past a gap in a followed row (the row beyond it). It is left out of
  /// the spacing (one difference of two spacings, it doubled the spacing over a 17 m gap; issue
  /// 10, zoo:1:31), and a tracked pair that wide is not followed: the nearer row alone is, at
  /// the corridor width, until the gap ends. A row missing widens the corridor by a whole
  /// spacing; half of it is the midpoint. Only once the corridor has settled (settle_frames).
  double gap_width_ratio = 0.5;
  /// [frames] the corridor has settled when both followed rows were seen and their width held
  /// within width_tolerance from frame to frame this many times in a row (5 s at 10 Hz). Pairs
  /// followed while turning are no reference (2.06 m in a 6.6 m orchard, 0.35 m in 1.8 m rows):
  /// measured against them, the corridor entered after the turn read as a gap.
  int settle_frames = 50;
  double width_tolerance = 0.2;            ///< [-] of the width; see settle_frames
  TargetRow target_row = TargetRow::none;  ///< implement row: none, left or right
  double target_offset =
      0.0;  ///< [m] wanted signed offset of the base from the target row (left +)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("max_coast_time", s.max_coast_time);
    v("max_speed", s.max_speed);
    v("max_yaw_rate_deg", s.max_yaw_rate_deg);
    v("default_row_spacing", s.default_row_spacing);
    v("spacing_window", s.spacing_window);
    v("gap_width_ratio", s.gap_width_ratio);
    v("settle_frames", s.settle_frames);
    v("width_tolerance", s.width_tolerance);
    v("target_row", s.target_row);
    v("target_offset", s.target_offset);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Frame driver of the trackers. update() gates the stamp and the odometry, calls predict() with
/// the odometry increment, correct() with a usable observation, then fills the deviations from
/// the followed rows. Stale frames (stamp not after the last one) and non-finite input are
/// ignored (the last answer is returned); implausible odometry increments are not applied.
class TrackerBase : public RowTracker {
 public:
  explicit TrackerBase(const TrackerConfig& common);
  RowTracking update(const core::RowObservation& obs, const core::Pose2& T_odom_base) final;
  void reset() final;
  const TrackerConfig& common() const { return common_; }
  void set_manoeuvring(bool manoeuvring) final { manoeuvring_ = manoeuvring; }

 protected:
  /// True between set_manoeuvring(true) and set_manoeuvring(false).
  bool manoeuvring() const { return manoeuvring_; }
  /// True while the tracker holds row models.
  virtual bool has_model() const = 0;
  /// Forgets every model.
  virtual void clear_models() = 0;
  /// Carries the models from the previous base frame to the current one (T_prev_now), dt [s].
  virtual void predict(const core::Pose2& T_prev_now, const core::Pose2& T_odom_base,
                       double dt) = 0;
  /// Updates the models with a usable observation; false when nothing was accepted.
  virtual bool correct(const core::RowObservation& obs, const core::Pose2& T_odom_base) = 0;
  /// Fills rows, left, right and row_spacing (0: unknown, then the base's estimate from every
  /// row seen is used) of `out`; a row's centre_offset left NaN is filled by the base.
  virtual void describe(RowTracking& out) const = 0;
  /// [m] row spacing centre to centre from the recent observations (0: none yet).
  double measured_spacing() const { return spacing_.spacing(); }
  /// Odometry pose of the last update (the models' base frame); nullopt before the first.
  std::optional<core::Pose2> last_pose() const {
    return started_ ? std::optional<core::Pose2>(last_pose_) : std::nullopt;
  }
  /// Last say on the output (e.g. a FIR filter); the default does nothing.
  virtual void finish(RowTracking& /*out*/) {}
  /// The followed model on one side stands beyond a gap (follow_nearer_past_a_gap): a tracker
  /// that keeps one model per side drops it, to take the nearer row again when the gap ends.
  virtual void forget_side(bool /*left*/) {}
  /// The followed pair was wrong (a tracker found it spans a row): its width no longer places a
  /// single row's corridor centre; the spacing and canopy do until a new pair is measured.
  void forget_corridor_width() { width_ = 0.0, width_frames_ = 0; }

 private:
  void fill_deviations(RowTracking& out);
  /// Row spacing and centre lines from the recent observations where the tracker gave none.
  void fill_centres(RowTracking& out) const;

  TrackerConfig common_;
  bool started_ = false;
  double last_stamp_ = 0.0;
  double last_seen_ = 0.0;  // stamp of the last frame whose observation updated the models
  core::Pose2 last_pose_;
  RowTracking last_;
  RowSpacingEstimator spacing_;  // centre to centre, every row seen (issue 10)
  /// True when the observation has two rows, one either side, standing gap_width_ratio x the
  /// spacing further apart than the followed rows of a settled corridor (width_): a followed row
  /// is missing from it, the row beyond seen instead.
  bool sees_past_a_gap(const core::RowObservation& obs) const;
  /// True when lines `left` and `right` stand gap_width_ratio x the spacing further apart than
  /// the followed rows of a settled corridor did (width_, settle_frames).
  bool wider_than_corridor(const core::Line2& left, const core::Line2& right) const;
  /// Unsets (and forgets) the farther of the followed pair when the pair is wider than the
  /// corridor.
  void follow_nearer_past_a_gap(RowTracking& out);
  /// The followed pair's width of this frame (width_) and for how long it has held.
  void update_width(const RowTracking& out, double width);

  bool manoeuvring_ = false;
  double width_ = 0.0;    // [m] last width between the followed rows' lines
  int width_frames_ = 0;  // successive frames the width held within width_tolerance
};

}  // namespace rownav::track

template <>
struct rownav::core::EnumNames<rownav::track::TargetRow> {
  using E = rownav::track::TargetRow;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::none, "none"}, {E::left, "left"}, {E::right, "right"}}};
};
