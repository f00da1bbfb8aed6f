/// @file pinhole_camera.cpp Ray-cast RGB camera: primary rays per pixel, Lambert + shadow ray.
#include "rownav/sim/pinhole_camera.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

constexpr double kMaxFovDeg = 170.0;  // a pinhole cannot model wider lenses
constexpr int kMaxSide = 16384;       // [px] image side guard
constexpr float kByte = 255.0f;

void check_colour(const Eigen::Vector3d& c, const char* field) {
  core::check(c.allFinite() && (c.array() >= 0.0).all() && (c.array() <= 1.0).all(), field,
              "every component must be in [0, 1]");
}

/// splitmix64: a well-mixed 64-bit hash (the texture must not show cell patterns).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// World-fixed value in [-1, 1] of the texture cell holding p.
float texture_value(const Eigen::Vector3f& p, float cell, std::uint64_t seed) {
  std::uint64_t h = seed;
  for (int k = 0; k < 3; ++k)
    h = mix(h ^ static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p[k] / cell))));
  return static_cast<float>(h >> 40) * 0x1p-23f - 1.0f;
}

}  // namespace

void PinholeCameraConfig::validate() const {
  core::check_range(width, 1, kMaxSide, "width");
  core::check_range(height, 1, kMaxSide, "height");
  core::check(horizontal_fov_deg > 0.0 && horizontal_fov_deg <= kMaxFovDeg, "horizontal_fov_deg",
              "must be in (0, 170]");
  core::check(mount_xyz.allFinite() && mount_xyz.cwiseAbs().maxCoeff() <= max_mount_offset,
              "mount_xyz", "every component must be finite and within max_mount_offset");
  core::check(mount_rpy_deg.allFinite(), "mount_rpy_deg", "must be finite");
  core::check_positive(max_mount_offset, "max_mount_offset");
  core::check_positive(range_max, "range_max");
  core::check(sun_direction.allFinite() && sun_direction.norm() > 0.0, "sun_direction",
              "must be a finite non-zero vector");
  core::check_range(ambient, 0.0, 1.0, "ambient");
  core::check_range(texture_variation, 0.0, 1.0, "texture_variation");
  core::check_positive(texture_cell, "texture_cell");
  core::check_range(pixel_noise_std, 0.0, 1.0, "pixel_noise_std");
  core::check_non_negative(sun_shadow_bias, "sun_shadow_bias");
  check_colour(sky_colour, "sky_colour");
  check_colour(ground_colour, "ground_colour");
  check_colour(crop_colour, "crop_colour");
  check_colour(canopy_colour, "canopy_colour");
  check_colour(crown_colour, "crown_colour");
  check_colour(trunk_colour, "trunk_colour");
  check_colour(post_colour, "post_colour");
  check_colour(wire_colour, "wire_colour");
  check_colour(weed_colour, "weed_colour");
  check_colour(obstacle_colour, "obstacle_colour");
  check_colour(other_colour, "other_colour");
  check_colour(other_crop_colour, "other_crop_colour");
  core::check(!use_target_region || (target_max.array() > target_min.array()).all(), "target_max",
              "must exceed target_min in x and y");
}

core::CameraIntrinsics PinholeCameraConfig::intrinsics() const {
  core::CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = 0.5 * width / std::tan(0.5 * core::deg2rad(horizontal_fov_deg));
  k.fy = k.fx;  // square pixels
  k.cx = 0.5 * width;
  k.cy = 0.5 * height;
  return k;
}

Eigen::Isometry3d PinholeCameraConfig::T_base_camera() const {
  const Eigen::Matrix3d R_base_body =
      (Eigen::AngleAxisd(core::deg2rad(mount_rpy_deg.z()), Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(core::deg2rad(mount_rpy_deg.y()), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(core::deg2rad(mount_rpy_deg.x()), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  Eigen::Matrix3d R_body_optical;  // columns: optical x (right), y (down), z (view) in the body
  R_body_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_base_body * R_body_optical;
  T.translation() = mount_xyz;
  return T;
}

Eigen::Vector3d PinholeCameraConfig::colour(SurfaceClass c, const Eigen::Vector2d& world) const {
  if (use_target_region &&
      std::find(field_classes.begin(), field_classes.end(), c) != field_classes.end() &&
      !((world.array() >= target_min.array()).all() && (world.array() <= target_max.array()).all()))
    return other_crop_colour;
  switch (c) {
    case SurfaceClass::ground:
      return ground_colour;
    case SurfaceClass::trunk:
      return trunk_colour;
    case SurfaceClass::canopy:
      return canopy_colour;
    case SurfaceClass::post:
      return post_colour;
    case SurfaceClass::wire:
      return wire_colour;
    case SurfaceClass::weed:
      return weed_colour;
    case SurfaceClass::crop:
      return crop_colour;
    case SurfaceClass::crown:
      return crown_colour;
    case SurfaceClass::obstacle:
      return obstacle_colour;
    case SurfaceClass::other:
      return other_colour;
  }
  return other_colour;
}

PinholeCamera::PinholeCamera(const PinholeCameraConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed), texture_seed_(mix(seed)) {
  config_.validate();
  intrinsics_ = config_.intrinsics();
  T_base_camera_ = config_.T_base_camera();
  local_dirs_.reserve(static_cast<std::size_t>(config_.width) * config_.height);
  for (int v = 0; v < config_.height; ++v)
    for (int u = 0; u < config_.width; ++u)  // through the pixel centre
      local_dirs_.push_back(intrinsics_.ray(u + 0.5, v + 0.5).cast<float>());
}

void PinholeCamera::cast_shadows(const RayCaster& world, const Eigen::Vector3f& sun) {
  shadow_idx_.clear();
  for (std::size_t i = 0; i < hits_.size(); ++i)
    if (lambert_[i] > 0.0f) shadow_idx_.push_back(i);
  const std::size_t n = shadow_idx_.size();
  origins_.resize(n);
  dirs_.assign(n, sun);
  const auto bias = static_cast<float>(config_.sun_shadow_bias);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = shadow_idx_[k];
    origins_[k] = points_[i] + bias * hits_[i].normal;  // off the surface, on the lit side
  }
  std::vector<RayHit> shadow(n);
  world.cast_batch(origins_.data(), dirs_.data(), n, 0.0f, static_cast<float>(config_.range_max),
                   shadow.data());
  for (std::size_t k = 0; k < n; ++k)
    if (shadow[k].hit()) lambert_[shadow_idx_[k]] = 0.0f;
}

void PinholeCamera::shade(std::size_t i, std::uint8_t* rgb) {
  std::normal_distribution<float> noise(0.0f, static_cast<float>(config_.pixel_noise_std));
  Eigen::Vector3f c;
  if (!hits_[i].hit()) {
    c = config_.sky_colour.cast<float>();
  } else {
    const Eigen::Vector3f& p = points_[i];
    const auto ambient = static_cast<float>(config_.ambient);
    const float light = ambient + (1.0f - ambient) * lambert_[i];
    const float texture =
        1.0f + static_cast<float>(config_.texture_variation) *
                   texture_value(p, static_cast<float>(config_.texture_cell), texture_seed_);
    c = config_.colour(hits_[i].label, p.head<2>().cast<double>()).cast<float>() *
        (light * texture);
  }
  for (int k = 0; k < 3; ++k)
    rgb[k] =
        static_cast<std::uint8_t>(std::lround(std::clamp(c[k] + noise(rng_), 0.0f, 1.0f) * kByte));
}

core::CameraImage PinholeCamera::render(const RayCaster& world,
                                        const Eigen::Isometry3d& T_world_base, double stamp) {
  core::CameraImage img;
  img.stamp = stamp;
  img.intrinsics = intrinsics_;
  img.T_base_camera = T_base_camera_;
  const std::size_t n = local_dirs_.size();
  img.rgb.resize(n * 3);
  const Eigen::Isometry3f T_world_camera = (T_world_base * T_base_camera_).cast<float>();
  origins_.assign(n, T_world_camera.translation());
  dirs_.resize(n);
  for (std::size_t i = 0; i < n; ++i) dirs_[i] = T_world_camera.linear() * local_dirs_[i];
  hits_.resize(n);
  // A non-finite pose makes every ray miss (RayCaster rejects it): a sky image, no throw.
  world.cast_batch(origins_.data(), dirs_.data(), n, 0.0f, static_cast<float>(config_.range_max),
                   hits_.data());
  const Eigen::Vector3f sun = config_.sun_direction.normalized().cast<float>();
  points_.resize(n);
  lambert_.assign(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    if (!hits_[i].hit()) continue;
    points_[i] = origins_[i] + hits_[i].distance * dirs_[i];
    lambert_[i] = std::max(0.0f, hits_[i].normal.dot(sun));  // normal faces the camera
  }
  if (config_.shadows) cast_shadows(world, sun);
  for (std::size_t i = 0; i < n; ++i) shade(i, img.rgb.data() + 3 * i);
  return img;
}

}  // namespace rownav::sim
