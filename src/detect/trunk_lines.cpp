#include "rownav/detect/trunk_lines.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rownav/detect/line_fit.hpp"
#include "rownav/detect/nearest_row.hpp"

namespace rownav::detect {

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// Trunk centres in the frame rotated by heading gamma: u along the rows, w across.
struct Rotated {
  double u = 0.0, w = 0.0;
  int points = 0;
};

void rotate(const std::vector<TrunkCentre>& trunks, double gamma, std::vector<Rotated>& out) {
  const double c = std::cos(gamma), s = std::sin(gamma);
  out.clear();
  for (const auto& t : trunks)
    out.push_back(
        {c * t.centre.x() + s * t.centre.y(), -s * t.centre.x() + c * t.centre.y(), t.points});
}

/// Heading vote: trunk pairs that line up along gamma (Gaussian kernel across it).
double vote(const std::vector<TrunkCentre>& trunks, double gamma, double sigma, double min_du,
            std::vector<Rotated>& r) {
  rotate(trunks, gamma, r);
  double score = 0.0;
  const double k = -0.5 / (sigma * sigma);
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t j = i + 1; j < r.size(); ++j) {
      if (std::abs(r[i].u - r[j].u) < min_du) continue;
      const double dw = r[i].w - r[j].w;
      score += std::exp(k * dw * dw);
    }
  return score;
}

/// Best heading over [lo, hi] in steps of `step`; `score` gets its vote.
double search(const std::vector<TrunkCentre>& trunks, double lo, double hi, double step,
              double sigma, double min_du, double& score, std::vector<Rotated>& buf) {
  double best = 0.5 * (lo + hi);
  score = -1.0;
  for (double g = lo; g <= hi + 1e-12; g += step) {
    const double v = vote(trunks, g, sigma, min_du, buf);
    if (v > score) score = v, best = g;
  }
  return best;
}

/// Groups of trunks (indices into r) whose across-row coordinates chain within `tol`.
std::vector<std::vector<std::size_t>> group(const std::vector<Rotated>& r, double tol) {
  std::vector<std::size_t> order(r.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return r[a].w < r[b].w; });
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || r[order[k]].w - r[order[k - 1]].w > tol) groups.emplace_back();
    groups.back().push_back(order[k]);
  }
  return groups;
}

/// Shared slope (in the rotated frame) of parallel lines through the groups (Lan 2021's
/// parallel lines by least squares, any number of rows).
double shared_slope(const std::vector<Rotated>& r, const std::vector<std::vector<std::size_t>>& g) {
  double sxy = 0.0, sxx = 0.0;
  for (const auto& idx : g) {
    double mu = 0.0, mw = 0.0;
    for (auto i : idx) mu += r[i].u, mw += r[i].w;
    mu /= static_cast<double>(idx.size());
    mw /= static_cast<double>(idx.size());
    for (auto i : idx) sxy += (r[i].u - mu) * (r[i].w - mw), sxx += (r[i].u - mu) * (r[i].u - mu);
  }
  return sxx > 1e-9 ? sxy / sxx : 0.0;
}

/// Canopy points above the trunk band within `window` of `line`.
int crown_points(const DetectorInput& in, const core::Line2& line, double z_min, double window) {
  int n = 0;
  const auto& pts = in.cloud->points;
  const bool use_h = in.heights != nullptr && in.heights->size() == pts.size();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const float h = use_h ? (*in.heights)[i] : pts[i].z;
    if (!(h > z_min)) continue;
    if (std::abs(line.signed_distance(Eigen::Vector2d(pts[i].x, pts[i].y))) <= window) ++n;
  }
  return n;
}

}  // namespace

void TrunkLinesConfig::validate() const {
  core::validate_nested(trunks, "trunks");
  core::check(heading_max_deg > heading_min_deg, "heading_max_deg", "must be > heading_min_deg");
  core::check_positive(heading_step_deg, "heading_step_deg");
  core::check_positive(fine_step_deg, "fine_step_deg");
  core::check_positive(line_tolerance, "line_tolerance");
  core::check(min_trunks >= 2, "min_trunks", "must be >= 2 (a line needs two trunks)");
  core::check_non_negative(min_row_length, "min_row_length");
  core::check_non_negative(min_pair_distance, "min_pair_distance");
  core::check_positive(crown_window, "crown_window");
  core::check_non_negative(min_crown_points, "min_crown_points");
  core::validate_nested(crowns, "crowns");
  core::check_non_negative(planar_min_length_per_start, "planar_min_length_per_start");
}

TrunkLinesDetector::TrunkLinesDetector(const TrunkLinesConfig& config)
    : config_((config.validate(), config)), finder_(config.trunks), crowns_(config.crowns) {}

core::RowObservation TrunkLinesDetector::detect(const DetectorInput& input) {
  core::RowObservation obs;
  obs.stamp = input.stamp;
  obs.heading = std::numeric_limits<double>::quiet_NaN();
  if (input.cloud != nullptr) {
    std::span<const float> h;
    if (input.heights != nullptr) h = *input.heights;
    trunk_rows(finder_.find(*input.cloud, h), input, obs);
  }
  if (config_.crown_fallback) add_crown_rows(input, obs);
  if (input.planar_scan)  // a short piece far ahead is a local object, not a row
    std::erase_if(obs.rows, [&](const core::RowLine& r) {
      return short_for_its_start(r.x_min, r.x_max, config_.planar_min_length_per_start);
    });
  finalize_observation(obs, config_.lookahead);
  return obs;
}

void TrunkLinesDetector::trunk_rows(const std::vector<TrunkCentre>& trunks,
                                    const DetectorInput& input, core::RowObservation& obs) {
  if (static_cast<int>(trunks.size()) < config_.min_trunks) return;
  std::vector<Rotated> r;  // one buffer for every heading tried
  const double sigma = 0.5 * config_.line_tolerance;
  const double coarse = config_.heading_step_deg * kDegToRad;
  double score = 0.0;
  double g =
      search(trunks, config_.heading_min_deg * kDegToRad, config_.heading_max_deg * kDegToRad,
             coarse, sigma, config_.min_pair_distance, score, r);
  g = search(trunks, g - coarse, g + coarse, config_.fine_step_deg * kDegToRad, sigma,
             config_.min_pair_distance, score, r);
  rotate(trunks, g, r);
  std::vector<std::vector<std::size_t>> rows;
  for (auto& idx : group(r, config_.line_tolerance)) {
    if (static_cast<int>(idx.size()) < config_.min_trunks) continue;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (auto i : idx) lo = std::min(lo, r[i].u), hi = std::max(hi, r[i].u);
    if (hi - lo >= config_.min_row_length) rows.push_back(std::move(idx));
  }
  if (rows.empty()) return;
  const double heading = g + std::atan(shared_slope(r, rows));
  const Eigen::Vector2d dir(std::cos(heading), std::sin(heading));
  std::vector<Eigen::Vector2f> support;
  for (const auto& idx : rows) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    int points = 0;
    support.clear();
    for (auto i : idx) {
      mean += trunks[i].centre;
      points += trunks[i].points;
      support.push_back(trunks[i].centre.cast<float>());
    }
    const core::Line2 line(mean / static_cast<double>(idx.size()), dir);
    if (config_.require_crown && crown_points(input, line, config_.trunks.z_max,
                                              config_.crown_window) < config_.min_crown_points)
      continue;  // a line of weeds or posts: no canopy above it
    core::RowLine row = make_row_line(line, support);
    row.support = points;
    row.centre_line = true;
    obs.rows.push_back(row);
  }
  if (!obs.rows.empty()) obs.heading = heading;
}

void TrunkLinesDetector::add_crown_rows(const DetectorInput& input, core::RowObservation& obs) {
  // Only without any trunk row (a hedge to the ground, a long gap on both sides, a 2D scan): a
  // crown face beside a trunk line would mix a face with a centre line in one corridor, and one
  // trunk line alone already gives the corridor (half the spacing from it).
  if (!obs.rows.empty()) return;
  const core::RowObservation crowns = crowns_.detect(input);
  obs.rows = crowns.rows;
  if (!obs.rows.empty()) obs.heading = crowns.heading;
}

}  // namespace rownav::detect
