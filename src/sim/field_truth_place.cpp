/// @file field_truth_place.cpp FieldTruth: place classification and rows seen from the robot.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "rownav/core/angle.hpp"
#include "rownav/sim/field_truth.hpp"

namespace rownav::sim {
namespace {

Eigen::Vector2d heading_of(const core::Pose2& T) {
  return {std::cos(T.theta), std::sin(T.theta)};
}

/// Corridor centre line (oriented along the robot's heading) and the errors relative to it.
void fill_corridor(const PolylineProjection& m, const core::Pose2& T, GroundTruth& gt) {
  const Eigen::Vector2d p = T.translation();
  const double sgn = m.tangent.dot(heading_of(T)) >= 0.0 ? 1.0 : -1.0;
  const Eigen::Vector2d dir = sgn * m.tangent;
  gt.lateral_error = sgn * m.lateral;
  gt.heading_error = core::angle_diff(T.theta, std::atan2(dir.y(), dir.x()));
  const core::Pose2 inv = T.inverse();
  gt.corridor_centre_base = core::Line2(inv * m.foot(p), inv.rotation() * dir);
}

/// Row's lateral offset seen from the robot (left +), ends extended.
double lateral_seen(const PolylineProjection& pr, const Eigen::Vector2d& heading) {
  return pr.tangent.dot(heading) >= 0.0 ? -pr.lateral : pr.lateral;
}

}  // namespace

void FieldTruth::fill_place(const Block& b, const core::Pose2& T,
                            const std::vector<PolylineProjection>& proj, GroundTruth& gt) const {
  const Eigen::Vector2d p = T.translation(), h = heading_of(T);
  const double hw = field_->headland_width, spacing = field_->row_spacing;
  double best_l = std::numeric_limits<double>::infinity(), best_r = best_l;
  for (int r : b.rows) {
    const double lat = lateral_seen(proj[static_cast<std::size_t>(r)], h);
    if (lat >= 0.0 && lat < best_l) best_l = lat, gt.left_row = r;
    if (lat < 0.0 && -lat < best_r) best_r = -lat, gt.right_row = r;
  }
  const auto lat_of = [&](std::size_t k) {
    return proj[static_cast<std::size_t>(b.rows[k])].lateral;
  };
  for (std::size_t k = 0; k + 1 < b.rows.size(); ++k) {
    if (lat_of(k) * lat_of(k + 1) > 0.0) continue;
    // Between rows k and k + 1: lane between their ends, headland beyond them.
    const PolylineProjection m = project_on_polyline(b.corridors[k], p);
    const double e = m.beyond();
    gt.place = e <= 0.0 ? Place::lane : (e <= hw ? Place::headland : Place::outside);
    if (gt.place == Place::lane) gt.corridor = static_cast<int>(k);
    if (gt.place != Place::outside) fill_corridor(m, T, gt);
    return;
  }
  // Beside the block: alley within one row spacing of the outermost row, between its ends.
  const std::size_t last = b.rows.size() - 1;
  const std::size_t j = std::abs(lat_of(0)) <= std::abs(lat_of(last)) ? 0 : last;
  const PolylineProjection& pr = proj[static_cast<std::size_t>(b.rows[j])];
  const double e = pr.beyond(), d = std::abs(pr.lateral);
  if (e <= 0.0 && d <= spacing)
    gt.place = Place::alley;
  else if (e > 0.0 && e <= hw && d <= hw)
    gt.place = Place::headland;
  else
    gt.place = Place::outside;
}

void FieldTruth::fill_rows(const core::Pose2& T, double reach,
                           const std::vector<PolylineProjection>& proj, GroundTruth& gt) const {
  const Eigen::Vector2d p = T.translation(), h = heading_of(T);
  const core::Pose2 inv = T.inverse();
  std::vector<int> order;
  for (std::size_t i = 0; i < proj.size(); ++i)
    if (proj[i].distance <= reach) order.push_back(static_cast<int>(i));
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return proj[static_cast<std::size_t>(a)].distance < proj[static_cast<std::size_t>(b)].distance;
  });
  gt.rows.reserve(order.size());
  for (int i : order) {
    const PolylineProjection& pr = proj[static_cast<std::size_t>(i)];
    const Row& row = field_->rows[static_cast<std::size_t>(i)];
    const double sgn = pr.tangent.dot(h) >= 0.0 ? 1.0 : -1.0;
    RowTruth rt;
    rt.row = i;
    rt.line_base = core::Line2(inv * pr.foot(p), inv.rotation() * (sgn * pr.tangent));
    rt.lateral = lateral_seen(pr, h);
    rt.start_base = inv * row.start();
    rt.end_base = inv * row.end();
    gt.rows.push_back(rt);
  }
}

}  // namespace rownav::sim
