// Malavazi 2018 sec. 2.3.1 / 3.1.1: the data filter in front of the crop modelling.
#include "rownav/core/data_filter.hpp"

#include <cmath>

namespace rownav::core {

namespace {

/// Side 0 (left) or 1 (right) keeps p: inside its model's box, else inside its window.
bool keeps(const Eigen::Vector2f& p, int side, const DataFilterBoxes& f) {
  const double x = p.x(), y = p.y();
  if (const auto& m = f.models[static_cast<std::size_t>(side)])
    return std::abs(y - (m->a * x + m->b)) <= f.half_width;
  const bool on_side = side == 0 ? y > 0.0 : y <= 0.0;
  const double r = std::hypot(x, y);
  return on_side && r >= f.init_min_range && r <= f.init_max_range;
}

}  // namespace

std::vector<Eigen::Vector2f> filter_points(std::span<const Eigen::Vector2f> points_base,
                                           const DataFilterBoxes& boxes) {
  std::vector<Eigen::Vector2f> out;
  out.reserve(points_base.size());
  for (const auto& p : points_base)
    if (p.allFinite() && (keeps(p, 0, boxes) || keeps(p, 1, boxes))) out.push_back(p);
  return out;
}

}  // namespace rownav::core
