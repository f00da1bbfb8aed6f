/// @file path_follower.cpp Pure pursuit on the true pose for scripted drives.
#include <algorithm>
#include <cmath>

#include "rownav/sim/scripted_path.hpp"

namespace rownav::sim {
namespace {

constexpr double kStopTolerance = 0.08;   // [m] a stop point counts as reached within this
constexpr double kBrake = 0.5;            // [m/s^2] planned deceleration before stops
constexpr double kMinSpeed = 0.08;        // [m/s] creeping speed when approaching a stop
constexpr double kAlignTolerance = 0.03;  // [rad] heading error that ends an in-place rotation
constexpr double kRotateGain = 2.0;       // [1/s] in-place rotation gain
constexpr double kRotateMax = 0.8;        // [rad/s] in-place rotation rate limit
constexpr double kSpeedHorizon = 2.0;     // [m] look for slower path sections this far ahead

}  // namespace

PathFollower::PathFollower(std::vector<PathPoint> path, double lookahead)
    : path_(std::move(path)),
      lookahead_(std::isfinite(lookahead) && lookahead > 0.1 ? lookahead : 1.0) {
  arc_.assign(path_.size(), 0.0);
  for (std::size_t i = 1; i < path_.size(); ++i)
    arc_[i] = arc_[i - 1] + (path_[i].p - path_[i - 1].p).norm();
  for (std::size_t i = 0; i < path_.size(); ++i)
    if (path_[i].speed <= 0.0 && i > 0) stops_.push_back(i);
  if (!path_.empty() && (stops_.empty() || stops_.back() != path_.size() - 1))
    stops_.push_back(path_.size() - 1);
  done_ = path_.size() < 2;
}

std::size_t PathFollower::advance(std::size_t from, double distance, std::size_t limit) const {
  std::size_t i = from;
  while (i < limit && arc_[i] < arc_[from] + distance) ++i;
  return i;
}

std::size_t PathFollower::next_stop(std::size_t from) const {
  const auto it = std::lower_bound(stops_.begin(), stops_.end(), from);
  return it == stops_.end() ? path_.size() - 1 : *it;
}

double PathFollower::progress() const {
  if (path_.size() < 2 || arc_.back() <= 0.0) return done_ ? 1.0 : 0.0;
  return done_ ? 1.0 : arc_[index_] / arc_.back();
}

core::Twist2 PathFollower::command(const core::Pose2& T) {
  const Eigen::Vector2d p = T.translation();
  if (done_ || !p.allFinite() || !std::isfinite(T.theta)) return {};
  std::size_t stop = next_stop(index_);
  // Closest point, searched forward only, never past the next stop (paths double back in turns).
  const std::size_t window = advance(index_, 2.0 * lookahead_, stop);
  double best = (path_[index_].p - p).squaredNorm();
  for (std::size_t i = index_ + 1; i <= window; ++i) {
    const double d2 = (path_[i].p - p).squaredNorm();
    if (d2 < best) best = d2, index_ = i;
  }
  if (index_ == stop) {
    const Eigen::Vector2d seg = path_[stop].p - path_[stop > 0 ? stop - 1 : 0].p;
    if (std::sqrt(best) < kStopTolerance || (p - path_[stop].p).dot(seg) >= 0.0) {
      if (stop + 1 >= path_.size()) {
        done_ = true;
        return {};
      }
      index_ = stop + 1;
      aligning_ = true;
      stop = next_stop(index_);
    }
  }
  // Look-ahead target, extended past a stop along the last segment to keep its distance.
  const std::size_t t = advance(index_, lookahead_, stop);
  Eigen::Vector2d target = path_[t].p;
  const double short_by = lookahead_ - (arc_[t] - arc_[index_]);
  if (t == stop && short_by > 0.0 && t > 0)
    target += short_by * (path_[t].p - path_[t - 1].p).normalized();
  const Eigen::Vector2d tb = T.inverse() * target;
  const double bearing = std::atan2(tb.y(), tb.x());
  if (aligning_ && std::abs(bearing) < kAlignTolerance) aligning_ = false;
  if (aligning_ || std::abs(bearing) > 1.2)
    return {0.0, 0.0, std::clamp(kRotateGain * bearing, -kRotateMax, kRotateMax)};
  // Speed: the slowest path section within the horizon, and braking towards the next stop.
  double v = path_[index_].speed > 0.0 ? path_[index_].speed : kMinSpeed;
  for (std::size_t i = index_; i <= advance(index_, kSpeedHorizon, stop); ++i)
    if (path_[i].speed > 0.0) v = std::min(v, path_[i].speed);
  const double to_stop = std::max(0.0, arc_[stop] - arc_[index_]);
  v = std::min(v, std::max(kMinSpeed, std::sqrt(2.0 * kBrake * to_stop)));
  const double kappa = 2.0 * tb.y() / std::max(tb.squaredNorm(), 1e-6);  // pure pursuit
  return {v, 0.0, v * kappa};
}

}  // namespace rownav::sim
