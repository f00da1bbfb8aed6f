// PEARL energy terms and model sampling (Malavazi 2018 sec. 2.1).
#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>

#include "pearl_models.hpp"

namespace rownav::detect::pearl_detail {

namespace {

struct CloudAdaptor {
  const Points* pts;
  std::size_t kdtree_get_point_count() const { return pts->size(); }
  float kdtree_get_pt(std::size_t i, std::size_t d) const { return (*pts)[i][static_cast<int>(d)]; }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};

using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>,
                                        CloudAdaptor, 2>;

double distance_to(const core::Line2& l, const Eigen::Vector2f& p) {
  return std::abs(l.signed_distance(p.cast<double>()));
}

}  // namespace

void build_neighbourhood(const Points& pts, const PearlConfig& cfg,
                         std::vector<LabelingProblem::Edge>& edges) {
  edges.clear();
  if (pts.size() < 2) return;
  const CloudAdaptor adaptor{&pts};
  KdTree tree(2, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  const std::size_t k = std::min(pts.size(), static_cast<std::size_t>(cfg.neighbours) + 1);
  std::vector<std::uint32_t> idx(k);
  std::vector<float> d2(k);
  const double r2 = cfg.neighbour_radius * cfg.neighbour_radius;
  const double z2 = cfg.zeta * cfg.zeta;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const std::size_t found = tree.knnSearch(pts[p].data(), k, idx.data(), d2.data());
    for (std::size_t i = 0; i < found; ++i) {
      const std::size_t q = idx[i];
      if (q == p || d2[i] > r2) continue;
      // Malavazi 2018 eq. (2), times lambda of eq. (1); each unordered pair once (below).
      edges.push_back({static_cast<int>(std::min(p, q)), static_cast<int>(std::max(p, q)),
                       cfg.smoothness * std::exp(-d2[i] / z2)});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const auto& a, const auto& b) { return a.p != b.p ? a.p < b.p : a.q < b.q; });
  edges.erase(std::unique(edges.begin(), edges.end(),
                          [](const auto& a, const auto& b) { return a.p == b.p && a.q == b.q; }),
              edges.end());
}

double outlier_data_cost(const PearlConfig& cfg) {
  // Malavazi 2018 eq. (4): phi |P(L_0)| is a per-outlier unary term.
  return cfg.outlier_cost + (cfg.variant == PearlVariant::pearl ? 0.0 : cfg.outlier_penalty);
}

void fill_data_costs(const Points& pts, const std::vector<Model>& models, double outlier_cost,
                     LabelingProblem& problem) {
  const int labels = static_cast<int>(models.size()) + 1;
  problem.num_points = static_cast<int>(pts.size());
  problem.num_labels = labels;
  problem.data_cost.resize(pts.size() * static_cast<std::size_t>(labels));
  for (std::size_t p = 0; p < pts.size(); ++p) {
    double* row = problem.data_cost.data() + p * static_cast<std::size_t>(labels);
    row[0] = outlier_cost;
    for (std::size_t j = 0; j < models.size(); ++j)
      row[j + 1] = distance_to(models[j].line, pts[p]);
  }
}

void sample_models(const Points& pts, const std::vector<int>& from, int count, int max_models,
                   const PearlConfig& cfg, std::mt19937_64& rng, std::vector<Model>& models) {
  if (from.size() < 2) return;
  std::uniform_int_distribution<std::size_t> pick(0, from.size() - 1);
  const double lo2 = cfg.sample_min * cfg.sample_min, hi2 = cfg.sample_max * cfg.sample_max;
  for (int m = 0; m < count && static_cast<int>(models.size()) < max_models; ++m) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const Eigen::Vector2f& a = pts[static_cast<std::size_t>(from[pick(rng)])];
      const Eigen::Vector2f& b = pts[static_cast<std::size_t>(from[pick(rng)])];
      const double d2 = (a - b).squaredNorm();
      if (d2 < lo2 || d2 > hi2) continue;
      models.push_back({core::Line2::through(a.cast<double>(), b.cast<double>()), true});
      break;
    }
  }
}

std::vector<int> supports(const std::vector<int>& labels, std::size_t num_models) {
  std::vector<int> s(num_models, 0);
  for (const int l : labels)
    if (l > 0 && static_cast<std::size_t>(l) <= num_models) ++s[static_cast<std::size_t>(l - 1)];
  return s;
}

double total_energy(const LabelingProblem& problem, const std::vector<int>& labels,
                    std::size_t num_models, double label_cost) {
  double e = labeling_energy(problem, labels);
  for (const int s : supports(labels, num_models))
    if (s > 0) e += label_cost;
  return e;
}

}  // namespace rownav::detect::pearl_detail
