#pragma once
/// @file scale_scene.hpp Synthetic corridors seen by a robot-fixed window, for the odometry
/// scale tests: persistent trunks and leaf clumps along two rows (each frame sees a random part
/// of them, with range noise), points fixed to the robot (a ring where a beam meets the ground),
/// and the crop box / range ring a real preprocessing chain cuts the sweep with.
#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "rownav/core/pose2.hpp"

namespace rownav::localize::testing {

struct CorridorScene {
  std::vector<Eigen::Vector2d> world;  ///< persistent points (trunks, leaf clumps)
  double width = 2.0;                  ///< [m] between the rows
};

enum class RowKind { vines, solid_hedge, plants_every_20cm };

/// Two rows along +x from x = -5 to 60 m, `width` apart, centred on y = 0.
inline CorridorScene make_corridor(std::mt19937& rng, RowKind kind) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  CorridorScene s;
  s.width = 1.5 + 2.0 * u(rng);
  for (const double side : {-1.0, 1.0}) {
    const double y = side * s.width / 2.0;
    if (kind == RowKind::plants_every_20cm) {
      for (double x = -5.0; x < 60.0; x += 0.2) s.world.emplace_back(x, y);
      continue;
    }
    if (kind == RowKind::solid_hedge) continue;  // drawn fresh in every frame (no texture)
    // Trunks 0.8-1.6 m apart, and the canopy as leaf clumps 0.2-0.6 m across with gaps,
    // sampled on a 5 cm grid (a voxel grid's output).
    for (double x = -5.0; x < 60.0; x += 0.8 + 0.8 * u(rng)) s.world.emplace_back(x, y);
    for (double x = -5.0; x < 60.0; x += 0.3 + 0.9 * u(rng)) {
      const double r = 0.1 + 0.2 * u(rng), cy = y + 0.2 * (u(rng) - 0.5);
      for (double dx = -r; dx <= r; dx += 0.05)
        for (double dy = -r; dy <= r; dy += 0.05)
          if (dx * dx + dy * dy <= r * r) s.world.emplace_back(x + dx, cy + dy);
    }
  }
  return s;
}

/// The points a robot at T_world_base sees, in its base frame: `share` of the persistent
/// points inside the window (x in [-2, 8] m, |y| <= 4 m, range <= 8 m), 1 cm noise, a ring of
/// ground hits 3 m around the robot, and for a solid hedge fresh points along both rows.
inline std::vector<Eigen::Vector2f> observe(const CorridorScene& s, RowKind kind,
                                            const core::Pose2& T_world_base, std::mt19937& rng,
                                            double share = 0.85) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  const core::Pose2 T_base_world = T_world_base.inverse();
  std::vector<Eigen::Vector2f> out;
  auto keep = [&](const Eigen::Vector2d& p) {
    if (p.x() >= -2.0 && p.x() <= 8.0 && std::abs(p.y()) <= 4.0 && p.norm() <= 8.0)
      out.emplace_back(static_cast<float>(p.x() + noise(rng)),
                       static_cast<float>(p.y() + noise(rng)));
  };
  for (const auto& w : s.world)
    if (u(rng) < share) keep(T_base_world * w);
  if (kind == RowKind::solid_hedge)
    for (int i = 0; i < 1200; ++i) {
      const double x = T_world_base.x - 3.0 + 12.0 * u(rng);
      keep(T_base_world * Eigen::Vector2d(x, (u(rng) < 0.5 ? -0.5 : 0.5) * s.width));
    }
  for (int i = 0; i < 120; ++i) {  // robot-fixed: a beam ring on the ground
    const double a = 2.0 * std::numbers::pi * i / 120.0;
    keep(Eigen::Vector2d(3.0 * std::cos(a), 3.0 * std::sin(a)));
  }
  return out;
}

}  // namespace rownav::localize::testing
