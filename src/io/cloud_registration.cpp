#include "rownav/io/cloud_registration.hpp"

// PCL's NDT / ICP templates instantiate Eigen code in which GCC 12 reports false positives after
// inlining (maybe-uninitialized in JacobiSVD, array-bounds in SSE loads); this file only.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Warray-bounds"

#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>

#include <cmath>

namespace rownav::io {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

constexpr std::size_t kMinPoints = 10;

Cloud::Ptr to_pcl(const core::PointCloud& in, double voxel) {
  auto out = std::make_shared<Cloud>();
  out->reserve(in.size());
  for (const auto& p : in.points)
    if (p.finite()) out->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  if (voxel <= 0.0 || out->empty()) return out;
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setLeafSize(static_cast<float>(voxel), static_cast<float>(voxel), static_cast<float>(voxel));
  grid.setInputCloud(out);
  auto down = std::make_shared<Cloud>();
  grid.filter(*down);
  return down;
}

/// Planar part of a 3D rigid transform: translation x, y and the yaw of the rotated x axis.
core::Pose2 planar(const Eigen::Matrix4f& T) {
  return {T(0, 3), T(1, 3), std::atan2(T(1, 0), T(0, 0))};
}

template <class Reg>
RegistrationResult run(Reg& reg, const Cloud::Ptr& source, const Cloud::Ptr& target,
                       const core::Pose2& guess) {
  RegistrationResult r;
  r.T_target_source = guess;
  reg.setInputSource(source);
  reg.setInputTarget(target);
  Cloud aligned;
  reg.align(aligned, guess.to_isometry().matrix().cast<float>());
  const Eigen::Matrix4f T = reg.getFinalTransformation();
  if (!reg.hasConverged() || !T.allFinite()) return r;
  r.converged = true;
  r.T_target_source = planar(T);
  r.fitness = reg.getFitnessScore();
  return r;
}

}  // namespace

void RegistrationConfig::validate() const {
  core::check_positive(ndt_resolution, "ndt_resolution");
  core::check_positive(step_size, "step_size");
  core::check_positive(transformation_epsilon, "transformation_epsilon");
  core::check_positive(max_iterations, "max_iterations");
  core::check_positive(max_correspondence_distance, "max_correspondence_distance");
  core::check_non_negative(voxel_size, "voxel_size");
}

RegistrationResult refine(const core::PointCloud& source, const core::PointCloud& target,
                          const core::Pose2& guess, const RegistrationConfig& config) {
  RegistrationResult none;
  none.T_target_source = guess;
  if (config.method == RegistrationMethod::none) return none;
  const Cloud::Ptr src = to_pcl(source, config.voxel_size);
  const Cloud::Ptr tgt = to_pcl(target, config.voxel_size);
  if (src->size() < kMinPoints || tgt->size() < kMinPoints) return none;
  if (config.method == RegistrationMethod::ndt) {
    pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ> ndt;
    ndt.setResolution(static_cast<float>(config.ndt_resolution));
    ndt.setStepSize(config.step_size);
    ndt.setTransformationEpsilon(config.transformation_epsilon);
    ndt.setMaximumIterations(config.max_iterations);
    RegistrationResult r = run(ndt, src, tgt, guess);
    r.iterations = ndt.getFinalNumIteration();
    return r;
  }
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setMaxCorrespondenceDistance(config.max_correspondence_distance);
  icp.setMaximumIterations(config.max_iterations);
  // PCL's ICP epsilon is on the squared transform change.
  icp.setTransformationEpsilon(config.transformation_epsilon * config.transformation_epsilon);
  return run(icp, src, tgt, guess);
}

}  // namespace rownav::io
