// Malavazi 2018 sec. 3.1.1: the model filter's initialisation window (rows 0.3-3 m away without a
// model), scaled by the rows' own lattice in narrow and wide fields (issue 10).
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <vector>

#include "rownav/core/statistics.hpp"
#include "rownav/track/model_filter.hpp"

namespace rownav::track {

namespace {

/// The frame's gaps between adjacent rows wider than `min_gap`, ascending (`centres`: between
/// the rows' centre lines, else between the fitted lines), of the rows whose |slope| in the base
/// frame is at most `max_slope`.
std::vector<double> row_gaps(const core::RowObservation& obs, double min_gap, bool centres,
                             double max_slope) {
  std::vector<double> offsets, gaps;
  for (const auto& r : obs.rows)
    if (ModelFilterTracker::usable_row(r) && std::isfinite(r.centre_shift) &&
        std::abs(std::tan(r.heading)) <= max_slope)
      offsets.push_back(centres ? core::centre_offset(r) : r.offset);
  std::sort(offsets.begin(), offsets.end());
  for (std::size_t i = 1; i < offsets.size(); ++i)
    if (offsets[i] - offsets[i - 1] > min_gap) gaps.push_back(offsets[i] - offsets[i - 1]);
  std::sort(gaps.begin(), gaps.end());
  return gaps;
}

}  // namespace

bool ModelFilterTracker::usable_row(const core::RowLine& r) {
  return std::isfinite(r.offset) && std::isfinite(r.heading) && std::abs(r.heading) < 1.4 &&
         std::isfinite(r.x_min) && std::isfinite(r.x_max);
}

double ModelFilterTracker::init_max() const {
  // Only the spacing measured over accepted frames: one frame's rows can skip a row (two rows
  // 10 m apart read as a 10 m spacing and would let the next row in).
  return std::max(config_.init_max_distance, config_.init_spacing_ratio * measured_spacing());
}

double ModelFilterTracker::init_max(const core::RowObservation& obs) const {
  double window = init_max();
  if (!(measured_spacing() > 0.0)) {
    // Issue 10: a 6.4 m orchard's corridor rows stand 3.2 m away, outside the paper's 3 m
    // window, and no spacing is measured before a first row is accepted: the robot never
    // started. The narrowest gap between adjacent rows of this frame is at most the spacing (a
    // row the detector missed widens a gap), so the window never reaches the next corridor's row.
    const std::vector<double> gaps = row_gaps(obs, 2.0 * config_.init_min_distance, false,
                                              std::numeric_limits<double>::infinity());
    window = std::max(window, config_.init_frame_ratio * (gaps.empty() ? 0.0 : gaps.front()));
  }
  // The rows' lattice caps it: in 0.75 m maize the paper's 3 m reached four corridors away, and
  // a side re-initialised on the next corridor's row while its near row was hidden (issue 10).
  const double lattice = lattice_median_;
  return lattice > 0.0 ? std::min(window, config_.init_spacing_ratio * lattice) : window;
}

void ModelFilterTracker::observe_lattice(const core::RowObservation& obs) {
  // Only a lattice narrows the window: the frame's two narrowest centre-to-centre gaps agree. Two
  // lines alone can be anything (the pairs 0.35-0.6 m apart seen while turning), and so can the
  // spacing measured in a turn's first frames (0.16 m seen in 0.75 m maize). Kept through a
  // turn's reset: the frames of a turn seldom show a lattice.
  if (manoeuvring()) return;  // a turn's frames: the rows at every angle, odd "lattices" too
  // Only rows along the robot (max_steepness): in a turn's frames the rows run across it, and
  // their offsets at x = 0 made a 0.68 m "lattice" in 2.8 m rows.
  const std::vector<double> gaps =
      row_gaps(obs, config_.init_min_distance, true, config_.max_steepness);
  if (gaps.size() < 2 || gaps[1] > (1.0 + config_.init_lattice_tolerance) * gaps[0]) return;
  // A followed pair spans one lattice gap (less for an opaque canopy's faces), or two when it
  // skipped a row: a "lattice" under half its width is fragments of crowns or trunks between the
  // rows (zoo hedgerow orchards: 0.7-1.2 m gaps in 3.9 m rows closed the window on every row).
  if (have_[0] && have_[1] &&
      gaps[0] < (model_[0].b - model_[1].b) / (2.0 * (1.0 + config_.init_lattice_tolerance)))
    return;
  lattice_.push_back(gaps[0]);
  while (static_cast<int>(lattice_.size()) > config_.history_size) lattice_.pop_front();
  lattice_median_ = core::median(lattice_);  // once per new gap, not per use
}

double ModelFilterTracker::init_min() const {
  const double lattice = lattice_median_;
  if (!(lattice > 0.0)) return config_.init_min_distance;
  return std::min(config_.init_min_distance, config_.init_min_spacing_ratio * lattice);
}

void ModelFilterTracker::drop_models_beyond_lattice(const core::RowObservation& obs, double near) {
  // A corridor row stands within init_spacing_ratio lattice gaps of the robot. A model beyond
  // that took the next corridor's row (in a turn's frames, with the near row hidden) and its box
  // holds it for good: dropped when this frame shows a row inside the window on its side, the
  // side re-initialises on it (issue 10: 0.75 m maize, a corridor two spacings wide followed).
  const double lattice = lattice_median_;
  if (!(lattice > 0.0)) return;
  const double cap = config_.init_spacing_ratio * lattice;
  for (int s = 0; s < 2; ++s) {
    if (!have_[s] || std::abs(model_[s].b) <= cap) continue;
    const double sign = s == 0 ? 1.0 : -1.0;
    for (const auto& r : obs.rows)
      if (usable_row(r) && sign * r.offset >= near && sign * r.offset <= cap) {
        have_[s] = false;
        spacings_.clear();
        forget_corridor_width();
        break;
      }
  }
  // Two followed models wider apart than a lattice gap span a row: the farther one goes (the
  // robot driven onto the row between them: a corridor 1.5 m wide in 0.75 m maize).
  if (have_[0] && have_[1] &&
      model_[0].b - model_[1].b > (1.0 + config_.init_lattice_tolerance) * lattice) {
    have_[std::abs(model_[0].b) >= std::abs(model_[1].b) ? 0 : 1] = false;
    spacings_.clear();
    forget_corridor_width();
  }
}

}  // namespace rownav::track
