#include "rownav/track/row_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::track {

namespace {

/// Direction flipped to point towards +x of the current base frame.
core::Line2 forward(core::Line2 l) {
  if (l.direction.x() < 0.0) l.direction = -l.direction;
  return l;
}

double safe_x(double dx) {
  constexpr double kMin = 1e-9;
  return std::abs(dx) < kMin ? (dx < 0.0 ? -kMin : kMin) : dx;
}

}  // namespace

SlopeIntercept slope_intercept(const core::Line2& line) {
  const core::Line2 l = forward(line);
  const double a = l.direction.y() / safe_x(l.direction.x());
  return {a, l.point.y() - a * l.point.x()};
}

core::Line2 line_of(const SlopeIntercept& si) {
  return core::Line2::from_slope_intercept(si.a, si.b);
}

core::Line2 move_line(const core::Line2& line_prev, const core::Pose2& T_prev_now) {
  // p_now = T_now_prev * p_prev with T_now_prev = T_prev_now^-1.
  return forward(line_prev.transformed(T_prev_now.inverse()));
}

SlopeIntercept move_line(const SlopeIntercept& si_prev, const core::Pose2& T_prev_now) {
  return slope_intercept(move_line(line_of(si_prev), T_prev_now));
}

Deviation deviation(const core::Line2& centre_base) {
  const core::Line2 c = forward(centre_base);
  return {c.signed_distance(Eigen::Vector2d::Zero()), -c.heading()};
}

core::Line2 centre_between(const core::Line2& left, const core::Line2& right) {
  const core::Line2 l = forward(left), r = forward(right);
  const Eigen::Vector2d p(0.0, 0.5 * (l.y_at(0.0) + r.y_at(0.0)));
  return {p, l.direction + r.direction};
}

core::Line2 centre_from_one(const core::Line2& row, bool row_is_left, double spacing) {
  const core::Line2 l = forward(row);
  const double shift = (row_is_left ? -0.5 : 0.5) * spacing;
  return {l.point + shift * l.normal(), l.direction};
}

double spacing_between(const core::Line2& left, const core::Line2& right) {
  const core::Line2 l = forward(left), r = forward(right);
  return l.signed_distance(Eigen::Vector2d(0.0, r.y_at(0.0))) * -1.0;
}

double robust_spacing(std::vector<double> centres) {
  std::sort(centres.begin(), centres.end());
  std::vector<double> d;
  for (std::size_t i = 1; i < centres.size(); ++i)
    if (centres[i] - centres[i - 1] > 0.0) d.push_back(centres[i] - centres[i - 1]);
  if (d.empty()) return 0.0;
  std::vector<double> sorted = d;
  std::sort(sorted.begin(), sorted.end());
  // The lower median: with one normal and one double difference (a row missing) it is the normal.
  const double ref = sorted[(sorted.size() - 1) / 2];
  for (double& x : d) x /= std::max(1.0, std::round(x / ref));
  std::sort(d.begin(), d.end());
  const std::size_t n = d.size();
  return n % 2 ? d[n / 2] : 0.5 * (d[n / 2 - 1] + d[n / 2]);
}

bool finite(const core::Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

}  // namespace rownav::track
