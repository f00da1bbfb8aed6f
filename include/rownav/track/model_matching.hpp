#pragma once
/// @file model_matching.hpp Row model matching (Nehme 2021, 000_0dc267f189bd9473.txt sec. 3.3):
/// one line model per row kept in a fixed odometry-anchored frame, row centres associated to the
/// models by the zone rule, models refitted by the heading-regularised regression of eq. (9).
///
/// The models live in the "model frame": the odometry pose of the base when the models were
/// initialised (so the rows run near its x axis and y = w1 x + w0 stays well defined).
#include <deque>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/track/tracker_base.hpp"

namespace rownav::track {

/// Parameters of ModelMatchingTracker. Defaults: Nehme 2021 sec. 3.3.
struct ModelMatchingConfig {
  double assign_zone = 0.4;  ///< [-] d < assign_zone * s: assign (Nehme 2021 sec. 3.3)
  double reject_zone = 0.5;  ///< [-] d in [assign, reject) * s: outlier; beyond: new model (ibid.)
  int buffer_size = 50;      ///< [-] row centres kept per model (Nehme 2021 sec. 3.3)
  double alpha = 1.5;        ///< [-] heading regularisation of eq. (9) (Nehme 2021 sec. 3.3)
  /// [s] a model not updated for this long is dropped (rownav: rows left behind or weeds)
  double model_timeout = 3.0;
  /// [-] centres a model created after the first frame needs before it can be followed (rownav:
  /// a weed seen once never becomes the followed row)
  int min_follow_support = 3;
  int max_models = 16;   ///< [-] at most this many models (rownav: bounds the per-frame cost)
  /// [deg] a row centre is assigned to a model only if their headings differ less than this
  /// (rownav: the zone rule measures the distance at the row centre only, so a row crossing a
  /// model at a steep angle - a row seen during a headland turn - would otherwise be merged)
  double max_assign_heading_deg = 15.0;
  /// [-] consecutive frames with rows on both sides (status ok) whose left or right row matches
  /// no model before every model is dropped and re-initialised from that frame (rownav: models
  /// initialised from headland clutter or odd-angle rows, Nehme's eq. (4) on a bad first
  /// observation, must not stay latched once the new corridor is in view)
  int reinit_after = 3;
  TrackerConfig common;  ///< coasting, odometry plausibility, implement target

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("assign_zone", s.assign_zone);
    v("reject_zone", s.reject_zone);
    v("buffer_size", s.buffer_size);
    v("alpha", s.alpha);
    v("model_timeout", s.model_timeout);
    v("min_follow_support", s.min_follow_support);
    v("max_models", s.max_models);
    v("max_assign_heading_deg", s.max_assign_heading_deg);
    v("reinit_after", s.reinit_after);
    v("common", s.common);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Nehme 2021 model matching as a RowTracker.
class ModelMatchingTracker : public TrackerBase {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit ModelMatchingTracker(const ModelMatchingConfig& config = {});
  std::string_view name() const override { return "model_matching"; }
  const ModelMatchingConfig& config() const { return config_; }

 protected:
  bool has_model() const override { return !models_.empty(); }
  void clear_models() override {
    models_.clear();
    contradictions_ = 0;
  }
  void predict(const core::Pose2& T_prev_now, const core::Pose2& T_odom_base, double dt) override;
  bool correct(const core::RowObservation& obs, const core::Pose2& T_odom_base) override;
  void describe(RowTracking& out) const override;

 private:
  /// A row centre (x_i, y_i, tan gamma_i) in the model frame (Nehme 2021 eq. (3)), with the
  /// observed row's centre shift and canopy half width (core::RowLine, issue 10).
  struct Centre {
    double x = 0.0, y = 0.0, tan_gamma = 0.0;
    double shift = 0.0, half_width = 0.0;
  };
  /// A row model y = w1 x + w0 in the model frame (Nehme 2021 eq. (4)).
  struct Model {
    int id = -1;
    double w0 = 0.0, w1 = 0.0;
    std::deque<Centre> buffer;
    double created = 0.0, last_seen = 0.0;
    double x_min = 0.0, x_max = 0.0;  // extent of the observed rows along x (model frame)
    int support = 0;
    bool initial = false;  // created from the first observation O_1
  };
  void fit(Model& m) const;
  double median_spacing(double x_robot) const;
  void add_model(const Centre& c, double stamp, bool initial, double x_min, double x_max);
  /// Row centre, heading tangent and x extent [xa, xb] of a detected row in the model frame.
  Centre to_model(const core::RowLine& r, double& xa, double& xb) const;
  /// Zone rule for one observed row (model frame); true when assigned to a model.
  bool associate(const core::RowLine& r, double s, double stamp, std::vector<bool>& touched);
  /// Nehme 2021 eq. (4) for every row of `obs`: the models of a (re)initialisation.
  void initialise(const core::RowObservation& obs);

  ModelMatchingConfig config_;
  std::vector<Model> models_;
  core::Pose2 T_odom_model_;
  core::Pose2 T_model_base_;  // current base in the model frame
  double stamp_ = 0.0;
  int next_id_ = 0;
  int contradictions_ = 0;  // consecutive good frames whose corridor rows matched no model
};

}  // namespace rownav::track
