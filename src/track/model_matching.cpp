// Nehme 2021 sec. 3.3: initialisation (eq. (4)), zone-rule data association, regularised
// regression (eq. (9)). rownav additions: a heading gate on the association and a
// re-initialisation when good frames keep contradicting the models (after a headland turn).
#include "rownav/track/model_matching.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rownav::track {

namespace {

/// Base-frame point of a detected row at the middle of its support (the paper's row centre).
Eigen::Vector2d centre_of(const core::RowLine& r) {
  const bool extent = std::isfinite(r.x_min) && std::isfinite(r.x_max) && r.x_max > r.x_min;
  const double x = extent ? 0.5 * (r.x_min + r.x_max) : 0.0;
  return {x, r.line.y_at(x)};
}

bool finite_row(const core::RowLine& r) {
  return std::isfinite(r.line.point.x()) && std::isfinite(r.line.point.y()) &&
         std::isfinite(r.line.direction.x()) && std::isfinite(r.line.direction.y()) &&
         std::abs(r.line.direction.x()) > 1e-6;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

void ModelMatchingConfig::validate() const {
  core::check_range(assign_zone, 0.01, 1.0, "assign_zone");
  core::check(reject_zone >= assign_zone, "reject_zone", "must be >= assign_zone");
  core::check_range(reject_zone, 0.01, 1.0, "reject_zone");
  core::check_range(buffer_size, 1, 100000, "buffer_size");
  core::check_non_negative(alpha, "alpha");
  core::check_positive(model_timeout, "model_timeout");
  core::check_range(min_follow_support, 1, 100000, "min_follow_support");
  core::check_range(max_models, 2, 1000, "max_models");
  core::check_range(max_assign_heading_deg, 0.1, 90.0, "max_assign_heading_deg");
  core::check_range(reinit_after, 1, 1000, "reinit_after");
  core::validate_nested(common, "common");
}

ModelMatchingTracker::ModelMatchingTracker(const ModelMatchingConfig& config)
    : TrackerBase((config.validate(), config.common)), config_(config) {}

void ModelMatchingTracker::predict(const core::Pose2& T_prev_now, const core::Pose2&, double) {
  T_model_base_ = T_model_base_ * T_prev_now;  // the models stay put in the model frame
}

void ModelMatchingTracker::add_model(const Centre& c, double stamp, bool initial, double x_min,
                                     double x_max) {
  // Nehme 2021 eq. (4): y = x tan(gamma) + y_i - x_i tan(gamma).
  Model m;
  m.id = next_id_++;
  m.w1 = c.tan_gamma;
  m.w0 = c.y - c.x * c.tan_gamma;
  m.buffer.push_back(c);
  m.created = m.last_seen = stamp;
  m.x_min = x_min, m.x_max = x_max;
  m.support = 1;
  m.initial = initial;
  models_.push_back(std::move(m));
}

void ModelMatchingTracker::fit(Model& m) const {
  // Nehme 2021 eq. (9), x centred on the buffer mean (same minimiser, better conditioned):
  // W = (X^T X + alpha a^T a)^-1 (X^T Y + alpha a^T Gamma).
  const double n = static_cast<double>(m.buffer.size());
  double xr = 0.0;
  for (const auto& c : m.buffer) xr += c.x;
  xr /= n;
  double sy = 0.0, sxx = 0.0, sxy = 0.0, sg = 0.0;
  for (const auto& c : m.buffer) {
    const double dx = c.x - xr;
    sy += c.y, sxx += dx * dx, sxy += dx * c.y, sg += c.tan_gamma;
  }
  const double denom = sxx + config_.alpha * n;
  if (denom <= 1e-12) return;
  m.w1 = (sxy + config_.alpha * sg) / denom;
  m.w0 = sy / n - m.w1 * xr;
}

double ModelMatchingTracker::median_spacing(double x_robot) const {
  // Nehme 2021 sec. 3.3: s = median of the differences of successive model intercepts, taken
  // at the robot's abscissa.
  std::vector<double> y;
  for (const auto& m : models_) y.push_back(m.w1 * x_robot + m.w0);
  std::sort(y.begin(), y.end());
  std::vector<double> d;
  for (std::size_t i = 1; i < y.size(); ++i) d.push_back(y[i] - y[i - 1]);
  const double fallback = common().default_row_spacing;
  if (d.empty()) return fallback;
  return std::max(median(std::move(d)), 0.25 * fallback);
}

ModelMatchingTracker::Centre ModelMatchingTracker::to_model(const core::RowLine& r, double& xa,
                                                            double& xb) const {
  const Eigen::Vector2d p = T_model_base_ * centre_of(r);
  const double heading = r.line.heading() + T_model_base_.theta;
  xa = (T_model_base_ * Eigen::Vector2d(r.x_min, r.line.y_at(r.x_min))).x();
  xb = (T_model_base_ * Eigen::Vector2d(r.x_max, r.line.y_at(r.x_max))).x();
  if (xa > xb) std::swap(xa, xb);
  return {p.x(), p.y(), std::tan(core::wrap_angle(heading)), r.centre_shift, r.half_width};
}

void ModelMatchingTracker::initialise(const core::RowObservation& obs) {
  models_.clear();
  contradictions_ = 0;
  T_model_base_ = core::Pose2();  // the model frame: the base at the first observation
  for (const auto& r : obs.rows) {
    if (!finite_row(r)) continue;
    double xa = 0.0, xb = 0.0;
    add_model(to_model(r, xa, xb), obs.stamp, true, xa, xb);
  }
}

bool ModelMatchingTracker::associate(const core::RowLine& r, double s, double stamp,
                                     std::vector<bool>& touched) {
  double xa = 0.0, xb = 0.0;
  const Centre c = to_model(r, xa, xb);
  const double max_dh = config_.max_assign_heading_deg * std::numbers::pi / 180.0;
  std::size_t best = models_.size();
  double d_best = 1e300;
  for (std::size_t j = 0; j < models_.size(); ++j) {
    const Model& m = models_[j];
    const double d = std::abs(m.w1 * c.x + m.w0 - c.y) / std::sqrt(1.0 + m.w1 * m.w1);
    if (d < d_best) d_best = d, best = j;
  }
  const bool aligned = best < models_.size() &&
                       std::abs(std::atan(models_[best].w1) - std::atan(c.tan_gamma)) < max_dh;
  if (aligned && d_best < config_.assign_zone * s) {  // assign
    Model& m = models_[best];
    m.buffer.push_back(c);
    while (static_cast<int>(m.buffer.size()) > config_.buffer_size) m.buffer.pop_front();
    m.last_seen = stamp, ++m.support, touched[best] = true;
    // The extent is the latest matched row's, as the other trackers keep it: a running union
    // only grows, and one detection reaching into the headland (a weed, a post on the row's line)
    // put the row end 2.5-4 m past the true one for the rest of the corridor (issue 11: Nehme's
    // pipeline on the narrow vineyard exited late and entered the wrong corridors).
    m.x_min = xa, m.x_max = xb;
    return true;
  }
  if ((!aligned || d_best > config_.reject_zone * s) &&
      static_cast<int>(models_.size()) < config_.max_models)  // new model
    add_model(c, stamp, false, xa, xb);
  return false;  // new model, or an outlier (rejected)
}

bool ModelMatchingTracker::correct(const core::RowObservation& obs, const core::Pose2&) {
  stamp_ = obs.stamp;
  if (models_.empty()) {
    initialise(obs);
    return !models_.empty();
  }
  const double s = median_spacing(T_model_base_.x);
  std::vector<bool> touched(models_.size(), false);
  bool assigned = false, sides_matched = true;
  for (std::size_t i = 0; i < obs.rows.size(); ++i) {
    if (!finite_row(obs.rows[i])) continue;
    const bool a = associate(obs.rows[i], s, obs.stamp, touched);
    assigned = assigned || a;
    if (!a && (static_cast<int>(i) == obs.left || static_cast<int>(i) == obs.right))
      sides_matched = false;
  }
  const bool good = obs.status == core::DetectionStatus::ok && obs.left >= 0 && obs.right >= 0;
  contradictions_ = good && !sides_matched ? contradictions_ + 1 : 0;
  if (contradictions_ >= config_.reinit_after) {  // latched onto wrong models: start again
    initialise(obs);
    return !models_.empty();
  }
  for (std::size_t j = 0; j < touched.size(); ++j)
    if (touched[j]) fit(models_[j]);
  std::erase_if(models_,
                [&](const Model& m) { return obs.stamp - m.last_seen > config_.model_timeout; });
  return assigned;
}

void ModelMatchingTracker::describe(RowTracking& out) const {
  std::vector<double> offsets;
  for (const auto& m : models_) {
    TrackedRow t;
    t.id = m.id;
    t.line_base = move_line(line_of({m.w1, m.w0}), T_model_base_);
    t.offset = t.line_base.y_at(0.0);
    t.heading = t.line_base.heading();
    t.x_min = m.x_min - T_model_base_.x;  // extent along the row, relative to the robot
    t.x_max = m.x_max - T_model_base_.x;
    t.support = static_cast<int>(m.buffer.size());
    t.age = stamp_ - m.created;
    t.last_seen = m.last_seen;
    // Centre line: the fitted line moved by the buffer's median centre shift away from the
    // robot (issue 10: the fit is the corridor-side face of an opaque canopy).
    std::vector<double> sh, hw;
    for (const auto& c : m.buffer) sh.push_back(c.shift), hw.push_back(c.half_width);
    const double cosine = std::max(std::abs(t.line_base.direction.x()), 1e-3);
    t.centre_offset = t.offset + (t.offset >= 0.0 ? 1.0 : -1.0) * median(sh) / cosine;
    t.half_width = median(std::move(hw));
    out.rows.push_back(t);
    if (m.initial || t.support >= config_.min_follow_support) offsets.push_back(t.centre_offset);
  }
  std::sort(out.rows.begin(), out.rows.end(),
            [](const TrackedRow& a, const TrackedRow& b) { return a.offset < b.offset; });
  for (std::size_t i = 0; i < out.rows.size(); ++i) {
    const auto& m = *std::find_if(models_.begin(), models_.end(),
                                  [&](const Model& k) { return k.id == out.rows[i].id; });
    if (!m.initial && out.rows[i].support < config_.min_follow_support) continue;
    if (out.rows[i].offset >= 0.0 && out.left < 0) out.left = static_cast<int>(i);
    if (out.rows[i].offset < 0.0) out.right = static_cast<int>(i);
  }
  // Nehme 2021 sec. 3.3's median of successive differences, over the centre lines of every
  // followable model, a difference spanning a missing row counted as two (issue 10). Two models
  // give one difference, one spacing or two (a followed row lost in a gap, the row beyond it
  // kept): then the base's estimate over the recent frames, which leaves such frames out.
  if (offsets.size() > 2) out.row_spacing = robust_spacing(std::move(offsets));
}

}  // namespace rownav::track
