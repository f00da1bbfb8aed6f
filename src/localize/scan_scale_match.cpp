#include "rownav/localize/scan_scale_match.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>

namespace rownav::localize {

void ScanScaleMatchConfig::validate() const {
  core::check_positive(resolution, "resolution");
  core::check(truncation > resolution, "truncation", "must be > resolution");
  core::check_range(max_scale_error, 0.01, 0.9, "max_scale_error");
  core::check_positive(min_contrast, "min_contrast");
  core::check_range(min_overlap, 0.0, 1.0, "min_overlap");
  core::check_positive(min_points, "min_points");
  core::check_range(ambiguity, 0.0, 1.0, "ambiguity");
  core::check_positive(max_range, "max_range");
}

namespace {

// The first frame's (finite, near) points: bounding box and farthest range.
struct Bounds {
  Eigen::Vector2d lo, hi;
  double range = 0.0;
};

Bounds bounds_of(const std::vector<Eigen::Vector2f>& points) {
  Bounds b;
  b.lo.setConstant(std::numeric_limits<double>::max());
  b.hi = -b.lo;
  for (const auto& p : points) {
    b.lo = b.lo.cwiseMin(p.cast<double>());
    b.hi = b.hi.cwiseMax(p.cast<double>());
    b.range = std::max(b.range, static_cast<double>(p.norm()));
  }
  return b;
}

// Squared distance to the nearest first-frame point, truncated, on a grid over those points.
class DistanceField {
 public:
  DistanceField(const std::vector<Eigen::Vector2f>& points, const Bounds& b, double res,
                double trunc)
      : res_(res), max_(trunc * trunc) {
    origin_ = b.lo.array() - trunc;
    nx_ = static_cast<int>(std::ceil((b.hi.x() - b.lo.x() + 2.0 * trunc) / res)) + 1;
    ny_ = static_cast<int>(std::ceil((b.hi.y() - b.lo.y() + 2.0 * trunc) / res)) + 1;
    cells_.assign(static_cast<std::size_t>(nx_) * ny_, static_cast<float>(max_));
    const int r = static_cast<int>(std::ceil(trunc / res));
    for (const auto& p : points) stamp(p.cast<double>(), r);
  }

  // Truncated squared distance at q (outside the grid: the truncation).
  double at(const Eigen::Vector2d& q) const {
    const double fx = (q.x() - origin_.x()) / res_, fy = (q.y() - origin_.y()) / res_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx < nx_ && fy < ny_)) return max_;
    return cells_[static_cast<std::size_t>(fy) * nx_ + static_cast<std::size_t>(fx)];
  }
  double truncation_sq() const { return max_; }

 private:
  void stamp(const Eigen::Vector2d& p, int r) {
    const int cx = static_cast<int>((p.x() - origin_.x()) / res_);
    const int cy = static_cast<int>((p.y() - origin_.y()) / res_);
    for (int y = std::max(0, cy - r); y <= std::min(ny_ - 1, cy + r); ++y) {
      const double dy = origin_.y() + (y + 0.5) * res_ - p.y();
      for (int x = std::max(0, cx - r); x <= std::min(nx_ - 1, cx + r); ++x) {
        const double dx = origin_.x() + (x + 0.5) * res_ - p.x();
        float& c = cells_[static_cast<std::size_t>(y) * nx_ + x];
        c = std::min(c, static_cast<float>(std::min(max_, dx * dx + dy * dy)));
      }
    }
  }

  double res_, max_;
  Eigen::Vector2d origin_;
  int nx_ = 0, ny_ = 0;
  std::vector<float> cells_;
};

// The part of the plane the first frame saw: its points' bounding box and range, shrunk by the
// truncation (a robot-fixed window: crop box and range ring).
class View {
 public:
  View(const Bounds& b, double margin)
      : lo_(b.lo.array() + margin), hi_(b.hi.array() - margin), range_(b.range - margin) {}
  bool contains(const Eigen::Vector2d& q) const {
    return q.x() >= lo_.x() && q.y() >= lo_.y() && q.x() <= hi_.x() && q.y() <= hi_.y() &&
           q.norm() <= range_;
  }

 private:
  Eigen::Vector2d lo_, hi_;
  double range_;
};

struct Scorer {
  const DistanceField& field;
  const std::vector<Eigen::Vector2d>& rotated;  // second-frame points, rotated into the first
  Eigen::Vector2d t;

  double cost(double s) const {
    double sum = 0.0;
    for (const auto& q : rotated) sum += field.at(q + s * t);
    return sum / static_cast<double>(rotated.size());
  }
  double overlap(double s) const {
    const double near = 0.25 * field.truncation_sq();  // (truncation / 2)^2
    std::size_t n = 0;
    for (const auto& q : rotated) n += field.at(q + s * t) <= near;
    return static_cast<double>(n) / static_cast<double>(rotated.size());
  }
};

// Costs f(centre + k step), k in [-n, n].
std::vector<double> profile(const Scorer& sc, double centre, double step, int n) {
  std::vector<double> c;
  c.reserve(static_cast<std::size_t>(2 * n + 1));
  for (int k = -n; k <= n; ++k) c.push_back(sc.cost(centre + k * step));
  return c;
}

std::size_t argmin(const std::vector<double>& c) {
  return static_cast<std::size_t>(std::min_element(c.begin(), c.end()) - c.begin());
}

// Another valley nearly as deep as the best one, behind a ridge: plants or trunks that repeat
// along the row closer than the odometry's error, so either valley could be the motion.
bool ambiguous(const std::vector<double>& c, std::size_t best, double share) {
  const double lo = c[best], tol = share * (*std::max_element(c.begin(), c.end()) - lo);
  for (std::size_t k = 1; k + 1 < c.size(); ++k) {
    if (k == best || c[k] > c[k - 1] || c[k] > c[k + 1] || c[k] - lo > tol) continue;
    const auto [a, b] = std::minmax(k, best);
    const double ridge = *std::max_element(c.begin() + a, c.begin() + b + 1);
    if (ridge - c[k] > tol) return true;
  }
  return false;
}

// The second frame's near points, rotated into the first, that stay inside the first frame's view
// for every s searched. One that leaves it is a miss for large s only, and the crop box's front
// edge then pulls s down (monotonic costs on maize, alpha 2 % low in vineyards before this).
void keep_in_view(std::vector<Eigen::Vector2d>& rotated, const View& view, const Eigen::Vector2d& t,
                  double max_scale_error) {
  std::erase_if(rotated, [&](const Eigen::Vector2d& q) {
    return !view.contains(q + (1.0 - max_scale_error) * t) ||
           !view.contains(q + (1.0 + max_scale_error) * t);
  });
}

// Quarter steps around the coarse minimum, then a parabola through the best three; returns the
// scale and the cost at the best quarter step.
std::pair<double, double> refine(const Scorer& sc, double coarse, double step) {
  const double fine = 0.25 * step;
  const auto c = profile(sc, coarse, fine, 4);
  const std::size_t j = argmin(c);
  double scale = coarse + (static_cast<int>(j) - 4) * fine;
  const double cm = j > 0 ? c[j - 1] : sc.cost(scale - fine);
  const double cp = j + 1 < c.size() ? c[j + 1] : sc.cost(scale + fine);
  const double curvature = cm + cp - 2.0 * c[j];
  if (curvature > 0.0) scale += 0.5 * fine * (cm - cp) / curvature;
  return {scale, c[j]};
}

}  // namespace

ScanScaleMatch match_scan_scale(const std::vector<Eigen::Vector2f>& first,
                                const std::vector<Eigen::Vector2f>& second,
                                const core::Pose2& T_first_second,
                                const ScanScaleMatchConfig& cfg) {
  ScanScaleMatch m;
  const auto usable = [&](const Eigen::Vector2f& p) {
    return p.allFinite() && p.norm() <= cfg.max_range;
  };
  std::vector<Eigen::Vector2f> near_first;
  near_first.reserve(first.size());
  std::copy_if(first.begin(), first.end(), std::back_inserter(near_first), usable);
  std::vector<Eigen::Vector2d> rotated;
  rotated.reserve(second.size());
  const Eigen::Matrix2d R = T_first_second.rotation();
  for (const auto& q : second)
    if (usable(q)) rotated.push_back(R * q.cast<double>());
  if (std::ssize(rotated) < cfg.min_points || std::ssize(near_first) < cfg.min_points) return m;
  const Eigen::Vector2d t = T_first_second.translation();
  // The coarse step moves the second frame by one field cell.
  const double step = cfg.resolution / t.norm();
  if (!std::isfinite(step) || !R.allFinite() || cfg.max_scale_error / step < 2.0)
    return m.status = ScaleMatchStatus::no_motion, m;
  const int n = static_cast<int>(cfg.max_scale_error / step);
  const Bounds bounds = bounds_of(near_first);
  keep_in_view(rotated, View(bounds, cfg.truncation), t, cfg.max_scale_error);
  if (std::ssize(rotated) < cfg.min_points) return m.status = ScaleMatchStatus::no_overlap, m;
  const DistanceField field(near_first, bounds, cfg.resolution, cfg.truncation);
  const Scorer sc{field, rotated, t};
  const auto coarse_costs = profile(sc, 1.0, step, n);
  const std::size_t best = argmin(coarse_costs);
  const int k = static_cast<int>(best) - n;
  if (std::abs(k) == n) return m.status = ScaleMatchStatus::at_bound, m;
  if (ambiguous(coarse_costs, best, cfg.ambiguity))
    return m.status = ScaleMatchStatus::ambiguous, m;
  const auto [scale, c0] = refine(sc, 1.0 + k * step, step);
  m.scale = scale;
  // Contrast: how much worse one coarse step either side is (a flat valley: a solid hedge).
  const double rise = std::min(sc.cost(m.scale - step), sc.cost(m.scale + step)) - c0;
  m.contrast = rise / std::max(c0, cfg.resolution * cfg.resolution);
  m.overlap = sc.overlap(m.scale);
  if (m.overlap < cfg.min_overlap) return m.status = ScaleMatchStatus::no_overlap, m;
  if (m.contrast < cfg.min_contrast) return m.status = ScaleMatchStatus::flat, m;
  m.status = ScaleMatchStatus::ok;
  return m;
}

}  // namespace rownav::localize
