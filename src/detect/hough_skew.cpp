#include "rownav/detect/hough_skew.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// Collects the finite x, y of the cloud (preferred, Nehme 2021 votes with the whole cloud) or
/// of the 2D points.
void gather(const DetectorInput& in, bool use_cloud, std::vector<Eigen::Vector2f>& out) {
  out.clear();
  if (use_cloud && in.cloud != nullptr && !in.cloud->empty()) {
    for (const auto& p : in.cloud->points)
      if (p.finite()) out.emplace_back(p.x, p.y);
    return;
  }
  for (const auto& p : in.points)
    if (std::isfinite(p.x()) && std::isfinite(p.y())) out.push_back(p);
}

/// Principal direction (oriented towards +x) of a pooled within-row scatter matrix: the total-
/// least-squares direction shared by parallel lines.
Eigen::Vector2d principal_direction(const Eigen::Matrix2d& scatter) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  Eigen::Vector2d d = eig.eigenvectors().col(1);
  return d.x() < 0.0 ? Eigen::Vector2d(-d) : d;
}

}  // namespace

void HoughSkewConfig::validate() const {
  using core::check;
  check(heading_min_deg < heading_max_deg, "heading_min_deg", "must be < heading_max_deg");
  core::check_range(heading_min_deg, -89.0, 89.0, "heading_min_deg");
  core::check_range(heading_max_deg, -89.0, 89.0, "heading_max_deg");
  core::check_positive(heading_step_deg, "heading_step_deg");
  core::check_positive(fine_step_deg, "fine_step_deg");
  check(y_min < y_max, "y_min", "must be < y_max");
  core::check_range(bins, 4, 100000, "bins");
  core::check_positive(min_points, "min_points");
  core::check_range(max_vote_points, 100, 100000000, "max_vote_points");
  core::check_non_negative(min_dispersion, "min_dispersion");
  core::check_positive(min_segment_bins, "min_segment_bins");
  core::check_positive(min_segment_points, "min_segment_points");
  core::check_positive(max_segment_width, "max_segment_width");
  core::check_positive(band_half_width, "band_half_width");
  core::check_range(valley_ratio, 0.0, 1.0, "valley_ratio");
  core::check_range(min_relative_support, 0.0, 1.0, "min_relative_support");
  core::check_non_negative(min_contrast, "min_contrast");
  core::check_range(refine_iterations, 1, 100, "refine_iterations");
  core::check_positive(trim_sigma, "trim_sigma");
  core::check_non_negative(min_row_length, "min_row_length");
  core::check_positive(max_row_rms, "max_row_rms");
}

HoughSkewDetector::HoughSkewDetector(const HoughSkewConfig& config) : config_(config) {
  config_.validate();
  const int n = static_cast<int>(
      std::floor((config_.heading_max_deg - config_.heading_min_deg) / config_.heading_step_deg +
                 1e-9)) + 1;
  for (int i = 0; i < n; ++i) {
    const double g = (config_.heading_min_deg + i * config_.heading_step_deg) * kDeg;
    coarse_gamma_.push_back(g);
    coarse_sin_.push_back(std::sin(g));
    coarse_cos_.push_back(std::cos(g));
  }
  hist_.resize(static_cast<std::size_t>(config_.bins));
}

double HoughSkewDetector::column(const std::vector<Eigen::Vector2f>& pts, double s, double c) {
  // Nehme 2021 eq. (1): y_rot = x sin(gamma) + y cos(gamma), one vote per point.
  std::fill(hist_.begin(), hist_.end(), 0);
  const float fs = static_cast<float>(s), fc = static_cast<float>(c);
  const float y0 = static_cast<float>(config_.y_min);
  const float inv = static_cast<float>(config_.bins / (config_.y_max - config_.y_min));
  const int nb = config_.bins;
  for (const auto& p : pts) {
    const float b = (p.x() * fs + p.y() * fc - y0) * inv;
    if (b >= 0.0f && b < static_cast<float>(nb)) ++hist_[static_cast<std::size_t>(b)];
  }
  double sum = 0.0, sq = 0.0;
  for (const int h : hist_) {
    sum += h;
    sq += double(h) * h;
  }
  const double mean = sum / nb;
  return sq / nb - mean * mean;
}

double HoughSkewDetector::best_gamma(double& variance) {
  // Nehme 2021 sec. 3.2.1: the heading maximises the variance of the y-histogram. rownav: the
  // search votes with an evenly strided subset of at most max_vote_points points.
  const std::vector<Eigen::Vector2f>* votes = &pts_;
  if (pts_.size() > static_cast<std::size_t>(config_.max_vote_points)) {
    const std::size_t stride = (pts_.size() + config_.max_vote_points - 1) / config_.max_vote_points;
    subset_.clear();
    for (std::size_t i = 0; i < pts_.size(); i += stride) subset_.push_back(pts_[i]);
    votes = &subset_;
  }
  variance = -1.0;
  double best = 0.0;
  for (std::size_t i = 0; i < coarse_gamma_.size(); ++i) {
    const double v = column(*votes, coarse_sin_[i], coarse_cos_[i]);
    if (v > variance) variance = v, best = coarse_gamma_[i];
  }
  if (config_.refine_heading) {  // rownav: fine pass +- one coarse step around the best column
    const double centre = best, step = config_.fine_step_deg * kDeg;
    const int k = static_cast<int>(std::ceil(config_.heading_step_deg / config_.fine_step_deg));
    for (int i = -k; i <= k; ++i) {
      const double g = centre + i * step;
      if (i == 0 || g < config_.heading_min_deg * kDeg || g > config_.heading_max_deg * kDeg)
        continue;
      const double v = column(*votes, std::sin(g), std::cos(g));
      if (v > variance) variance = v, best = g;
    }
  }
  variance = column(pts_, std::sin(best), std::cos(best));  // every point for the segmentation
  return best;
}

void HoughSkewDetector::split(int from, int to, int depth) {
  // rownav: a run above the threshold may hold several rows joined by weed / noise bins. It is
  // cut at every deep valley (below valley_ratio x the lower of the two neighbouring peaks) found
  // between the sub-runs above the run's own mean; each part is examined again.
  const auto h = [&](int i) { return double(hist_[static_cast<std::size_t>(i)]); };
  double mean = 0.0;
  for (int i = from; i < to; ++i) mean += h(i);
  mean /= (to - from);
  std::vector<int> cuts{from};
  int i = from;
  while (i < to && h(i) <= mean) ++i;
  while (i < to && depth < 6) {
    double peak = 0.0;
    while (i < to && h(i) > mean) peak = std::max(peak, h(i++));
    int valley = i;
    while (i < to && h(i) <= mean) valley = h(i) < h(valley) ? i : valley, ++i;
    if (i < to) {
      double next_peak = 0.0;
      for (int j = i; j < to && h(j) > mean; ++j) next_peak = std::max(next_peak, h(j));
      if (h(valley) < config_.valley_ratio * std::min(peak, next_peak)) cuts.push_back(valley);
    }
  }
  cuts.push_back(to);
  if (cuts.size() > 2) {
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) split(cuts[k], cuts[k + 1], depth + 1);
    return;
  }
  accept(from, to);
}

void HoughSkewDetector::accept(int from, int to) {
  const double bw = (config_.y_max - config_.y_min) / config_.bins;
  double votes = 0.0, moment = 0.0;
  int lo = to, hi = from;
  for (int i = from; i < to; ++i) {
    const double c = hist_[static_cast<std::size_t>(i)];
    if (c <= threshold_) continue;  // shoulders below the column mean are not the row
    lo = std::min(lo, i), hi = std::max(hi, i + 1);
    votes += c;
    moment += c * (config_.y_min + (i + 0.5) * bw);  // count-weighted mean (Nehme 2021)
  }
  if (hi - lo < config_.min_segment_bins || votes < config_.min_segment_points) return;
  if ((hi - lo) * bw > config_.max_segment_width) return;
  segments_.push_back({moment / votes, config_.y_min + lo * bw, config_.y_min + hi * bw,
                       static_cast<int>(votes)});
}

double HoughSkewDetector::lower_quartile() {
  int first = 0, last = config_.bins - 1;
  while (first < last && hist_[static_cast<std::size_t>(first)] == 0) ++first;
  while (last > first && hist_[static_cast<std::size_t>(last)] == 0) --last;
  quartile_.assign(hist_.begin() + first, hist_.begin() + last + 1);
  const auto q = quartile_.begin() + static_cast<long>(quartile_.size() / 4);
  std::nth_element(quartile_.begin(), q, quartile_.end());
  return *q;
}

void HoughSkewDetector::segment() {
  // Nehme 2021 sec. 3.2.3: bins above the column mean form segments; each segment's position is
  // the count-weighted mean of its bins.
  segments_.clear();
  threshold_ = 0.0;
  for (const int h : hist_) threshold_ += h;
  threshold_ /= config_.bins;
  for (int i = 0; i < config_.bins;) {
    if (hist_[static_cast<std::size_t>(i)] <= threshold_) { ++i; continue; }
    int j = i;
    while (j < config_.bins && hist_[static_cast<std::size_t>(j)] > threshold_) ++j;
    if (config_.split_segments) split(i, j, 0);
    else accept(i, j);
    i = j;
  }
  // rownav: weak segments (weed strips, far rows seen by a few points) are dropped, and so are
  // segments that do not stand out of the background (lower quartile of the occupied bins).
  int strongest = 0;
  for (const auto& s : segments_) strongest = std::max(strongest, s.votes);
  const double background = lower_quartile();
  const double bw = (config_.y_max - config_.y_min) / config_.bins;
  std::erase_if(segments_, [&](const Segment& s) {
    const double density = s.votes / std::max(1.0, (s.hi - s.lo) / bw);
    return s.votes < config_.min_relative_support * strongest ||
           density < config_.min_contrast * background;
  });
  std::sort(segments_.begin(), segments_.end(),
            [](const Segment& a, const Segment& b) { return a.position < b.position; });
}

namespace {

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

void HoughSkewDetector::fit_rows(double gamma, core::RowObservation& obs) {
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
    obs.rows.push_back(row);
  }
}

core::RowObservation HoughSkewDetector::detect(const DetectorInput& input) {
  core::RowObservation obs;
  obs.stamp = input.stamp;
  gather(input, config_.use_cloud, pts_);
  if (static_cast<int>(pts_.size()) < config_.min_points) return obs;
  double variance = 0.0;
  const double gamma = best_gamma(variance);
  double mean = 0.0;
  for (const int h : hist_) mean += h;
  mean /= config_.bins;
  // rownav: a row-less (uniform) cloud has a Poisson histogram, variance ~ mean.
  if (mean <= 0.0 || variance / mean < config_.min_dispersion) return obs;
  segment();
  if (segments_.empty()) return obs;
  fit_rows(gamma, obs);
  finalize_observation(obs);
  return obs;
}

}  // namespace rownav::detect
