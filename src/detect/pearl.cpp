#include "rownav/detect/pearl.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "pearl_models.hpp"
#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {

using namespace pearl_detail;

void PearlConfig::validate() const {
  core::validate_nested(nearest_row, "nearest_row");
  core::validate_nested(row_direction, "row_direction");
  core::check_positive(outlier_cost, "outlier_cost");
  core::check_non_negative(outlier_penalty, "outlier_penalty");
  core::check_non_negative(smoothness, "smoothness");
  core::check_positive(zeta, "zeta");
  core::check_positive(neighbours, "neighbours");
  core::check_positive(neighbour_radius, "neighbour_radius");
  core::check_non_negative(label_cost, "label_cost");
  core::check_non_negative(planar_label_cost, "planar_label_cost");
  core::check_positive(initial_models, "initial_models");
  core::check_non_negative(new_models, "new_models");
  core::check_range(max_models, 1, 256, "max_models");
  core::check_non_negative(sample_min, "sample_min");
  core::check(sample_max > sample_min, "sample_max", "must be > sample_min");
  core::check_positive(max_iterations, "max_iterations");
  core::check_positive(expansion_cycles, "expansion_cycles");
  core::check_positive(stall_iterations, "stall_iterations");
  core::check_range(min_support, 2, 100000, "min_support");
  core::check_range(merge_angle_deg, 0.0, 90.0, "merge_angle_deg");
  core::check_non_negative(merge_distance, "merge_distance");
  core::check_positive(parallel_slope, "parallel_slope");
  core::check_positive(parallel_omega, "parallel_omega");
  core::check_positive(parallel_max_ratio, "parallel_max_ratio");
  core::check_range(max_row_heading_deg, 0.0, 90.0, "max_row_heading_deg");
}

/// Per-instance buffers, reused between frames.
struct PearlState {
  Points pts;
  LabelingProblem problem;
  AlphaExpansion expansion;
  std::vector<int> labels;
};

namespace {

/// Indices of the points currently in L_0.
std::vector<int> outliers_of(const std::vector<int>& labels) {
  std::vector<int> out;
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels[p] == 0) out.push_back(static_cast<int>(p));
  return out;
}

/// Steps after an expansion that did lower the energy, in the order of the variant.
void update_models(const PearlConfig& cfg, const Points& pts, double outlier_cost,
                   std::mt19937_64& rng, std::vector<int>& labels, std::vector<Model>& models) {
  for (auto& m : models) m.fresh = false;
  if (cfg.variant == PearlVariant::pearl) {
    apply_label_cost(pts, cfg, outlier_cost, labels, models);
    refit_models(pts, labels, models);  // sec. 2.1.2 step 4, eq. (3)
    sample_models(pts, outliers_of(labels), cfg.new_models, cfg.max_models, cfg, rng, models);
    merge_models(pts, cfg, labels, models);  // step 5
    return;
  }
  eliminate_small(cfg, labels, models);  // sec. 2.2.2
  apply_label_cost(pts, cfg, outlier_cost, labels, models);
  // Fig. 5 step 4 (sec. 2.2.3), step 5 eq. (3), step 6.
  sample_models(pts, outliers_of(labels), cfg.new_models, cfg.max_models, cfg, rng, models);
  refit_models(pts, labels, models);
  if (cfg.variant == PearlVariant::ruby) parallel_constraint(pts, cfg, labels, models);
  merge_models(pts, cfg, labels, models);
}

/// The returned set L_{i-1} goes through the deterministic steps of its variant once more
/// (elimination, label cost, eq. (3), merge): eq. (1) alone prefers two lines along
/// the edges of a wide canopy and short fragments sharing a row; the merge and the label cost
/// make them one row (sec. 2.1.3).
void finish_models(const PearlConfig& cfg, const Points& pts, double outlier_cost,
                   std::vector<int>& labels, std::vector<Model>& models) {
  for (auto& m : models) m.fresh = false;
  if (cfg.variant != PearlVariant::pearl) eliminate_small(cfg, labels, models);
  apply_label_cost(pts, cfg, outlier_cost, labels, models);
  refit_models(pts, labels, models);
  // No parallelism pass here: on corn_rows_2d it removed 10 % of the labelled rows (two visible
  // rows that disagree in slope leave psi_j = 0); the paper applies it inside the loop only.
  merge_models(pts, cfg, labels, models);
}

/// The reported rows: every model with enough support heading along the robot.
core::RowObservation make_observation(const PearlConfig& cfg, const Points& pts, double stamp,
                                      const std::vector<int>& labels,
                                      const std::vector<Model>& models) {
  core::RowObservation obs;
  obs.stamp = stamp;
  obs.heading = std::numeric_limits<double>::quiet_NaN();
  const double max_heading = cfg.max_row_heading_deg * std::numbers::pi / 180.0;
  std::vector<Eigen::Vector2f> support;
  for (std::size_t j = 0; j < models.size(); ++j) {
    support.clear();
    for (std::size_t p = 0; p < labels.size(); ++p)
      if (labels[p] == static_cast<int>(j) + 1) support.push_back(pts[p]);
    if (static_cast<int>(support.size()) < cfg.min_support) continue;
    const auto line = fit_line_tls(support);
    if (!line) continue;
    const core::RowLine row = make_row_line(*line, support);
    if (std::abs(row.heading) > max_heading) continue;
    obs.rows.push_back(row);
  }
  finalize_observation(obs, cfg.lookahead);
  return obs;
}

}  // namespace

PearlDetector::PearlDetector(const PearlConfig& config)
    : config_(config), planar_config_(config), state_(std::make_unique<PearlState>()) {
  config_.validate();
  planar_config_.label_cost = config_.planar_label_cost;
}

PearlDetector::~PearlDetector() = default;

std::string_view PearlDetector::name() const {
  return core::enum_name(config_.variant);
}

core::RowObservation PearlDetector::detect(const DetectorInput& input) {
  PearlState& st = *state_;
  const PearlConfig& cfg = input.planar_scan ? planar_config_ : config_;
  st.pts.clear();
  for (const auto& p : input.points)
    if (std::isfinite(p.x()) && std::isfinite(p.y())) st.pts.push_back(p);
  last_iterations_ = 0;
  last_energy_ = 0.0;
  if (static_cast<int>(st.pts.size()) < cfg.min_support) {
    core::RowObservation obs;
    obs.stamp = input.stamp;
    return obs;  // no_rows
  }
  std::mt19937_64 rng(cfg.seed);
  const double outlier_cost = outlier_data_cost(cfg);
  build_neighbourhood(st.pts, cfg, st.problem.edges);
  std::vector<Model> models;
  std::vector<int> all(st.pts.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  sample_models(st.pts, all, cfg.initial_models, cfg.max_models, cfg, rng, models);  // step 1
  st.labels.assign(st.pts.size(), 0);
  double best_energy = std::numeric_limits<double>::infinity();
  std::vector<Model> best_models;
  std::vector<int> best_labels(st.labels);
  int stalled = 0;
  for (int it = 0; it < cfg.max_iterations && !models.empty(); ++it) {
    fill_data_costs(st.pts, models, outlier_cost, st.problem);
    st.expansion.run(st.problem, st.labels, cfg.expansion_cycles);  // step 2
    const double e = total_energy(st.problem, st.labels, models.size(), cfg.label_cost);
    ++last_iterations_;
    if (e < best_energy - 1e-9) {
      stalled = 0;
      best_energy = e;
      best_models = models;
      best_labels = st.labels;
    } else if (++stalled >= cfg.stall_iterations) {
      break;  // step 3: return the best (previous) models
    }
    update_models(cfg, st.pts, outlier_cost, rng, st.labels, models);
  }
  last_energy_ = std::isfinite(best_energy) ? best_energy : 0.0;
  finish_models(cfg, st.pts, outlier_cost, best_labels, best_models);
  auto obs = make_observation(cfg, st.pts, input.stamp, best_labels, best_models);
  // Issue 11: a short fit off the rows' heading wins the pick (row_direction.hpp); a sparse near
  // row pays its label cost poorly (nearest_row.hpp).
  if (input.planar_scan) keep_rows_along_direction(obs, st.pts, cfg.row_direction, cfg.lookahead);
  step_in_nearest_rows(obs, st.pts, cfg.nearest_row, !input.planar_scan, cfg.lookahead);
  return obs;
}

}  // namespace rownav::detect
