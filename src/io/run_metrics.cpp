// Run metrics against the ground truth (docs/summary_json.md).
#include "rownav/io/run_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rownav::io {

std::optional<double> percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::nullopt;
  std::sort(v.begin(), v.end());
  const auto i =
      static_cast<std::size_t>(std::clamp(q * (v.size() - 1) + 0.5, 0.0, v.size() - 1.0));
  return v[i];
}

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

/// Running mean / RMS / max of |x|, and mean / std of x.
struct Stats {
  double sum = 0.0, sum_abs = 0.0, sum_sq = 0.0, max_abs = 0.0, min = 1e300, max = -1e300;
  int n = 0;
  void add(double x) {
    if (!std::isfinite(x)) return;
    sum += x, sum_abs += std::abs(x), sum_sq += x * x, ++n;
    max_abs = std::max(max_abs, std::abs(x)), min = std::min(min, x), max = std::max(max, x);
  }
  std::optional<double> mean() const { return n ? std::optional(sum / n) : std::nullopt; }
  std::optional<double> mean_abs() const { return n ? std::optional(sum_abs / n) : std::nullopt; }
  std::optional<double> rms() const {
    return n ? std::optional(std::sqrt(sum_sq / n)) : std::nullopt;
  }
  std::optional<double> maxabs() const { return n ? std::optional(max_abs) : std::nullopt; }
  std::optional<double> lo() const { return n ? std::optional(min) : std::nullopt; }
  std::optional<double> hi() const { return n ? std::optional(max) : std::nullopt; }
  std::optional<double> stddev() const {
    if (n < 2) return std::nullopt;
    const double m = sum / n;
    return std::sqrt(std::max(0.0, sum_sq / n - m * m));
  }
};

/// Consecutive in-row lane samples of one true corridor.
std::vector<std::pair<int, std::vector<const RunSample*>>> corridor_runs(const RunResult& run) {
  std::vector<std::pair<int, std::vector<const RunSample*>>> out;
  bool open = false;
  for (const auto& s : run.samples) {
    const bool in = s.state == navigate::NavState::in_row && s.place == sim::Place::lane;
    if (!in) {
      open = false;
      continue;
    }
    if (!open || out.back().first != s.corridor) out.push_back({s.corridor, {}});
    open = true;
    out.back().second.push_back(&s);
  }
  return out;
}

/// Corridors driven end to end, in the order driven (ground truth): consecutive lane samples of
/// one corridor, whatever the navigator's state, covering at least kServedCoverage of its
/// centre line. A corridor left half-way (a false row end) is not served.
constexpr double kServedCoverage = 0.95;
std::vector<int> full_passes(const RunResult& run, const sim::FieldTruth& truth, int block) {
  std::vector<int> out;
  int k = -1;
  double lo = 0.0, hi = 0.0, length = 0.0;
  auto close = [&] {
    if (k >= 0 && length > 0.0 &&
        std::clamp(hi, 0.0, length) - std::clamp(lo, 0.0, length) >= kServedCoverage * length)
      out.push_back(k);
  };
  for (const auto& s : run.samples) {
    const int c = s.place == sim::Place::lane ? s.corridor : -1;
    if (c != k) close(), k = c, lo = 1e300, hi = -1e300, length = 0.0;
    if (k < 0) continue;
    const auto p =
        sim::project_on_polyline(truth.corridor_centre(block, k), s.T_world_base.translation());
    lo = std::min(lo, p.along), hi = std::max(hi, p.along), length = p.length;
  }
  close();
  return out;
}

void fill_corridors(const RunResult& run, const sim::FieldTruth& truth, int block, RunSummary& r) {
  Stats lat, head, ratio;
  for (const auto& [k, samples] : corridor_runs(run)) {
    CorridorMetrics c;
    c.corridor = k;
    Stats cl, ch;
    std::vector<Eigen::Vector2d> driven;
    for (const RunSample* s : samples) {
      cl.add(s->lateral_error), ch.add(s->heading_error * kDeg);
      lat.add(s->lateral_error), head.add(s->heading_error * kDeg);
      driven.push_back(s->T_world_base.translation());
    }
    const auto& centre = truth.corridor_centre(block, k);
    const auto pr = path_length_ratio(driven, centre);
    if (!pr) continue;  // a brush through a lane, not a served corridor
    c.path_length_ratio = *pr;
    c.lateral_rmse = *cl.rms(), c.mean_displacement = *cl.mean_abs();
    c.max_displacement = *cl.maxabs(), c.heading_rmse_deg = *ch.rms();
    ratio.add(c.path_length_ratio);
    r.per_corridor.push_back(c);
  }
  r.in_row_mean_displacement = lat.mean_abs(), r.in_row_max_displacement = lat.maxabs();
  r.in_row_lateral_rmse = lat.rms(), r.in_row_heading_rmse_deg = head.rms();
  r.path_length_ratio_mean = ratio.mean(), r.path_length_ratio_max = ratio.hi();
  r.path_length_ratio_min = ratio.lo();
  const std::vector<int> served = full_passes(run, truth, block);
  r.corridors_served = static_cast<int>(served.size());
  r.corridors_in_order = !served.empty() && served.size() <= run.order.size() &&
                         std::equal(served.begin(), served.end(), run.order.begin());
}

void fill_tracking(const RunResult& run, RunSummary& r) {
  Stats lat, head, slope, icpt, width;
  std::vector<double> lat_ms;
  for (const auto& f : run.frames) {
    lat_ms.push_back(f.latency * 1e3);
    if (!f.in_row) continue;
    if (f.status == track::TrackStatus::lost) ++r.tracking_lost_in_row;
    if (f.status != track::TrackStatus::tracking) continue;
    lat.add(f.lateral_error - f.true_lateral_error);
    head.add((f.heading_error - f.true_heading_error) * kDeg);
    for (double e : f.slope_errors) slope.add(e);
    for (double e : f.intercept_errors) icpt.add(e);
    if (f.row_spacing > 0.0) width.add(f.row_spacing);
  }
  r.frame_latency_median_ms = percentile(lat_ms, 0.5);
  r.frame_latency_p99_ms = percentile(lat_ms, 0.99);
  r.track_lateral_error_rmse = lat.rms(), r.track_lateral_error_max = lat.maxabs();
  r.track_heading_error_rmse_deg = head.rms(), r.track_heading_error_max_deg = head.maxabs();
  r.line_slope_error_mean = slope.mean(), r.line_slope_error_std = slope.stddev();
  r.line_intercept_error_mean = icpt.mean(), r.line_intercept_error_std = icpt.stddev();
  r.corridor_width_mean = width.mean(), r.corridor_width_max = width.hi();
  r.corridor_width_min = width.lo();
}

/// The true row ends of a block: each row's two ends (its last plant or end post) with the
/// outward direction there (the row's last segment, pointing off the row).
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> true_row_ends(const sim::FieldTruth& truth,
                                                                       int block) {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> out;
  for (int row : truth.block_rows(block)) {
    const auto& line = truth.field().rows[static_cast<std::size_t>(row)].polyline;
    const std::size_t n = line.size();
    if (n < 2) continue;
    out.emplace_back(line.front(), (line.front() - line[1]).normalized());
    out.emplace_back(line.back(), (line.back() - line[n - 2]).normalized());
  }
  return out;
}

/// The nearest of `ends` to `p`, with p's offset along the row (+ past the end) and beside it.
RowEndRecord nearest_end(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& ends,
                         const Eigen::Vector2d& p) {
  RowEndRecord best;
  best.estimate = p;
  best.error = 1e300;
  for (const auto& [end, out] : ends) {
    const double d = (end - p).norm();
    if (d >= best.error) continue;
    const Eigen::Vector2d q = p - end;
    best.truth = end, best.error = d;
    best.along = q.dot(out), best.across = out.x() * q.y() - out.y() * q.x();
  }
  return best;
}

/// Each estimated row end against the nearest true one of the block: the distance, and the
/// offset along the row, + past the end into the headland, - short of it inside the row.
/// And 003 Table II: the turn frames' row-end points against the nearest true row end.
void fill_row_ends(const RunResult& run, const sim::FieldTruth& truth, int block, RunSummary& r) {
  const auto truth_ends = true_row_ends(truth, block);
  Stats ends, along, turn;
  for (const auto& p : run.row_ends_world) {
    const RowEndRecord e = nearest_end(truth_ends, p);
    ends.add(e.error);
    along.add(e.along);
    r.row_ends.push_back(e);
  }
  r.row_end_error_mean = ends.mean(), r.row_end_error_max = ends.hi();
  r.row_end_along_mean = along.mean();
  // A point nearer another point than to any true end by half their spacing is no row end.
  double gap = 1e300;
  for (std::size_t i = 0; i < truth_ends.size(); ++i)
    for (std::size_t j = i + 1; j < truth_ends.size(); ++j)
      gap = std::min(gap, (truth_ends[i].first - truth_ends[j].first).norm());
  // Per frame (one stamp), each true row end against the frame's nearest end point (003: "the
  // distance from the real pole centre to the end point detected"): a vine cluster a metre
  // into the row is no detection of the pole, only counted as a point.
  const auto& pts = run.turn_row_ends_world;
  for (std::size_t i = 0; i < pts.size();) {
    std::size_t j = i;
    while (j < pts.size() && pts[j].stamp == pts[i].stamp) ++j;
    for (const auto& [end, out] : truth_ends) {
      double best = 1e300;
      for (std::size_t k = i; k < j; ++k) best = std::min(best, (pts[k].world - end).norm());
      if (best <= 0.5 * gap) turn.add(best);
    }
    for (std::size_t k = i; k < j; ++k)
      r.turn_row_end_spurious += nearest_end(truth_ends, pts[k].world).error > 0.5 * gap;
    i = j;
  }
  r.turn_row_end_points = turn.n;
  r.turn_row_end_error_mean = turn.mean(), r.turn_row_end_error_max = turn.hi();
  r.turn_row_end_error_min = turn.lo();
}

}  // namespace

std::optional<double> path_length_ratio(const std::vector<Eigen::Vector2d>& driven,
                                        const std::vector<Eigen::Vector2d>& reference) {
  if (driven.size() < 2 || reference.size() < 2) return std::nullopt;
  double length = 0.0;
  for (std::size_t i = 1; i < driven.size(); ++i) length += (driven[i] - driven[i - 1]).norm();
  const auto a = sim::project_on_polyline(reference, driven.front());
  const auto b = sim::project_on_polyline(reference, driven.back());
  const double covered =
      std::abs(std::clamp(b.along, 0.0, b.length) - std::clamp(a.along, 0.0, a.length));
  if (covered < 1.0) return std::nullopt;
  // Only the part over the reference counts: scale the driven length by the covered fraction.
  const double span = std::abs(b.along - a.along);
  return length * (covered / std::max(span, covered)) / covered;
}

RunSummary summarize(const RunResult& run, const sim::FieldTruth& truth, int block) {
  RunSummary r;
  r.mission_done = run.final_state == navigate::NavState::done;
  r.safe_stop = run.final_state == navigate::NavState::safe_stop;
  r.stop_reason = std::string(core::enum_name(run.stop_reason));
  r.corridors_planned = static_cast<int>(run.order.size());
  r.turns = run.turns;
  for (const auto& [planned, actual] : run.entries)
    (planned == actual ? r.correct_entries : r.wrong_entries)++;
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const auto& s = run.samples[i];
    r.collision = r.collision || s.collision;
    r.plants_crushed = std::max(r.plants_crushed, s.plants_crushed);
    r.speed_max = std::max(r.speed_max, std::abs(s.twist.v));
    if (i > 0)
      r.distance +=
          (s.T_world_base.translation() - run.samples[i - 1].T_world_base.translation()).norm();
  }
  fill_corridors(run, truth, block, r);
  r.crushes = run.crushes;
  fill_tracking(run, r);
  fill_row_ends(run, truth, block, r);
  r.place = place_metrics(run, truth, block);
  r.sim_time = run.sim_time, r.wall_time = run.wall_time;
  r.odometry_alpha = run.odometry_alpha;
  r.odometry_scale_samples = run.odometry_scale_samples;
  // Every planned corridor driven end to end in the planned order (the navigator's own count,
  // run.served, could include a corridor left early on a false row end).
  r.success = r.mission_done && !r.collision && !r.safe_stop && r.wrong_entries == 0 &&
              r.corridors_served == r.corridors_planned && r.corridors_in_order;
  return r;
}

}  // namespace rownav::io
