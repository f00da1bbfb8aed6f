// Path geometry of the headland turns (navigate/turn_path.hpp).
#include "rownav/navigate/turn_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rownav::navigate {

std::vector<Eigen::Vector2d> turn_arc(const Eigen::Vector2d& c, const Eigen::Vector2d& a,
                                      const Eigen::Vector2d& b, bool ccw) {
  const double r = (a - c).norm();
  const double a0 = std::atan2(a.y() - c.y(), a.x() - c.x());
  double a1 = std::atan2(b.y() - c.y(), b.x() - c.x());
  if (ccw)
    while (a1 <= a0 + 1e-9) a1 += 2.0 * std::numbers::pi;
  else
    while (a1 >= a0 - 1e-9) a1 -= 2.0 * std::numbers::pi;
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(a1 - a0) * r / kTurnPathStep)) + 1);
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i < n; ++i) {
    const double t = a0 + (a1 - a0) * i / (n - 1);
    out.emplace_back(c.x() + r * std::cos(t), c.y() + r * std::sin(t));
  }
  return out;
}

void append_path(std::vector<Eigen::Vector2d>& path, const std::vector<Eigen::Vector2d>& more) {
  for (const auto& p : more)
    if (path.empty() || (p - path.back()).norm() > 1e-6) path.push_back(p);
}

void densify_turn_path(std::vector<Eigen::Vector2d>& path, std::vector<double>& w) {
  std::vector<Eigen::Vector2d> p;
  std::vector<double> ww;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const int n =
        std::max(1, static_cast<int>(std::ceil((path[i + 1] - path[i]).norm() / kTurnPathStep)));
    for (int k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) / n;
      p.push_back(path[i] + t * (path[i + 1] - path[i]));
      ww.push_back(w[i] + t * (w[i + 1] - w[i]));
    }
  }
  p.push_back(path.back());
  ww.push_back(w.back());
  path = std::move(p);
  w = std::move(ww);
}

std::vector<double> anchor_ramp(const std::vector<Eigen::Vector2d>& path) {
  std::vector<double> w(path.size(), 0.0);
  double total = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) total += (path[i] - path[i - 1]).norm();
  double acc = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    acc += (path[i] - path[i - 1]).norm();
    w[i] = total > 0.0 ? acc / total : 1.0;
  }
  return w;
}

}  // namespace rownav::navigate
