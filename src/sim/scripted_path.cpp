#include "rownav/sim/scripted_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rownav::sim {
namespace {

constexpr double kSpacing = 0.05;  // [m] dense path spacing

/// A corner of the coarse path; its attributes apply to the segment that ends at it.
struct Key {
  Eigen::Vector2d p;
  double speed;
  bool in_row;
  bool stop;
};

Eigen::Vector2d left_normal(const Eigen::Vector2d& d) {
  return {-d.y(), d.x()};
}

/// Appends an arc of centre c, radius r, from angle a0 to a1 (sign of a1 - a0 = direction).
void arc(const Eigen::Vector2d& c, double r, double a0, double a1,
         std::vector<Eigen::Vector2d>& out) {
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(a1 - a0) * r / kSpacing)));
  for (int i = 1; i <= n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    out.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
  }
}

/// Turn in a local frame: start (x0, 0) heading +x, end (x0, D) heading -x, radius R.
std::vector<Eigen::Vector2d> local_turn(double x0, double D, double R) {
  constexpr double half_pi = 0.5 * std::numbers::pi;
  std::vector<Eigen::Vector2d> pts;
  if (D >= 2.0 * R) {  // U: quarter arc, straight across, quarter arc
    arc({x0, R}, R, -half_pi, 0.0, pts);
    arc({x0, D - R}, R, 0.0, half_pi, pts);
    return pts;
  }
  // Bulb (omega): right arc on C1, long left arc on C2, right arc on C3.
  const double x2 = std::sqrt(std::max(0.0, 4.0 * R * R - (0.5 * D + R) * (0.5 * D + R)));
  const double phi = std::atan2(0.5 * D + R, x2);
  arc({x0, -R}, R, half_pi, phi, pts);
  arc({x0 + x2, 0.5 * D}, R, phi - std::numbers::pi, std::numbers::pi - phi, pts);
  arc({x0, D + R}, R, -phi, -half_pi, pts);
  return pts;
}

/// Headland turn keys from A (heading dA) to B (heading about -dA).
void add_turn(const Eigen::Vector2d& A, const Eigen::Vector2d& dA, const Eigen::Vector2d& B,
              const PathConfig& cfg, double radius, std::vector<Key>& keys) {
  const Eigen::Vector2d w = B - A;
  const Eigen::Vector2d uy = (w.dot(left_normal(dA)) >= 0.0 ? 1.0 : -1.0) * left_normal(dA);
  const double bx = w.dot(dA), D = w.dot(uy), x0 = std::max(0.0, bx);
  const auto world = [&](const Eigen::Vector2d& l) {
    return Eigen::Vector2d(A + l.x() * dA + l.y() * uy);
  };
  if (x0 > 0.0) keys.push_back({world({x0, 0.0}), cfg.speed, false, false});
  if (cfg.turn == TurnStyle::in_place) {
    keys.back().stop = true;
    keys.push_back({world({x0, D}), cfg.turn_speed, false, true});
  } else {
    for (const auto& l : local_turn(x0, D, radius))
      keys.push_back({world(l), cfg.turn_speed, false, false});
  }
  keys.push_back({B, cfg.turn_speed, false, false});
}

std::vector<Eigen::Vector2d> checked_corridor(const FieldTruth& truth, const PathConfig& cfg,
                                              std::size_t i) {
  const int c = cfg.corridors[i], n = truth.corridor_count(cfg.block);
  if (c < 0 || c >= n)
    throw std::invalid_argument(
        "corridors[" + std::to_string(i) + "]: corridor " + std::to_string(c) +
        " does not exist in block " + std::to_string(cfg.block) +
        (n > 0 ? " (0.." + std::to_string(n - 1) + ")" : " (no corridors)"));
  auto centre = truth.corridor_centre(cfg.block, c);
  if (i % 2 == 1) std::reverse(centre.begin(), centre.end());
  return centre;
}

std::vector<Key> corridor_keys(const FieldTruth& truth, const PathConfig& cfg, double radius) {
  const auto blocks = truth.blocks();
  if (std::find(blocks.begin(), blocks.end(), cfg.block) == blocks.end())
    throw std::invalid_argument("block: block " + std::to_string(cfg.block) +
                                " does not exist in the field");
  std::vector<Key> keys;
  for (std::size_t i = 0; i < cfg.corridors.size(); ++i) {
    const auto centre = checked_corridor(truth, cfg, i);
    const Eigen::Vector2d d_in = (centre[1] - centre[0]).normalized();
    const Eigen::Vector2d d_out = (centre.back() - centre[centre.size() - 2]).normalized();
    if (i == 0) {
      keys.push_back({centre[0] - cfg.lead_in * d_in, cfg.speed, false, false});
    } else {
      const Key exit = keys.back();
      const Eigen::Vector2d d_prev = (exit.p - keys[keys.size() - 2].p).normalized();
      add_turn(exit.p, d_prev, centre[0] - cfg.lead_out * d_in, cfg, radius, keys);
    }
    keys.push_back({centre[0], cfg.speed, false, false});
    for (std::size_t j = 1; j < centre.size(); ++j)
      keys.push_back({centre[j], cfg.speed, true, false});
    keys.push_back({centre.back() + cfg.lead_out * d_out, cfg.speed, false, false});
  }
  return keys;
}

/// Resamples the keys every kSpacing; stops and the last point get speed 0.
std::vector<PathPoint> densify(const std::vector<Key>& keys) {
  std::vector<PathPoint> out;
  if (keys.empty()) return out;
  out.push_back({keys.front().p, keys.size() > 1 ? keys[1].speed : 0.0, false});
  for (std::size_t k = 1; k < keys.size(); ++k) {
    const Eigen::Vector2d d = keys[k].p - keys[k - 1].p;
    const double len = d.norm();
    if (len < 1e-9) {
      if (keys[k].stop) out.back().speed = 0.0;
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(len / kSpacing)));
    for (int j = 1; j <= n; ++j)
      out.push_back(
          {keys[k - 1].p + d * (static_cast<double>(j) / n), keys[k].speed, keys[k].in_row});
    if (keys[k].stop) out.back().speed = 0.0;
  }
  out.back().speed = 0.0;
  return out;
}

void check_inside(const FieldTruth& truth, const std::vector<PathPoint>& path) {
  Eigen::AlignedBox2d box = truth.field().row_bounds();
  const double m = truth.field().headland_width + 1e-6;
  box.min().array() -= m;
  box.max().array() += m;
  for (const auto& pt : path)
    if (!box.contains(pt.p))
      throw std::invalid_argument(
          "path leaves the field area (row bounds grown by headland_width) at (" +
          std::to_string(pt.p.x()) + ", " + std::to_string(pt.p.y()) + ")");
}

}  // namespace

void PathConfig::validate() const {
  core::check_positive(speed, "speed");
  core::check_positive(turn_speed, "turn_speed");
  core::check_non_negative(lead_in, "lead_in");
  core::check_non_negative(lead_out, "lead_out");
  if (waypoints.empty()) core::check(!corridors.empty(), "corridors", "must not be empty");
  core::check(waypoints.empty() || waypoints.size() >= 2, "waypoints", "needs at least 2 points");
  for (std::size_t i = 0; i < waypoints.size(); ++i)
    core::check(waypoints[i].allFinite(), "waypoints[" + std::to_string(i) + "]", "must be finite");
}

std::vector<PathPoint> build_path(const FieldTruth& truth, const PathConfig& cfg,
                                  const RobotConfig& robot) {
  cfg.validate();
  if (cfg.turn == TurnStyle::in_place && !robot.can_turn_in_place())
    throw std::invalid_argument("turn: in_place needs a differential or skid-steer robot (robot '" +
                                robot.name + "' is ackermann)");
  std::vector<PathPoint> path;
  if (!cfg.waypoints.empty()) {
    std::vector<Key> keys;
    for (const auto& w : cfg.waypoints) keys.push_back({w, cfg.speed, false, false});
    path = densify(keys);
    for (auto& pt : path)
      pt.in_row = truth.at(core::Pose2(pt.p.x(), pt.p.y(), 0.0), 0.0, 0.0).place == Place::lane;
  } else {
    // Small margin over the minimum radius so the follower is not steering at its limit.
    const double radius = std::max(0.5 * truth.field().row_spacing, 1.1 * robot.min_turn_radius());
    path = densify(corridor_keys(truth, cfg, radius));
  }
  check_inside(truth, path);
  return path;
}

}  // namespace rownav::sim
