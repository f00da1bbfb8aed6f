#pragma once
/// @file model_filter.hpp The model filter of Malavazi 2018 (004_1bee156ef8a2b3f7.txt sec. 2.3,
/// Fig. 9): data-filter boxes around the followed rows, left / right model selection consistent
/// with the history, a permanence counter falling back to an initialisation mode, the
/// pre-control values (mean spacing, steepness, distance to target with the steep-model safety)
/// and a FIR filter on the output.
///
/// The paper filters the LiDAR points with the boxes before RUBY; a tracker sees the detector's
/// rows, so the boxes gate the detected rows along their support. The followed models are carried
/// between frames by odometry (the paper's Oz robot had none in the loop).
#include <Eigen/Core>
#include <deque>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/track/tracker_base.hpp"

namespace rownav::track {

/// Parameters of ModelFilterTracker. Paper values where it gives them, rownav otherwise.
struct ModelFilterConfig {
  double box_half_width = 0.4;  ///< [m] half width of the data-filter box around a model (rownav)
  /// [-] the point filter's box (filter_points): once the row spacing is measured its half
  /// width is this fraction of it (0.4 m at a 2 m vineyard spacing; a 1 m vegetable bed gets
  /// ~0.16 m, so the lane's weeds stay out, issue 11); 0 keeps box_half_width. The gate of the
  /// detected rows keeps box_half_width (scaled, it cost maize 2 of 3 closed-loop runs)
  double box_spacing_ratio = 0.2;
  /// Malavazi 2018 sec. 2.3.1 as published: the boxes select the next scan's points before the
  /// detector (a planar scan's points; 3D detectors see their cloud unfiltered). false: only
  /// the detected rows are gated by the boxes
  bool filter_points = true;
  double init_min_distance = 0.3;  ///< [m] without a model: rows nearer are ignored (Malavazi 2018)
  /// [-] the same near edge never exceeds this fraction of the rows' lattice gap (see
  /// init_lattice_tolerance): the paper's 0.3 m fit its 1 m beds, but a robot 0.09 m off a
  /// 0.75 m maize corridor's centre has its near row 0.29 m away, and the tracker took the row
  /// beyond it (issues 10 / 11: maize 0 / 5 with calibrated odometry)
  double init_min_spacing_ratio = 0.3;
  /// [-] a frame's two narrowest gaps between adjacent rows' centre lines (> init_min_distance,
  /// rows within max_steepness of the robot's heading) make a lattice when the wider is at most
  /// this fraction above the narrower. The median of the recent frames' lattice gaps
  /// (history_size frames, kept through a turn) sets the near edge (init_min_spacing_ratio) and
  /// caps the far one (init_spacing_ratio); a model beyond that cap, or a followed pair wider
  /// than the lattice, is dropped. A lattice under half the followed pair's width (/ (1 + this))
  /// is crown or trunk fragments and not learnt, nor is any while NavStack says the robot
  /// manoeuvres. Without a lattice the edges are the paper's (rownav)
  double init_lattice_tolerance = 0.25;
  double init_max_distance = 3.0;  ///< [m] without a model: rows farther are ignored (ibid.)
  /// [-] once the row spacing is measured (centre to centre, accepted frames), the same window
  /// reaches at least this fraction of it (issue 10: the paper's 3 m fit its vegetable beds; a
  /// corridor row of a 5 m orchard stands up to ~4 m away, the next row a spacing farther); and
  /// never beyond this fraction of the rows' lattice gap (init_lattice_tolerance)
  double init_spacing_ratio = 0.9;
  /// [-] before any spacing is measured (the start, after a turn), the window reaches at least
  /// this fraction of the narrowest gap between the frame's adjacent rows: the corridor's rows
  /// stand half a spacing away plus the robot's offset (issue 10: a 6.4 m orchard's rows at
  /// 3.2 m were outside the 3 m window, the robot never started; 0.9 let a 5 m orchard's next
  /// row in after a turn)
  double init_frame_ratio = 0.6;
  double max_slope_change = 0.1;    ///< [-] |a - a_prev| above this: inconsistent (rownav)
  double max_offset_change = 0.25;  ///< [m] |b - b_prev| above this: inconsistent (rownav)
  /// [m] |b_l - b_r - mean width| above this: inconsistent (b_l - b_r: the width between the
  /// fitted lines, not the row spacing, issue 10)
  double spacing_tolerance = 0.4;
  /// [-] successive rejected frames that erase the followed models (initialisation mode);
  /// "chosen heuristically" in Malavazi 2018 sec. 2.3.2
  int permanence_limit = 5;
  int history_size = 20;  ///< [-] accepted frames averaged for the mean spacing and slope (rownav)
  /// [-] |a| above this: steep models, distance to target by interception (Malavazi 2018
  /// sec. 2.3.3; tan 15 deg, rownav)
  double max_steepness = 0.27;
  /// [-] FIR impulse response b_0..b_N of eq. (6), newest first; sums to 1 ("empirically tuned",
  /// Malavazi 2018 sec. 2.3.4; rownav values)
  std::vector<double> fir_coefficients = {0.5, 0.3, 0.2};
  TrackerConfig common;  ///< coasting, odometry plausibility, implement target

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("box_half_width", s.box_half_width);
    v("box_spacing_ratio", s.box_spacing_ratio);
    v("filter_points", s.filter_points);
    v("init_min_distance", s.init_min_distance);
    v("init_min_spacing_ratio", s.init_min_spacing_ratio);
    v("init_lattice_tolerance", s.init_lattice_tolerance);
    v("init_max_distance", s.init_max_distance);
    v("init_spacing_ratio", s.init_spacing_ratio);
    v("init_frame_ratio", s.init_frame_ratio);
    v("max_slope_change", s.max_slope_change);
    v("max_offset_change", s.max_offset_change);
    v("spacing_tolerance", s.spacing_tolerance);
    v("permanence_limit", s.permanence_limit);
    v("history_size", s.history_size);
    v("max_steepness", s.max_steepness);
    v("fir_coefficients", s.fir_coefficients);
    v("common", s.common);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Malavazi 2018 model filter as a RowTracker; fills RowTracking::steepness and
/// distance_to_target.
class ModelFilterTracker : public TrackerBase {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit ModelFilterTracker(const ModelFilterConfig& config = {});
  std::string_view name() const override { return "model_filter"; }
  const ModelFilterConfig& config() const { return config_; }
  std::optional<core::DataFilterBoxes> data_filter(const core::Pose2& T_odom_base) const override;
  /// A detected row the filter considers: finite geometry, not running across the robot's path.
  static bool usable_row(const core::RowLine& r);

 protected:
  bool has_model() const override { return have_[0] || have_[1]; }
  void clear_models() override;
  void predict(const core::Pose2& T_prev_now, const core::Pose2& T_odom_base, double dt) override;
  bool correct(const core::RowObservation& obs, const core::Pose2& T_odom_base) override;
  void describe(RowTracking& out) const override;
  void forget_side(bool left) override;
  void finish(RowTracking& out) override;

 private:
  /// Data-filter box test of a detected row against side s (0 left, 1 right).
  bool in_box(const core::RowLine& r, int s, double init_min, double init_max) const;
  /// Consistency of a candidate with the followed model of side s and the history.
  bool consistent(const SlopeIntercept& c, int s) const;
  double mean_spacing() const;
  /// [m] initialisation window's far edge (init_max_distance, or more with the spacing measured).
  double init_max() const;
  /// [m] the same for one frame: before any spacing is measured, init_frame_ratio x the
  /// narrowest gap between this frame's adjacent rows (a missing row widens a gap, never
  /// narrows it), so that a field wider than 2 x init_max_distance can be entered at all;
  /// never beyond init_spacing_ratio x the recent lattice gap.
  double init_max(const core::RowObservation& obs) const;
  /// Remembers `obs`'s lattice gap (its two narrowest centre-to-centre gaps agree).
  void observe_lattice(const core::RowObservation& obs);
  /// Drops a side's model that stands beyond init_spacing_ratio lattice gaps while `obs` shows a
  /// row on that side inside [near, that cap].
  void drop_models_beyond_lattice(const core::RowObservation& obs, double near);
  /// [m] initialisation window's near edge: init_min_distance, or less in narrow rows
  /// (init_min_spacing_ratio x the recent frames' median lattice gap).
  double init_min() const;
  /// [m] the data-filter box half width in effect (box_spacing_ratio x the measured spacing).
  double box_half_width() const;

  ModelFilterConfig config_;
  bool have_[2] = {false, false};  // left, right
  SlopeIntercept model_[2];        // followed models, current base frame
  double seen_[2] = {0.0, 0.0};    // stamp of the last acceptance per side
  // Extent of the accepted rows' points along x (first / last point, current base frame), carried
  // by odometry like the models: the end-of-row and row-end logic read it.
  Eigen::Vector2d first_[2], last_[2];
  int support_[2] = {0, 0};
  int permanence_ = 0;           // successive rejected frames
  std::deque<double> spacings_;  // accepted b_l - b_r
  std::deque<double> lattice_;   // recent frames' lattice gaps (kept through clear_models)
  double lattice_median_ = 0.0;  // [m] median of lattice_ (0: none yet)
  std::deque<double> fir_lat_, fir_head_, fir_dist_;  // newest first
};

}  // namespace rownav::track
