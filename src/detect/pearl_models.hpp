#pragma once
// Private to src/detect: the model steps of PEARL / OPAL / RUBY (Malavazi 2018 sec. 2): the
// energy's data and smoothness terms, model sampling, re-fit (eq. (3)), elimination, label cost,
// merging and the parallelism constraint. Label 0 is the outlier label L_0, model j is label j + 1.
#include <Eigen/Core>
#include <optional>
#include <random>
#include <vector>

#include "rownav/core/line2.hpp"
#include "rownav/detect/alpha_expansion.hpp"
#include "rownav/detect/pearl.hpp"

namespace rownav::detect::pearl_detail {

using Points = std::vector<Eigen::Vector2f>;

/// One line model L_j.
struct Model {
  core::Line2 line;
  bool fresh = true;  ///< sampled this iteration, no points yet
};

/// Neighbourhood system N with w_pq = lambda exp(-|p-q|^2 / zeta^2) (Malavazi 2018 eq. (1), (2)).
void build_neighbourhood(const Points& pts, const PearlConfig& cfg,
                         std::vector<LabelingProblem::Edge>& edges);

/// Outlier data cost: the threshold, plus phi of eq. (4) for opal / ruby.
double outlier_data_cost(const PearlConfig& cfg);

/// Data costs D_p(0) = outlier cost, D_p(j + 1) = |p - L_j| (eq. (1)).
void fill_data_costs(const Points& pts, const std::vector<Model>& models, double outlier_cost,
                     LabelingProblem& problem);

/// Samples up to `count` models from pairs of the points `from` (sec. 2.1.2 step 1 / step 5),
/// never exceeding `max_models` in total.
void sample_models(const Points& pts, const std::vector<int>& from, int count, int max_models,
                   const PearlConfig& cfg, std::mt19937_64& rng, std::vector<Model>& models);

/// Support of each model (index j -> number of points with label j + 1).
std::vector<int> supports(const std::vector<int>& labels, std::size_t num_models);

/// Eq. (3): L'_j = argmin sum |p - L_j| over the model's points, by iteratively reweighted TLS.
void refit_models(const Points& pts, const std::vector<int>& labels, std::vector<Model>& models);

/// Removes the models flagged in `drop`, sends their points to L_0 and renumbers the labels.
void remove_models(const std::vector<bool>& drop, std::vector<int>& labels,
                   std::vector<Model>& models);

/// Model elimination (sec. 2.2.2): models with fewer than min_support points.
void eliminate_small(const PearlConfig& cfg, std::vector<int>& labels, std::vector<Model>& models);

/// Label cost h (Isack & Boykov 2012), greedily: drop a model when moving its points to their
/// best other label (model or L_0) raises the data cost by less than h. Empty models go too.
void apply_label_cost(const Points& pts, const PearlConfig& cfg, double outlier_cost,
                      std::vector<int>& labels, std::vector<Model>& models);

/// Merges models closer than merge_angle_deg / merge_distance (sec. 2.1.2 step 5, sec. 2.2.5
/// step 6), re-fitting the merged model on the union of the points.
void merge_models(const Points& pts, const PearlConfig& cfg, std::vector<int>& labels,
                  std::vector<Model>& models);

/// Parallelism constraint (sec. 2.2.4): R_j = omega D_j / psi_j, exclude R_j > threshold, keep
/// the lowest-R model when all would go. Fresh models (no points yet) are not judged.
void parallel_constraint(const Points& pts, const PearlConfig& cfg, std::vector<int>& labels,
                         std::vector<Model>& models);

/// Energy of the labelling plus the label costs of the non-empty models.
double total_energy(const LabelingProblem& problem, const std::vector<int>& labels,
                    std::size_t num_models, double label_cost);

}  // namespace rownav::detect::pearl_detail
