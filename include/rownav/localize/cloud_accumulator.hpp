#pragma once
/// @file cloud_accumulator.hpp Motion-compensated (deskewed) LiDAR sweeps accumulated in the odom
/// frame, so a sparse 16-beam cloud can be densified with the last few sweeps (Lan 2021,
/// 001_b5f4b55a1b95775a.txt sec. 3: "the point cloud is registered by odometer data").
#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/localize/localizer.hpp"

namespace rownav::localize {

/// Options of CloudAccumulator.
struct CloudAccumulatorConfig {
  int sweeps = 3;      ///< [-] sweeps kept (the newest included)
  bool deskew = true;  ///< place each point at its own time (needs the cloud's time field)
  std::size_t max_points = 200000;  ///< [-] newest sweeps kept within this many points in total

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("sweeps", s.sweeps);
    v("deskew", s.deskew);
    v("max_points", s.max_points);
  }
  void validate() const;
};

/// Outcome of adding a sweep.
enum class AccumulateStatus : std::uint8_t { ok, no_pose, empty };

/// Result of CloudAccumulator::add.
struct AccumulateResult {
  AccumulateStatus status = AccumulateStatus::empty;
  std::size_t points = 0;   ///< points stored from this sweep
  std::size_t dropped = 0;  ///< non-finite points or points without a pose at their time
};

/// Keeps the last sweeps in the odom frame. Poses are planar (roll / pitch ignored).
class CloudAccumulator {
 public:
  /// Validates `config` (throws std::invalid_argument naming the field).
  explicit CloudAccumulator(const CloudAccumulatorConfig& config = {});

  /// Deskews a sweep (sensor frame; point i measured at stamp + time_i) with the localizer's
  /// T_odom_base and stores it. Never throws; a sweep without a pose is dropped (no_pose).
  AccumulateResult add(const core::PointCloud& cloud, const Eigen::Isometry3d& T_base_sensor,
                       const Localizer& localizer);
  /// The stored sweeps in the base frame at `T_odom_base` (stamp / frame_id "base_link", the
  /// time field is the offset from `stamp`).
  core::PointCloud cloud_in_base(const core::Pose2& T_odom_base, double stamp) const;
  /// The stored sweeps in the base frame at the newest sweep's start pose.
  core::PointCloud latest_in_base() const;
  std::size_t sweeps() const { return sweeps_.size(); }
  void clear() { sweeps_.clear(); }
  const CloudAccumulatorConfig& config() const { return config_; }

 private:
  struct Sweep {
    double stamp = 0.0;
    core::Pose2 T_odom_base;  // at stamp
    std::vector<core::PointXYZIRT> points_odom;
  };
  CloudAccumulatorConfig config_;
  std::deque<Sweep> sweeps_;
};

}  // namespace rownav::localize
