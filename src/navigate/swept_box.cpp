#include "rownav/navigate/swept_box.hpp"

#include <cmath>

namespace rownav::navigate {

namespace {
constexpr double kStraight = 1e-3;  // [1/m] below: a radius over 1 km, the straight box
constexpr double kPi = 3.14159265358979323846;
}  // namespace

bool in_swept_box(const Eigen::Vector2d& p, double curvature, double s_min, double s_max,
                  double half_width) {
  if (!p.allFinite() || !std::isfinite(curvature)) return false;
  if (std::abs(curvature) < kStraight)
    return p.x() > s_min && p.x() < s_max && std::abs(p.y()) < half_width;
  const double radius = 1.0 / std::abs(curvature);
  const double side = curvature > 0.0 ? 1.0 : -1.0;  // centre on the left for a left turn
  const Eigen::Vector2d centre(0.0, side * radius);
  const Eigen::Vector2d start = -centre, r = p - centre;  // from the centre: base, point
  // Angle swept from the base to the point in the direction of motion.
  double phi = std::atan2(side * (start.x() * r.y() - start.y() * r.x()), start.dot(r));
  if (phi < 0.0) phi += 2.0 * kPi;
  const double s = radius * phi;
  return s > s_min && s < s_max && std::abs(r.norm() - radius) < half_width;
}

}  // namespace rownav::navigate
