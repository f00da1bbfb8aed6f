#include "rownav/localize/cloud_accumulator.hpp"

#include <cmath>

namespace rownav::localize {
namespace {

/// 3D transform of a planar pose with a point's z kept (planar odometry: no roll / pitch).
Eigen::Isometry3d planar(const core::Pose2& T) {
  return T.to_isometry();
}

}  // namespace

void CloudAccumulatorConfig::validate() const {
  core::check_range(sweeps, 1, 100, "sweeps");
  core::check_positive(max_points, "max_points");
}

CloudAccumulator::CloudAccumulator(const CloudAccumulatorConfig& config) : config_(config) {
  config_.validate();
}

AccumulateResult CloudAccumulator::add(const core::PointCloud& cloud,
                                       const Eigen::Isometry3d& T_base_sensor,
                                       const Localizer& localizer) {
  AccumulateResult r;
  const auto T0 = localizer.T_odom_base(cloud.stamp);
  if (!T0) {
    r.status = AccumulateStatus::no_pose;
    r.dropped = cloud.size();
    return r;
  }
  Sweep sweep{cloud.stamp, *T0, {}};
  sweep.points_odom.reserve(cloud.size());
  const bool deskew = config_.deskew && cloud.has_time;
  // Points of one column share a time: the pose is looked up once per distinct time.
  float last_time = 0.0f;
  Eigen::Isometry3d T_odom_sensor = planar(*T0) * T_base_sensor;
  for (const auto& p : cloud.points) {
    if (!p.finite() || !std::isfinite(p.time)) {
      ++r.dropped;
      continue;
    }
    if (deskew && p.time != last_time) {
      const auto T = localizer.T_odom_base(cloud.stamp + p.time);
      if (!T) {
        ++r.dropped;
        continue;
      }
      last_time = p.time;
      T_odom_sensor = planar(*T) * T_base_sensor;
    }
    const Eigen::Vector3d q = T_odom_sensor * Eigen::Vector3d(p.x, p.y, p.z);
    core::PointXYZIRT o = p;
    o.x = static_cast<float>(q.x());
    o.y = static_cast<float>(q.y());
    o.z = static_cast<float>(q.z());
    sweep.points_odom.push_back(o);
  }
  r.points = sweep.points_odom.size();
  r.status = r.points > 0 ? AccumulateStatus::ok : AccumulateStatus::empty;
  if (r.points == 0) return r;
  sweeps_.push_back(std::move(sweep));
  std::size_t total = 0;
  for (const auto& s : sweeps_) total += s.points_odom.size();
  while (sweeps_.size() > 1 &&
         (static_cast<int>(sweeps_.size()) > config_.sweeps || total > config_.max_points)) {
    total -= sweeps_.front().points_odom.size();
    sweeps_.pop_front();
  }
  return r;
}

core::PointCloud CloudAccumulator::cloud_in_base(const core::Pose2& T_odom_base,
                                                 double stamp) const {
  core::PointCloud out;
  out.stamp = stamp;
  out.frame_id = "base_link";
  out.has_time = true;
  const Eigen::Isometry3d T_base_odom = planar(T_odom_base.inverse());
  for (const auto& s : sweeps_) {
    const float dt = static_cast<float>(s.stamp - stamp);
    for (const auto& p : s.points_odom) {
      const Eigen::Vector3d q = T_base_odom * Eigen::Vector3d(p.x, p.y, p.z);
      core::PointXYZIRT b = p;
      b.x = static_cast<float>(q.x());
      b.y = static_cast<float>(q.y());
      b.z = static_cast<float>(q.z());
      b.time = p.time + dt;
      out.points.push_back(b);
    }
  }
  return out;
}

core::PointCloud CloudAccumulator::latest_in_base() const {
  if (sweeps_.empty()) return {};
  const Sweep& s = sweeps_.back();
  core::PointCloud out = cloud_in_base(s.T_odom_base, s.stamp);
  return out;
}

}  // namespace rownav::localize
