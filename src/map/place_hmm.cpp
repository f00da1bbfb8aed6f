/// @file place_hmm.cpp HMM place filter, Emmi 2021 eq. (8) and (10).
#include "rownav/map/place_hmm.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/map/place_indices.hpp"

namespace rownav::map {

namespace {

constexpr std::size_t kN = kFilteredPlaces;
/// [m] rounding slack when comparing accumulated travel with the step length
constexpr double kTravelSlack = 1e-9;

/// Normalises in place; false (and left unchanged) when the sum is not positive / finite.
bool normalise(std::array<double, kN>& p) {
  double sum = 0.0;
  for (double x : p) sum += x;
  if (!(sum > 0.0) || !std::isfinite(sum)) return false;
  for (double& x : p) x /= sum;
  return true;
}

}  // namespace

void PlaceHmmConfig::validate() const {
  core::check(motion_transitions.size() == kN * kN, "motion_transitions", "must hold 9 values");
  for (std::size_t i = 0; i < kN; ++i) {
    double row = 0.0;
    for (std::size_t j = 0; j < kN; ++j) {
      const double p = motion_transitions[i * kN + j];
      core::check(p >= 0.0 && p <= 1.0, "motion_transitions", "values must be in [0, 1]");
      row += p;
    }
    core::check(std::abs(row - 1.0) < 1e-6, "motion_transitions", "every row must sum to 1");
  }
  core::check_positive(step_length, "step_length");
  core::check_range(observation_floor, 0.0, 1.0, "observation_floor");
  core::check_range(min_margin, 0.0, 1.0, "min_margin");
  core::check_positive(max_steps_per_update, "max_steps_per_update");
}

PlaceHmm::PlaceHmm(const PlaceHmmConfig& config) : config_(config) {
  config_.validate();
  reset(Place::unknown);
}

void PlaceHmm::reset(Place initial) {
  const int i = filtered_index(initial);
  for (std::size_t k = 0; k < kN; ++k)
    pe_[k] = i < 0 ? 1.0 / static_cast<double>(kN) : (static_cast<int>(k) == i ? 1.0 : 0.0);
  travelled_ = 0.0;
}

void PlaceHmm::predict_one_step() {
  // Emmi 2021 eq. (10): sum over m_k-1 of P(m_k | m_k-1, motion) PE(m_k-1).
  std::array<double, kN> next{};
  for (std::size_t from = 0; from < kN; ++from)
    for (std::size_t to = 0; to < kN; ++to)
      next[to] += config_.motion_transitions[from * kN + to] * pe_[from];
  if (normalise(next)) pe_ = next;
}

PlaceHmmResult PlaceHmm::update(double forward_distance,
                                const std::array<double, kFilteredPlaces>* c_index) {
  PlaceHmmResult out;
  if (std::isfinite(forward_distance) && forward_distance > 0.0) travelled_ += forward_distance;
  while (travelled_ + kTravelSlack >= config_.step_length && out.motion_steps < config_.max_steps_per_update) {
    predict_one_step();
    travelled_ = std::max(0.0, travelled_ - config_.step_length);
    ++out.motion_steps;
  }
  if (out.motion_steps == config_.max_steps_per_update) travelled_ = 0.0;
  if (c_index) {
    // Emmi 2021 eq. (8): P(z_k | m_k) = eta * c_index_m (with a floor).
    std::array<double, kN> post = pe_;
    bool finite = true;
    for (std::size_t k = 0; k < kN; ++k) {
      const double c = (*c_index)[k];
      finite = finite && std::isfinite(c);
      post[k] *= config_.observation_floor + (1.0 - config_.observation_floor) * c;
    }
    if (finite && normalise(post)) pe_ = post;
  }
  out.posterior = pe_;
  double margin = 0.0;
  out.place = instantaneous_place(pe_, config_.min_margin, &margin);
  out.confidence = *std::max_element(pe_.begin(), pe_.end());
  return out;
}

}  // namespace rownav::map
