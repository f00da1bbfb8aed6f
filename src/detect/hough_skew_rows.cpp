// Hough / iterative skewing: joint parallel-line refinement of the segments' rows (rownav) and
// the trunk-line offsets (trunk_offset.hpp).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rownav/detect/hough_skew.hpp"
#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// Principal direction (oriented towards +x) of a pooled within-row scatter matrix: the total-
/// least-squares direction shared by parallel lines.
Eigen::Vector2d principal_direction(const Eigen::Matrix2d& scatter) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  Eigen::Vector2d d = eig.eigenvectors().col(1);
  return d.x() < 0.0 ? Eigen::Vector2d(-d) : d;
}

/// Band half widths: the configured width, capped at 0.45 x the gap to the neighbouring rows so
/// that bands never overlap (and weeds mid-corridor stay out).
std::vector<double> band_limits(const std::vector<double>& centres, double band) {
  std::vector<double> w(centres.size(), band);
  for (std::size_t k = 0; k + 1 < centres.size(); ++k) {
    const double cap = 0.45 * (centres[k + 1] - centres[k]);
    w[k] = std::min(w[k], cap);
    w[k + 1] = std::min(w[k + 1], cap);
  }
  return w;
}

/// Puts every point into the band of the nearest centre when within its limit.
void assign(const std::vector<Eigen::Vector2f>& pts, const Eigen::Vector2d& n,
            const std::vector<double>& centres, const std::vector<double>& limits,
            std::vector<std::vector<Eigen::Vector2f>>& bands) {
  bands.resize(centres.size());
  for (auto& b : bands) b.clear();
  for (const auto& p : pts) {
    const double y = n.x() * p.x() + n.y() * p.y();
    const auto it = std::lower_bound(centres.begin(), centres.end(), y);
    std::size_t k = static_cast<std::size_t>(it - centres.begin());
    if (k == centres.size() || (k > 0 && y - centres[k - 1] < centres[k] - y)) --k;
    if (std::abs(y - centres[k]) <= limits[k]) bands[k].push_back(p);
  }
}

Eigen::Vector2d mean_of(const std::vector<Eigen::Vector2f>& pts) {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (const auto& p : pts) m += p.cast<double>();
  return pts.empty() ? m : Eigen::Vector2d(m / static_cast<double>(pts.size()));
}

/// Joint TLS of parallel lines, one per band: the common direction is the principal axis of the
/// pooled within-band scatter (rownav; Nehme 2021 regularises its regressions to the common
/// heading for the same reason). Returns false when no band has 2 points.
bool fit_parallel(const std::vector<std::vector<Eigen::Vector2f>>& bands, Eigen::Vector2d& d) {
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  int used = 0;
  for (const auto& b : bands) {
    if (b.size() < 2) continue;
    const Eigen::Vector2d m = mean_of(b);
    for (const auto& p : b) {
      const Eigen::Vector2d q = p.cast<double>() - m;
      scatter += q * q.transpose();
    }
    ++used;
  }
  if (used == 0 || scatter.trace() <= 1e-12) return false;
  d = principal_direction(scatter);
  return true;
}

/// RMS distance of a band to the line through its mean along d.
double band_rms(const std::vector<Eigen::Vector2f>& b, const Eigen::Vector2d& d) {
  if (b.empty()) return 0.0;
  const Eigen::Vector2d m = mean_of(b), n(-d.y(), d.x());
  double sq = 0.0;
  for (const auto& p : b) sq += std::pow(n.dot(p.cast<double>() - m), 2);
  return std::sqrt(sq / static_cast<double>(b.size()));
}

}  // namespace

void HoughSkewDetector::fit_rows(double gamma, const core::PointCloud* cloud,
                                 core::RowObservation& obs) {
  Eigen::Vector2d d(std::cos(gamma), -std::sin(gamma));  // row direction, heading = -gamma
  const Eigen::Vector2d d_hough = d;
  std::vector<double> centres;
  for (const auto& s : segments_) centres.push_back(s.position);
  const std::vector<double> limits0 = band_limits(centres, config_.band_half_width);
  std::vector<double> limits = limits0;
  const int iterations = config_.refine_rows ? config_.refine_iterations : 1;
  for (int it = 0; it < iterations; ++it) {
    assign(pts_, {-d.y(), d.x()}, centres, limits, bands_);
    if (!config_.refine_rows) break;
    Eigen::Vector2d d_new = d;
    // Keep the Hough heading when the bands are too degenerate to give a direction near it.
    const double max_turn = std::cos(3.0 * config_.heading_step_deg * kDeg);
    if (fit_parallel(bands_, d_new) && d_new.dot(d_hough) > max_turn) d = d_new;
    const Eigen::Vector2d n(-d.y(), d.x());
    for (std::size_t k = 0; k < centres.size(); ++k) {
      if (bands_[k].size() >= 2) centres[k] = n.dot(mean_of(bands_[k]));
      limits[k] = std::min(std::max(config_.trim_sigma * band_rms(bands_[k], d), 0.05), limits0[k]);
    }
    if (!std::is_sorted(centres.begin(), centres.end())) break;
  }
  obs.heading = config_.common_heading ? std::atan2(d.y(), d.x())
                                       : std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector2d n(-d.y(), d.x());
  // The canopy rows sit in front of the trunk lines: re-estimate their offsets from the trunk
  // band of the 3D cloud when there is one (trunk_offset.hpp).
  const bool trunks = cloud != nullptr && trunks_.collect(*cloud, d) > 0;
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const auto& b = bands_[k];
    if (b.size() < 2) continue;
    core::Line2 line(centres[k] * n, d);
    if (config_.refine_rows && !config_.common_heading) {
      const auto tls = fit_line_tls(b);
      if (!tls) continue;
      line = *tls;
    }
    auto row = make_row_line(line, b);
    if (row.x_max - row.x_min < config_.min_row_length || row.rms > config_.max_row_rms) continue;
    if (trunks) trunks_.apply(row);
    obs.rows.push_back(row);
  }
}

}  // namespace rownav::detect
