// Malavazi 2018 sec. 2.3: data filtering, model filter with permanence counter, pre-control and
// FIR filter.
#include "rownav/track/model_filter.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rownav::track {

namespace {

/// Malavazi 2018 eq. (6): e_f[k] = sum b_i e[k - i] over the values available so far (the
/// coefficients renormalised while the history is shorter than the filter).
double fir(std::deque<double>& history, double e, const std::vector<double>& b) {
  history.push_front(e);
  while (history.size() > b.size()) history.pop_back();
  double sum = 0.0, weight = 0.0;
  for (std::size_t i = 0; i < history.size(); ++i) sum += b[i] * history[i], weight += b[i];
  return weight > 0.0 ? sum / weight : e;
}

}  // namespace

void ModelFilterConfig::validate() const {
  core::check_positive(box_half_width, "box_half_width");
  core::check_range(box_spacing_ratio, 0.0, 1.0, "box_spacing_ratio");
  core::check_non_negative(init_min_distance, "init_min_distance");
  core::check_range(init_min_spacing_ratio, 0.0, 0.5, "init_min_spacing_ratio");
  core::check_range(init_lattice_tolerance, 0.0, 1.0, "init_lattice_tolerance");
  core::check(init_max_distance > init_min_distance, "init_max_distance",
              "must be > init_min_distance");
  core::check_non_negative(init_spacing_ratio, "init_spacing_ratio");
  core::check_range(init_frame_ratio, 0.0, 1.0, "init_frame_ratio");
  core::check_positive(max_slope_change, "max_slope_change");
  core::check_positive(max_offset_change, "max_offset_change");
  core::check_positive(spacing_tolerance, "spacing_tolerance");
  core::check_range(permanence_limit, 1, 100000, "permanence_limit");
  core::check_range(history_size, 1, 100000, "history_size");
  core::check_positive(max_steepness, "max_steepness");
  core::check(!fir_coefficients.empty() && fir_coefficients.size() <= 100, "fir_coefficients",
              "must hold 1 to 100 values");
  const double sum = std::accumulate(fir_coefficients.begin(), fir_coefficients.end(), 0.0);
  core::check(std::abs(sum - 1.0) < 1e-6, "fir_coefficients", "must sum to 1");
  core::check(fir_coefficients[0] > 0.0, "fir_coefficients", "b_0 must be > 0");
  core::validate_nested(common, "common");
}

ModelFilterTracker::ModelFilterTracker(const ModelFilterConfig& config)
    : TrackerBase((config.validate(), config.common)), config_(config) {}

void ModelFilterTracker::clear_models() {
  have_[0] = have_[1] = false;
  permanence_ = 0;
  // The width history belonged to the erased pair: kept, it rejected the first side to come back
  // for good (only the side with a model passes it; closed_loop_narrow, a turn's pair 1.32 m).
  spacings_.clear();
  fir_lat_.clear(), fir_head_.clear(), fir_dist_.clear();
}

void ModelFilterTracker::predict(const core::Pose2& T_prev_now, const core::Pose2&, double) {
  const core::Pose2 T_now_prev = T_prev_now.inverse();
  for (int s = 0; s < 2; ++s)
    if (have_[s]) {
      model_[s] = move_line(model_[s], T_prev_now);
      first_[s] = T_now_prev * first_[s];
      last_[s] = T_now_prev * last_[s];
    }
}

double ModelFilterTracker::mean_spacing() const {
  if (spacings_.empty()) return common().default_row_spacing;
  return std::accumulate(spacings_.begin(), spacings_.end(), 0.0) / double(spacings_.size());
}

double ModelFilterTracker::box_half_width() const {
  const double s = measured_spacing();
  if (config_.box_spacing_ratio <= 0.0 || !std::isfinite(s) || s <= 0.0)
    return config_.box_half_width;
  return config_.box_spacing_ratio * s;
}

std::optional<core::DataFilterBoxes> ModelFilterTracker::data_filter(
    const core::Pose2& T_odom_base) const {
  const auto pose = last_pose();
  if (!config_.filter_points || !pose) return std::nullopt;
  core::DataFilterBoxes f;
  f.half_width = box_half_width();
  f.init_min_range = config_.init_min_distance;
  f.init_max_range = init_max();
  const core::Pose2 step = pose->inverse() * T_odom_base;  // models' frame -> this frame
  for (int s = 0; s < 2; ++s)
    if (have_[s] && std::abs(model_[s].a) <= config_.max_steepness) {
      const SlopeIntercept m = move_line(model_[s], step);
      f.models[static_cast<std::size_t>(s)] = core::SideModel{m.a, m.b};
    }
  return f;
}

bool ModelFilterTracker::in_box(const core::RowLine& r, int s, double init_min,
                                double init_max) const {
  const bool side = s == 0 ? r.offset > 0.0 : r.offset < 0.0;
  if (!side) return false;
  if (!have_[s] || std::abs(model_[s].a) > config_.max_steepness) {
    // Malavazi 2018 sec. 3.1.1: no (or a steep) model: the rows on that side, 0.3-3 m away.
    const double d = std::abs(r.offset);
    return d >= init_min && d <= init_max;
  }
  // Infinite-length box of half width box_half_width around the model (sec. 2.3.1), checked over
  // the row's support.
  const SlopeIntercept& m = model_[s];
  for (const double x : {r.x_min, r.x_max, 0.0})
    if (std::abs(r.line.y_at(x) - (m.a * x + m.b)) > config_.box_half_width) return false;
  return true;
}

bool ModelFilterTracker::consistent(const SlopeIntercept& c, int s) const {
  if (!have_[s]) return true;  // initialisation mode for this side
  return std::abs(c.a - model_[s].a) <= config_.max_slope_change &&
         std::abs(c.b - model_[s].b) <= config_.max_offset_change;
}

bool ModelFilterTracker::correct(const core::RowObservation& obs, const core::Pose2&) {
  // Model filter 1 + 2 (Malavazi 2018 Fig. 9): per side the nearest row inside its box.
  int pick[2] = {-1, -1};
  observe_lattice(obs);
  const double near = init_min(), far = init_max(obs);
  drop_models_beyond_lattice(obs, near);
  for (int s = 0; s < 2; ++s)
    for (std::size_t i = 0; i < obs.rows.size(); ++i) {
      const auto& r = obs.rows[i];
      if (!usable_row(r) || !in_box(r, s, near, far)) continue;
      if (pick[s] < 0 || std::abs(r.offset) < std::abs(obs.rows[std::size_t(pick[s])].offset))
        pick[s] = static_cast<int>(i);
    }
  SlopeIntercept cand[2];
  bool ok[2] = {false, false};
  for (int s = 0; s < 2; ++s) {
    if (pick[s] < 0) continue;
    cand[s] = slope_intercept(obs.rows[std::size_t(pick[s])].line);
    ok[s] = consistent(cand[s], s);
  }
  if (ok[0] && ok[1] && !spacings_.empty() &&
      std::abs(cand[0].b - cand[1].b - mean_spacing()) > config_.spacing_tolerance) {
    // Inconsistent with the history's spacing: keep the side that moved least.
    const double d0 = have_[0] ? std::abs(cand[0].b - model_[0].b) : 1e9;
    const double d1 = have_[1] ? std::abs(cand[1].b - model_[1].b) : 1e9;
    ok[d0 <= d1 ? 1 : 0] = false;
  }
  if (!ok[0] && !ok[1]) {
    // Permanence counter (sec. 2.3.2): too many rejections erase the models -> initialisation.
    if (++permanence_ >= config_.permanence_limit) clear_models();
    return false;
  }
  permanence_ = 0;
  for (int s = 0; s < 2; ++s)
    if (ok[s]) {
      model_[s] = cand[s], have_[s] = true, seen_[s] = obs.stamp;
      const auto& r = obs.rows[std::size_t(pick[s])];
      first_[s] = {r.x_min, r.line.y_at(r.x_min)};
      last_[s] = {r.x_max, r.line.y_at(r.x_max)};
      support_[s] = r.support;
    }
  // Update filters: a side not seen for the coasting time is dropped.
  for (int s = 0; s < 2; ++s)
    if (have_[s] && obs.stamp - seen_[s] > common().max_coast_time) {
      // A side re-initialises: the width history belonged to the old pair of models and would
      // reject the new one forever (a crown face taken for the row at the start, issue 10).
      have_[s] = false;
      spacings_.clear();
    }
  if (ok[0] && ok[1]) {
    spacings_.push_back(cand[0].b - cand[1].b);
    while (static_cast<int>(spacings_.size()) > config_.history_size) spacings_.pop_front();
  }
  return true;
}

void ModelFilterTracker::forget_side(bool left) {
  // Issue 10: the side's model took the row beyond a gap (inside the 3 m initialisation window
  // in 1.6 m rows); dropped, the side re-initialises on the nearest row, the near one once the
  // gap ends. The width history goes too: it holds the far pair's widths, and against them the
  // near row's pair read as inconsistent for good.
  have_[left ? 0 : 1] = false;
  spacings_.clear();
}

void ModelFilterTracker::describe(RowTracking& out) const {
  for (int s = 1; s >= 0; --s) {  // right first: sorted right to left
    if (!have_[s]) continue;
    TrackedRow t;
    t.id = s == 0 ? 1 : 0;
    t.line_base = line_of(model_[s]);
    t.offset = model_[s].b;
    t.heading = std::atan(model_[s].a);
    t.last_seen = seen_[s];
    t.x_min = first_[s].x();
    t.x_max = last_[s].x();
    t.support = support_[s];
    out.rows.push_back(t);
    (s == 0 ? out.left : out.right) = static_cast<int>(out.rows.size()) - 1;
  }
  if (out.left >= 0 && out.right >= 0 &&
      out.rows[std::size_t(out.left)].offset <= out.rows[std::size_t(out.right)].offset)
    out.left = -1;  // crossed models: follow the right one only
  // spacings_ holds b_l - b_r, the width between the fitted lines (the consistency check of the
  // candidates); the row spacing is centre to centre, from TrackerBase (issue 10).
  out.row_spacing = 0.0;
}

void ModelFilterTracker::finish(RowTracking& out) {
  if (out.status == TrackStatus::lost) {
    fir_lat_.clear(), fir_head_.clear(), fir_dist_.clear();
    return;
  }
  // Pre-control (sec. 2.3.3): with steep models the error is the signed distance to where the
  // robot crosses the model it heads into, so two steep rows around the robot do not read as 0.
  double e = out.lateral_error;
  if (out.steepness > config_.max_steepness) {
    double nearest = 1e300;
    for (const int i : {out.left, out.right}) {
      if (i < 0) continue;
      const SlopeIntercept m = slope_intercept(out.rows[std::size_t(i)].line_base);
      const double x = -m.b / m.a;  // where y = 0 (the robot's path) meets the model
      if (x > 0.0 && x < nearest) nearest = x, e = (i == out.left ? 1.0 : -1.0) * x;
    }
  }
  const auto& b = config_.fir_coefficients;
  out.distance_to_target = fir(fir_dist_, e, b);
  out.lateral_error = fir(fir_lat_, out.lateral_error, b);
  out.heading_error = fir(fir_head_, out.heading_error, b);
}

}  // namespace rownav::track
