// PEARL model re-fit and the OPAL / RUBY refinements (Malavazi 2018 sec. 2.1.2 steps 4-5, 2.2).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "pearl_models.hpp"

namespace rownav::detect::pearl_detail {

namespace {

double distance_to(const core::Line2& l, const Eigen::Vector2f& p) {
  return std::abs(l.signed_distance(p.cast<double>()));
}

/// Weighted total-least-squares line; nullopt when degenerate.
std::optional<core::Line2> weighted_tls(const Points& pts, const std::vector<int>& idx,
                                        const std::vector<double>& w) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double sw = 0.0;
  for (std::size_t i = 0; i < idx.size(); ++i) {
    mean += w[i] * pts[static_cast<std::size_t>(idx[i])].cast<double>();
    sw += w[i];
  }
  if (sw <= 0.0) return std::nullopt;
  mean /= sw;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < idx.size(); ++i) {
    const Eigen::Vector2d d = pts[static_cast<std::size_t>(idx[i])].cast<double>() - mean;
    cov += w[i] * d * d.transpose();
  }
  if (cov.trace() <= 1e-12 * sw) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Eigen::Vector2d dir = eig.eigenvectors().col(1);
  if (dir.x() < 0.0) dir = -dir;
  return core::Line2(mean, dir);
}

/// Eq. (3) by iteratively reweighted TLS (weights 1 / max(|d|, 1 cm)): minimises the sum of
/// distances rather than of their squares, as the paper writes it.
std::optional<core::Line2> fit_l1(const Points& pts, const std::vector<int>& idx) {
  std::vector<double> w(idx.size(), 1.0);
  auto line = weighted_tls(pts, idx, w);
  for (int it = 0; it < 3 && line; ++it) {
    for (std::size_t i = 0; i < idx.size(); ++i)
      w[i] = 1.0 / std::max(distance_to(*line, pts[static_cast<std::size_t>(idx[i])]), 0.01);
    if (auto next = weighted_tls(pts, idx, w)) line = next;
  }
  return line;
}

std::vector<std::vector<int>> members(const std::vector<int>& labels, std::size_t num_models) {
  std::vector<std::vector<int>> m(num_models);
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels[p] > 0) m[static_cast<std::size_t>(labels[p] - 1)].push_back(static_cast<int>(p));
  return m;
}

double slope(const core::Line2& l) {
  const double dx = l.direction.x();
  return std::abs(dx) < 1e-9 ? std::numeric_limits<double>::infinity() : l.direction.y() / dx;
}

}  // namespace

void refit_models(const Points& pts, const std::vector<int>& labels, std::vector<Model>& models) {
  const auto m = members(labels, models.size());
  for (std::size_t j = 0; j < models.size(); ++j) {
    if (m[j].size() < 2) continue;
    if (auto l = fit_l1(pts, m[j])) models[j].line = *l;
  }
}

void remove_models(const std::vector<bool>& drop, std::vector<int>& labels,
                   std::vector<Model>& models) {
  std::vector<int> new_label(models.size() + 1, 0);
  std::vector<Model> kept;
  for (std::size_t j = 0; j < models.size(); ++j) {
    if (drop[j]) continue;
    kept.push_back(models[j]);
    new_label[j + 1] = static_cast<int>(kept.size());
  }
  for (auto& l : labels) l = new_label[static_cast<std::size_t>(l)];
  models.swap(kept);
}

void eliminate_small(const PearlConfig& cfg, std::vector<int>& labels, std::vector<Model>& models) {
  const auto s = supports(labels, models.size());
  std::vector<bool> drop(models.size());
  for (std::size_t j = 0; j < models.size(); ++j) drop[j] = s[j] < cfg.min_support;
  remove_models(drop, labels, models);
}

void apply_label_cost(const Points& pts, const PearlConfig& cfg, double outlier_cost,
                      std::vector<int>& labels, std::vector<Model>& models) {
  // Data-cost increase of deleting label j: its points move to their best other label.
  std::vector<double> loss(models.size(), 0.0);
  std::vector<int> count(models.size(), 0);
  for (std::size_t p = 0; p < labels.size(); ++p) {
    if (labels[p] <= 0) continue;
    const auto j = static_cast<std::size_t>(labels[p] - 1);
    double alternative = outlier_cost;
    for (std::size_t k = 0; k < models.size(); ++k)
      if (k != j) alternative = std::min(alternative, distance_to(models[k].line, pts[p]));
    loss[j] += alternative - distance_to(models[j].line, pts[p]);
    ++count[j];
  }
  std::vector<bool> drop(models.size());
  for (std::size_t j = 0; j < models.size(); ++j)
    drop[j] = count[j] == 0 || loss[j] < cfg.label_cost;
  remove_models(drop, labels, models);
}

void merge_models(const Points& pts, const PearlConfig& cfg, std::vector<int>& labels,
                  std::vector<Model>& models) {
  const double max_angle = cfg.merge_angle_deg * std::numbers::pi / 180.0;
  std::vector<bool> drop(models.size(), false);
  for (std::size_t i = 0; i < models.size(); ++i) {
    for (std::size_t j = i + 1; j < models.size(); ++j) {
      if (drop[i] || drop[j]) continue;
      const auto& a = models[i].line;
      const auto& b = models[j].line;
      const double angle = std::acos(std::min(1.0, std::abs(a.direction.dot(b.direction))));
      const double across =
          std::max(std::abs(a.signed_distance(b.point)), std::abs(b.signed_distance(a.point)));
      if (angle > max_angle || across > cfg.merge_distance) continue;
      for (auto& l : labels)
        if (l == static_cast<int>(j) + 1) l = static_cast<int>(i) + 1;
      drop[j] = true;
      std::vector<int> idx;
      for (std::size_t p = 0; p < labels.size(); ++p)
        if (labels[p] == static_cast<int>(i) + 1) idx.push_back(static_cast<int>(p));
      if (idx.size() >= 2)
        if (auto l = fit_l1(pts, idx)) models[i].line = *l;
    }
  }
  remove_models(drop, labels, models);
}

void parallel_constraint(const Points& pts, const PearlConfig& cfg, std::vector<int>& labels,
                         std::vector<Model>& models) {
  const std::size_t n = models.size();
  std::vector<double> inertia(n, 0.0), ratio(n, std::numeric_limits<double>::infinity());
  std::vector<int> count(n, 0);
  for (std::size_t p = 0; p < labels.size(); ++p) {
    if (labels[p] <= 0) continue;
    const auto j = static_cast<std::size_t>(labels[p] - 1);
    inertia[j] += distance_to(models[j].line, pts[p]);  // D_j numerator
    ++count[j];
  }
  std::size_t best = n;
  for (std::size_t j = 0; j < n; ++j) {
    if (count[j] == 0) continue;
    inertia[j] /= count[j];
    int psi = 0;  // psi_j: models parallel to L_j, eq. (5)
    for (std::size_t k = 0; k < n; ++k)
      if (k != j && std::abs(slope(models[j].line) - slope(models[k].line)) < cfg.parallel_slope)
        ++psi;
    ratio[j] =
        psi > 0 ? cfg.parallel_omega * inertia[j] / psi : std::numeric_limits<double>::infinity();
    const bool better = best == n || ratio[j] < ratio[best] ||
                        (ratio[j] == ratio[best] && inertia[j] < inertia[best]);
    if (better) best = j;
  }
  std::vector<bool> drop(n, false);
  bool any_kept = false;
  for (std::size_t j = 0; j < n; ++j) {
    drop[j] = !models[j].fresh && count[j] > 0 && ratio[j] > cfg.parallel_max_ratio;
    any_kept = any_kept || !drop[j];
  }
  if (!any_kept && best < n) drop[best] = false;  // sec. 2.2.4: re-append the lowest R_j
  remove_models(drop, labels, models);
}

}  // namespace rownav::detect::pearl_detail
