/// @file place_indices.cpp Emmi 2021 eq. (4)-(9).
#include "rownav/map/place_indices.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rownav::map {

namespace {

/// Closest point of a row's support segment to q.
Eigen::Vector2d nearest_on_row(const RowCluster& row, const Eigen::Vector2d& q) {
  return row.line.at(std::clamp(row.line.arc(q), row.arc_min, row.arc_max));
}

/// A row's extent covers the robot's abscissa (within `margin`).
bool covers(const RowCluster& row, const core::Pose2& T, double margin) {
  const double s = row.line.arc(T.translation());
  return s >= row.arc_min - margin && s <= row.arc_max + margin;
}

/// The nearest row (or part of one) on the robot's left / right (sign) that covers its
/// abscissa, with its distance; parts of a row that did not merge count too.
std::pair<const RowCluster*, double> beside(const std::vector<RowCluster>& rows,
                                            const core::Pose2& T, double half_width, double sign,
                                            const KeyLocationConfig& kc, double margin) {
  std::pair<const RowCluster*, double> best{nullptr, 0.0};
  for (const auto& row : rows) {
    const auto lat = side_lateral(row, T, half_width, kc);
    if (!lat || *lat * sign <= 0.0 || !covers(row, T, margin)) continue;
    if (!best.first || std::abs(*lat) < best.second) best = {&row, std::abs(*lat)};
  }
  return best;
}

std::vector<Eigen::Vector2d> positions_of(const std::vector<KeyLocation>& keys, KeyType t) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& k : keys)
    if (k.type == t) out.push_back(k.p);
  return out;
}

}  // namespace

void PlaceIndicesConfig::validate() const {
  core::check_positive(projection_distance, "projection_distance");
  core::check_non_negative(beside_margin, "beside_margin");
  core::check_range(min_margin, 0.0, 1.0, "min_margin");
}

double position_correlation(const std::vector<Eigen::Vector2d>& positions) {
  if (positions.size() < 3) return 0.0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : positions) mean += p;
  mean /= static_cast<double>(positions.size());
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (const auto& p : positions) {
    const Eigen::Vector2d d = p - mean;
    sxx += d.x() * d.x();
    syy += d.y() * d.y();
    sxy += d.x() * d.y();
  }
  constexpr double kTiny = 1e-12;
  if (sxx < kTiny || syy < kTiny) return 1.0;  // on a line parallel to an axis
  return std::abs(sxy) / std::sqrt(sxx * syy);
}

double cluster_index(const RowCluster& row, const core::Pose2& T, double L) {
  // Emmi 2021 eq. (7), Fig. 4: FR / BR projected at +-L, FC / BC the nearest row points.
  const Eigen::Vector2d h(std::cos(T.theta), std::sin(T.theta));
  const Eigen::Vector2d fr = T.translation() + L * h, br = T.translation() - L * h;
  const Eigen::Vector2d fc = nearest_on_row(row, fr), bc = nearest_on_row(row, br);
  const double base = (fc - bc).norm();
  const double diff = std::abs((br - bc).norm() - (fr - fc).norm());
  constexpr double kMinBase = 1e-6;
  if (base < kMinBase) return 1.0;
  return std::clamp(diff / base, 0.0, 1.0);
}

Place instantaneous_place(const std::array<double, kFilteredPlaces>& c, double min_margin,
                          double* margin) {
  std::array<int, kFilteredPlaces> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return c[static_cast<std::size_t>(a)] > c[static_cast<std::size_t>(b)];
  });
  const double m = c[static_cast<std::size_t>(order[0])] - c[static_cast<std::size_t>(order[1])];
  if (margin) *margin = m;
  if (!std::isfinite(m) || m < min_margin) return Place::unknown;  // Emmi 2021 eq. (9)
  return filtered_place(order[0]);
}

PlaceIndices compute_place_indices(const std::vector<RowCluster>& rows, const core::Pose2& T,
                                   double half_width, const std::vector<KeyLocation>& valid_keys,
                                   const KeyLocationConfig& key_config,
                                   const PlaceIndicesConfig& config) {
  PlaceIndices out;
  out.p_index_entry = position_correlation(positions_of(valid_keys, KeyType::entry));
  out.p_index_exit = position_correlation(positions_of(valid_keys, KeyType::exit));
  const auto left = beside(rows, T, half_width, 1.0, key_config, config.beside_margin);
  const auto right = beside(rows, T, half_width, -1.0, key_config, config.beside_margin);
  out.left_beside = left.first != nullptr;
  out.right_beside = right.first != nullptr;
  const RowCluster* nearest = left.first;
  if (!nearest || (right.first && right.second < left.second)) nearest = right.first;
  double along_rows = 0.0;
  if (nearest) {
    const Eigen::Vector2d h(std::cos(T.theta), std::sin(T.theta));
    out.a_index = std::abs(h.dot(nearest->line.direction));  // eq. (5) against the row
    out.cluster_idx = cluster_index(*nearest, T, config.projection_distance);
    along_rows = out.a_index * (1.0 - out.cluster_idx);
  }
  // Emmi 2021 eq. (6) as read by rownav (see the file comment).
  const double lane_idx = out.left_beside && out.right_beside ? 1.0 : 0.0;
  const double alley_idx = out.left_beside != out.right_beside ? 1.0 : 0.0;
  out.c_index[1] = along_rows * lane_idx;
  out.c_index[2] = along_rows * alley_idx;
  out.c_index[0] = 1.0 - std::max(out.c_index[1], out.c_index[2]);
  out.instantaneous = instantaneous_place(out.c_index, config.min_margin, &out.margin);
  return out;
}

}  // namespace rownav::map
