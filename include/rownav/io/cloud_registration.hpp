#pragma once
/// @file cloud_registration.hpp Planar refinement of the odometry motion between two LiDAR clouds
/// by PCL's NDT or ICP (Lan 2021, 001_b5f4b55a1b95775a.txt sec. 3: consecutive clouds are
/// registered by odometry, then optimised by the Normal-Distributions Transform). Off by default.
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/pose2.hpp"

namespace rownav::io {

/// Registration method.
enum class RegistrationMethod : std::uint8_t { none, ndt, icp };

/// Parameters of refine().
struct RegistrationConfig {
  RegistrationMethod method = RegistrationMethod::none;  ///< none: the guess is returned
  double ndt_resolution = 1.0;  ///< [m] NDT voxel edge (PCL default scale for outdoor scans)
  double step_size = 0.1;       ///< [m] NDT More-Thuente maximum step
  /// [m, rad] convergence: smallest transform change. 0.01 (a common NDT setting) stopped PCL
  /// 1.13's NDT after its first, short line-search step in tests/io/cloud_registration_test.cpp
  double transformation_epsilon = 0.001;
  int max_iterations = 30;                   ///< [-] iterations of NDT / ICP
  double max_correspondence_distance = 0.5;  ///< [m] ICP: farther pairs are not matched
  /// [m] both clouds are voxel-downsampled to this edge first (0: off) to bound the cost
  double voxel_size = 0.1;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("method", s.method);
    v("ndt_resolution", s.ndt_resolution);
    v("step_size", s.step_size);
    v("transformation_epsilon", s.transformation_epsilon);
    v("max_iterations", s.max_iterations);
    v("max_correspondence_distance", s.max_correspondence_distance);
    v("voxel_size", s.voxel_size);
  }
  void validate() const;
};

/// Outcome of refine().
struct RegistrationResult {
  core::Pose2 T_target_source;  ///< refined planar transform (the guess when not converged)
  bool converged = false;       ///< the method converged (always false for `none`)
  /// [m^2] mean squared distance of source points to their nearest target points (PCL fitness;
  /// -1 when not computed)
  double fitness = -1.0;
  int iterations = 0;  ///< iterations the method used
};

/// Refines `guess` = T_target_source (maps source points into the target frame) by registering
/// the source cloud onto the target cloud, then projects the result onto the plane (x, y, yaw).
/// Never throws on data: NaN points are dropped; too few points or divergence return the guess
/// with converged = false.
RegistrationResult refine(const core::PointCloud& source, const core::PointCloud& target,
                          const core::Pose2& guess, const RegistrationConfig& config);

}  // namespace rownav::io

template <>
struct rownav::core::EnumNames<rownav::io::RegistrationMethod> {
  using E = rownav::io::RegistrationMethod;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::none, "none"}, {E::ndt, "ndt"}, {E::icp, "icp"}}};
};
