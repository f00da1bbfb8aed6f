// Pose history queried at frame stamps (localize/pose_history.hpp).
#include "rownav/localize/pose_history.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::localize {

bool PoseHistory::push(const StampedPose& s) {
  const auto& p = s.T_odom_base;
  if (!std::isfinite(s.stamp) || !std::isfinite(p.x) || !std::isfinite(p.y) ||
      !std::isfinite(p.theta))
    return false;
  if (!samples_.empty() && s.stamp <= samples_.back().stamp) return false;
  samples_.push_back(s);
  while (samples_.size() > 2 && samples_.front().stamp < s.stamp - history_) samples_.pop_front();
  return true;
}

std::optional<core::Pose2> PoseHistory::at(double stamp) const {
  if (samples_.empty() || !std::isfinite(stamp) || stamp < samples_.front().stamp)
    return std::nullopt;
  const StampedPose& last = samples_.back();
  if (stamp >= last.stamp) {
    const double dt = stamp - last.stamp;
    if (dt > max_extrapolation_) return std::nullopt;
    const auto& w = last.twist;
    const double v = std::isfinite(w.v) ? w.v : 0.0, vy = std::isfinite(w.vy) ? w.vy : 0.0,
                 om = std::isfinite(w.omega) ? w.omega : 0.0;
    return last.T_odom_base * core::Pose2(v * dt, vy * dt, om * dt);
  }
  const auto next = std::upper_bound(
      samples_.begin(), samples_.end(), stamp,
      [](double t, const StampedPose& s) { return t < s.stamp; });  // first sample after stamp
  const auto prev = std::prev(next);
  const double s = (stamp - prev->stamp) / (next->stamp - prev->stamp);
  return core::interpolate(prev->T_odom_base, next->T_odom_base, s);
}

std::optional<StampedPose> PoseHistory::latest() const {
  if (samples_.empty()) return std::nullopt;
  return samples_.back();
}

}  // namespace rownav::localize
