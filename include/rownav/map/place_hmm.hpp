#pragma once
/// @file place_hmm.hpp Hidden Markov model filter of the place (Emmi 2021,
/// 002_806e72d300173f73.txt, eq. (8) observation model, eq. (10) filter, after Rottmann 2005 /
/// Weiss and Biber 2010): motion and no-motion transition models over headland, lane, alley.
#include <array>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/map/place.hpp"
#include "rownav/map/transition_model_data.hpp"

namespace rownav::map {

/// Configuration of the place filter.
struct PlaceHmmConfig {
  /// [-] P(m_k | m_k-1, motion) for one motion step, row-major from -> to over (headland, lane,
  /// alley); default: estimated by rownav's simulator (transition_model_data.hpp, Emmi 2021 sec.
  /// "Current state estimation": random poses, one motion step, counted transitions)
  std::vector<double> motion_transitions{kMotionTransitions.begin(), kMotionTransitions.end()};
  /// [m] forward travel of one motion step (the step the matrix was counted with)
  double step_length = kMotionStepLength;
  /// [-] eq. (8) likelihood floor: P(z | m) = floor + (1 - floor) * c_index_m, so that one
  /// contradicting frame cannot zero a state (rownav)
  double observation_floor = 0.25;
  /// [-] top two posteriors closer than this: the filtered state is unknown (eq. (9) margin)
  double min_margin = 0.05;
  int max_steps_per_update = 50;  ///< [steps] motion steps applied in one update at most

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("motion_transitions", s.motion_transitions);
    v("step_length", s.step_length);
    v("observation_floor", s.observation_floor);
    v("min_margin", s.min_margin);
    v("max_steps_per_update", s.max_steps_per_update);
  }
  void validate() const;
};

/// Output of one filter step.
struct PlaceHmmResult {
  std::array<double, kFilteredPlaces> posterior{};  ///< PE(m_k), sums to 1
  Place place = Place::unknown;  ///< argmax of the posterior, unknown within min_margin
  double confidence = 0.0;       ///< the top posterior
  int motion_steps = 0;          ///< motion steps applied this update (0: no-motion model)
};

/// The filter. Stateful; update() never throws.
class PlaceHmm {
 public:
  explicit PlaceHmm(const PlaceHmmConfig& config = {});
  /// Starts from a known place (uniform for unknown / gate).
  void reset(Place initial);
  /// One frame: `forward_distance` [m] travelled forward since the last update (<= 0: the
  /// no-motion model, P = identity; Emmi 2021: transitions happen moving forward), and the
  /// c_index of eq. (6) (nullptr or non-finite: no observation, prediction only).
  PlaceHmmResult update(double forward_distance, const std::array<double, kFilteredPlaces>* c_index);
  const std::array<double, kFilteredPlaces>& posterior() const { return pe_; }
  const PlaceHmmConfig& config() const { return config_; }

 private:
  void predict_one_step();

  PlaceHmmConfig config_;
  std::array<double, kFilteredPlaces> pe_{};
  double travelled_ = 0.0;  // forward travel not yet used by a motion step
};

}  // namespace rownav::map
