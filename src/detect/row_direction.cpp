// The rows' heading as the sharpest projection direction (issue 11): see row_direction.hpp.
#include "rownav/detect/row_direction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Sum of squared counts of the returns' across-row coordinates in bins of width `bin`, each
// return split linearly between its two nearest bins (no aliasing as the angle steps).
double sharpness(const std::vector<Eigen::Vector2d>& pts, double angle, double bin, double reach,
                 std::vector<double>& hist) {
  const double inv = 1.0 / bin, nx = -std::sin(angle) * inv, ny = std::cos(angle) * inv;
  const double shift = reach * inv;
  hist.assign(std::size_t(2.0 * shift) + 2, 0.0);
  for (const auto& p : pts) {
    const double u = nx * p.x() + ny * p.y() + shift;
    const auto i = static_cast<std::size_t>(u);
    const double w = u - static_cast<double>(i);
    hist[i] += 1.0 - w;
    hist[i + 1] += w;
  }
  double s = 0.0;
  for (const double h : hist) s += h * h;
  return s;
}

// Sharpness at centre + k x step [deg] for k in [-n, n].
std::vector<double> sweep(const std::vector<Eigen::Vector2d>& pts, double centre, double step,
                          int n, double bin, double reach) {
  std::vector<double> score(std::size_t(2 * n + 1)), hist;
  for (int k = -n; k <= n; ++k)
    score[std::size_t(k + n)] = sharpness(pts, (centre + k * step) * kDeg, bin, reach, hist);
  return score;
}

}  // namespace

void RowDirectionConfig::validate() const {
  core::check_range(max_angle_deg, 0.5, 89.0, "max_angle_deg");
  core::check_range(step_deg, 0.01, 10.0, "step_deg");
  core::check_range(coarse_factor, 1, 20, "coarse_factor");
  core::check_positive(bin, "bin");
  core::check_positive(max_range, "max_range");
  core::check_positive(min_points, "min_points");
  core::check(min_contrast >= 1.0, "min_contrast", "must be >= 1");
  core::check_range(max_row_skew_deg, 0.1, 90.0, "max_row_skew_deg");
}

std::optional<double> row_direction(std::span<const Eigen::Vector2f> points,
                                    const RowDirectionConfig& c) {
  if (!c.enabled) return std::nullopt;
  std::vector<Eigen::Vector2d> pts;
  const double r2 = c.max_range * c.max_range;
  for (const auto& p : points)
    if (p.allFinite() && p.cast<double>().squaredNorm() <= r2) pts.push_back(p.cast<double>());
  if (static_cast<int>(pts.size()) < c.min_points) return std::nullopt;
  // Coarse to fine: a coarse_factor wider bin widens each row's peak by the same factor, so a
  // coarse_factor longer step cannot step over it; the fine search then covers one coarse step
  // each side of the coarse best.
  const double coarse_step = c.step_deg * c.coarse_factor;
  const int n = static_cast<int>(std::floor(c.max_angle_deg / coarse_step));
  const auto coarse = sweep(pts, 0.0, coarse_step, n, c.bin * c.coarse_factor, c.max_range);
  const double mean =
      std::accumulate(coarse.begin(), coarse.end(), 0.0) / static_cast<double>(coarse.size());
  const auto cb = std::max_element(coarse.begin(), coarse.end());
  if (!(*cb >= c.min_contrast * mean)) return std::nullopt;
  const int ci = static_cast<int>(cb - coarse.begin()) - n;
  // A maximum on the search's edge is no peak: the rows lie outside the searched arc, or the
  // frame holds no rows and the score merely rises towards one side.
  if (std::abs(ci) == n) return std::nullopt;
  const double centre = ci * coarse_step;
  const auto fine = sweep(pts, centre, c.step_deg, c.coarse_factor, c.bin, c.max_range);
  const auto i =
      static_cast<std::size_t>(std::max_element(fine.begin(), fine.end()) - fine.begin());
  double frac = 0.0;  // parabola through the best and its neighbours
  if (i > 0 && i + 1 < fine.size()) {
    const double a = fine[i - 1], b = fine[i], d = fine[i + 1], den = a - 2.0 * b + d;
    if (den < 0.0) frac = std::clamp(0.5 * (a - d) / den, -0.5, 0.5);
  }
  return (centre + (static_cast<double>(i) - c.coarse_factor + frac) * c.step_deg) * kDeg;
}

int keep_rows_along_direction(core::RowObservation& obs, std::span<const Eigen::Vector2f> points,
                              const RowDirectionConfig& c, double lookahead) {
  const auto heading = row_direction(points, c);
  if (!heading) return 0;
  const double tol = c.max_row_skew_deg * kDeg;
  const auto before = obs.rows.size();
  std::erase_if(obs.rows, [&](const core::RowLine& r) {
    return std::abs(std::remainder(r.heading - *heading, std::numbers::pi)) > tol;
  });
  const int dropped = static_cast<int>(before - obs.rows.size());
  if (dropped > 0) {
    obs.heading = std::numeric_limits<double>::quiet_NaN();  // recomputed from the rows kept
    finalize_observation(obs, lookahead);
  }
  return dropped;
}

}  // namespace rownav::detect
