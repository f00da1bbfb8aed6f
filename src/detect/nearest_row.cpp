// The nearest row on each side of a 2D scan (issue 11): see nearest_row.hpp for why.
#include "rownav/detect/nearest_row.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {
namespace {

struct Frame {
  Eigen::Vector2d d, n;  // along the rows, left normal
};

// Signed distance of a reported row from the robot, across the rows (its offset at x = 0 x cos).
double across(const core::RowLine& r, const Frame& f) {
  return f.n.dot(r.line.point);
}

// A return between the two reported rows: across (u) and along (t) the rows.
struct Across {
  double u, t;
  Eigen::Vector2f p;
};

// The densest band of half width b among the returns `in` (sorted by u) lying across between lo
// and hi; nullopt when none passes the support, length, direction and contrast tests.
std::optional<NearBand> densest_band(const std::vector<Across>& in, double lo, double hi, double b,
                                     double interior_width, const Frame& f,
                                     const NearestRowConfig& c, int inner_points) {
  const auto first = std::lower_bound(in.begin(), in.end(), lo,
                                      [](const Across& a, double v) { return a.u <= v; });
  const auto last =
      std::lower_bound(first, in.end(), hi, [](const Across& a, double v) { return a.u < v; });
  const std::size_t i0 = std::size_t(first - in.begin()), i1 = std::size_t(last - in.begin());
  std::size_t best_i = i0, best_n = 0;
  for (std::size_t i = i0, j = i0; i < i1; ++i) {
    j = std::max(j, i);
    while (j + 1 < i1 && in[j + 1].u - in[i].u <= 2.0 * b) ++j;
    if (j - i + 1 > best_n) best_n = j - i + 1, best_i = i;
  }
  if (static_cast<int>(best_n) < c.min_points) return std::nullopt;
  NearBand band;
  double t_min = 1e30, t_max = -1e30, sum = 0.0;
  std::vector<double> mags;
  for (std::size_t k = best_i; k < best_i + best_n; ++k) {
    t_min = std::min(t_min, in[k].t), t_max = std::max(t_max, in[k].t);
    sum += in[k].u;
    mags.push_back(std::abs(in[k].u));
    band.points.push_back(in[k].p);
  }
  if (t_max - t_min < c.min_length) return std::nullopt;
  // A row seen from the robot runs from where it comes into view to the range limit; a short
  // piece far ahead is a local object (min_length_per_start).
  if (short_for_its_start(t_min, t_max, c.min_length_per_start)) return std::nullopt;
  const auto line = fit_line_tls(band.points);
  if (!line ||
      std::abs(line->direction.dot(f.n)) > std::sin(c.max_angle_deg * std::numbers::pi / 180.0))
    return std::nullopt;
  // Contrast against the rest of the corridor between the reported rows, over the band's reach
  // along the rows: a skipped row stands alone in an empty corridor, while a line crossing it
  // (the scan plane meeting the ground ahead) or clutter spreads over the whole width.
  int rest = 0;
  for (std::size_t k = 0; k < in.size(); ++k)
    if ((k < best_i || k >= best_i + best_n) && in[k].t >= t_min && in[k].t <= t_max) ++rest;
  const double rest_width = std::max(interior_width - 2.0 * b, 2.0 * b);
  if (best_n / (2.0 * b) < c.min_contrast * rest / rest_width) return std::nullopt;
  band.offset = sum / static_cast<double>(best_n);
  const auto k = std::min<std::size_t>(mags.size() - 1, std::size_t(std::max(1, inner_points) - 1));
  std::nth_element(mags.begin(), mags.begin() + static_cast<long>(k), mags.end());
  band.inner = std::copysign(mags[k], band.offset);
  return band;
}

}  // namespace

void NearestRowConfig::validate() const {
  core::check_positive(band_half_width, "band_half_width");
  core::check_range(band_fraction, 0.01, 0.5, "band_fraction");
  core::check_range(min_gap_fraction, 0.05, 0.95, "min_gap_fraction");
  core::check_positive(min_points, "min_points");
  core::check_non_negative(min_length, "min_length");
  core::check_range(max_angle_deg, 0.5, 45.0, "max_angle_deg");
  core::check_non_negative(min_contrast, "min_contrast");
  core::check_non_negative(min_length_per_start, "min_length_per_start");
}

std::array<std::optional<NearBand>, 2> find_nearer_rows(const core::RowObservation& obs,
                                                        std::span<const Eigen::Vector2f> points,
                                                        double heading, const NearestRowConfig& c,
                                                        int inner_points) {
  std::array<std::optional<NearBand>, 2> out;
  if (!c.enabled || obs.left < 0 || obs.right < 0 || !std::isfinite(heading)) return out;
  const Frame f{{std::cos(heading), std::sin(heading)}, {-std::sin(heading), std::cos(heading)}};
  const double ul = across(obs.rows[std::size_t(obs.left)], f);
  const double ur = across(obs.rows[std::size_t(obs.right)], f);
  const double width = ul - ur;
  if (!(width > 0.0) || !std::isfinite(width)) return out;
  // Thresholds scale with the corridor measured in this frame, not with one field's spacing.
  const double b = std::min(c.band_half_width, c.band_fraction * width);
  const double gap = c.min_gap_fraction * width;
  // The corridor interior: between the reported rows, clear of their own bands.
  std::vector<Across> in;
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    const double u = f.n.dot(p.cast<double>());
    if (u > ur + 2.0 * b && u < ul - 2.0 * b) in.push_back({u, f.d.dot(p.cast<double>()), p});
  }
  std::sort(in.begin(), in.end(), [](const Across& a, const Across& q) { return a.u < q.u; });
  const double interior = width - 4.0 * b;
  if (ul - gap > 0.0) out[0] = densest_band(in, 0.0, ul - gap, b, interior, f, c, inner_points);
  if (ur + gap < 0.0) out[1] = densest_band(in, ur + gap, 0.0, b, interior, f, c, inner_points);
  return out;
}

int step_in_nearest_rows(core::RowObservation& obs, std::span<const Eigen::Vector2f> points,
                         const NearestRowConfig& c, bool not_planar, double lookahead,
                         bool replace) {
  if (!c.enabled || (not_planar && !c.on_clouds)) return 0;
  int stepped = 0;
  for (int pass = 0; pass < 2; ++pass) {  // a second pass catches a row two spacings in
    const double heading = obs.corridor ? obs.corridor->heading : obs.heading;
    const auto bands = find_nearer_rows(obs, points, heading, c);
    if (!bands[0] && !bands[1]) break;
    const Eigen::Vector2d d(std::cos(heading), std::sin(heading));
    const std::array<int, 2> idx{obs.left, obs.right};
    for (int side = 0; side < 2; ++side) {
      const auto& band = bands[std::size_t(side)];
      if (!band) continue;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const auto& p : band->points) mean += p.cast<double>();
      mean /= static_cast<double>(band->points.size());
      core::RowLine row = make_row_line(core::Line2(mean, d), band->points);
      if (replace)
        obs.rows[std::size_t(idx[std::size_t(side)])] = row;
      else
        obs.rows.push_back(row);
      ++stepped;
    }
    finalize_observation(obs, lookahead);
  }
  return stepped;
}

}  // namespace rownav::detect
