#pragma once
/// @file pinhole_camera.hpp Simulated pinhole RGB camera rendered by the LiDAR's ray caster: the
/// camera of Emmi 2021 (002_806e72d300173f73.txt, Fig. 2b: laser points labelled by the crop
/// detected in the image). One primary ray per pixel, a colour per surface class (the crop of a
/// neighbouring field may have its own colour), Lambertian shading from the sun with a shadow
/// ray, seeded per-pixel noise and a world-fixed texture, the sky's colour for misses.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "rownav/core/camera_image.hpp"
#include "rownav/core/config_fields.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Camera model. Colours are reflectances in [0, 1] (R, G, B); the image is
/// colour x (ambient + (1 - ambient) x sun term) x variation, clamped, times 255.
struct PinholeCameraConfig {
  int width = 320;   ///< [px] image columns (rownav; Emmi 2021's cameras: 752 x 480)
  int height = 240;  ///< [px] image rows
  /// [deg] horizontal field of view; fx = fy = width / (2 tan(fov / 2)), principal point at the
  /// image centre (Emmi 2021 sec. "Experimental set-up": about 107 deg on the Oz; rownav
  /// measured: 90 deg misses the rows beside the robot in a 2.8 m vineyard, BENCHMARK.md)
  double horizontal_fov_deg = 107.0;
  Eigen::Vector3d mount_xyz{0.4, 0.0, 0.8};  ///< [m] camera position in the base frame (rownav)
  /// [deg] roll, pitch, yaw of the camera body (x along the view) in the base frame, rotation
  /// Rz(yaw) Ry(pitch) Rx(roll) as the LiDAR mount; pitch > 0 looks down (rownav)
  Eigen::Vector3d mount_rpy_deg{0.0, 25.0, 0.0};
  double max_mount_offset = 100.0;  ///< [m] largest |mount_xyz| component (a typo guard, as LiDARs)
  double range_max = 60.0;          ///< [m] farther surfaces show the sky (rownav)
  /// [-] direction towards the sun, world frame (normalised on use; z > 0: above the horizon)
  Eigen::Vector3d sun_direction{-0.4, 0.3, 0.85};
  double ambient = 0.35;            ///< [-] share of light reaching shadowed surfaces (sky light)
  bool shadows = true;              ///< cast a shadow ray towards the sun from every lit hit
  double texture_variation = 0.15;  ///< [-] relative brightness amplitude of a world-fixed texture
  double texture_cell = 0.04;       ///< [m] cell of that texture (leaves, soil clods)
  double pixel_noise_std = 0.02;    ///< [-] gaussian noise per channel and pixel (sensor noise)
  double sun_shadow_bias = 0.01;    ///< [m] shadow rays start this far off the surface (acne)
  Eigen::Vector3d sky_colour{0.55, 0.70, 0.90};       ///< [-] misses
  Eigen::Vector3d ground_colour{0.45, 0.35, 0.25};    ///< [-] bare soil
  Eigen::Vector3d crop_colour{0.42, 0.62, 0.12};      ///< [-] target crop plants (yellow-green)
  Eigen::Vector3d canopy_colour{0.30, 0.55, 0.15};    ///< [-] vine foliage
  Eigen::Vector3d crown_colour{0.25, 0.50, 0.15};     ///< [-] tree crowns
  Eigen::Vector3d trunk_colour{0.35, 0.25, 0.18};     ///< [-] trunks
  Eigen::Vector3d post_colour{0.55, 0.55, 0.52};      ///< [-] posts
  Eigen::Vector3d wire_colour{0.60, 0.60, 0.60};      ///< [-] wires
  Eigen::Vector3d weed_colour{0.30, 0.45, 0.22};      ///< [-] weeds, grass
  Eigen::Vector3d obstacle_colour{0.20, 0.25, 0.60};  ///< [-] obstacles (a person's clothes)
  Eigen::Vector3d other_colour{0.50, 0.50, 0.50};     ///< [-] anything else
  /// Surfaces of a crop classes outside [target_min, target_max] (world x, y) take
  /// other_crop_colour: a neighbouring field of another crop (as sim::TruthLabeller's region).
  bool use_target_region = false;
  Eigen::Vector2d target_min = Eigen::Vector2d::Zero();  ///< [m] world, lower corner
  Eigen::Vector2d target_max = Eigen::Vector2d::Zero();  ///< [m] world, upper corner
  /// classes recoloured outside the target region (the plants of a field)
  std::vector<SurfaceClass> field_classes{SurfaceClass::crop, SurfaceClass::canopy,
                                          SurfaceClass::crown};
  /// [-] the neighbouring field's crop (blue-green, like cabbage or leek beside a yellow-green
  /// crop)
  Eigen::Vector3d other_crop_colour{0.22, 0.48, 0.42};

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("width", s.width);
    v("height", s.height);
    v("horizontal_fov_deg", s.horizontal_fov_deg);
    v("mount_xyz", s.mount_xyz);
    v("mount_rpy_deg", s.mount_rpy_deg);
    v("max_mount_offset", s.max_mount_offset);
    v("range_max", s.range_max);
    v("sun_direction", s.sun_direction);
    v("ambient", s.ambient);
    v("shadows", s.shadows);
    v("texture_variation", s.texture_variation);
    v("texture_cell", s.texture_cell);
    v("pixel_noise_std", s.pixel_noise_std);
    v("sun_shadow_bias", s.sun_shadow_bias);
    v("sky_colour", s.sky_colour);
    v("ground_colour", s.ground_colour);
    v("crop_colour", s.crop_colour);
    v("canopy_colour", s.canopy_colour);
    v("crown_colour", s.crown_colour);
    v("trunk_colour", s.trunk_colour);
    v("post_colour", s.post_colour);
    v("wire_colour", s.wire_colour);
    v("weed_colour", s.weed_colour);
    v("obstacle_colour", s.obstacle_colour);
    v("other_colour", s.other_colour);
    v("use_target_region", s.use_target_region);
    v("target_min", s.target_min);
    v("target_max", s.target_max);
    v("field_classes", s.field_classes);
    v("other_crop_colour", s.other_crop_colour);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
  /// Pinhole intrinsics from width, height and the horizontal field of view.
  core::CameraIntrinsics intrinsics() const;
  /// Optical frame (z along the view, x right, y down) to base frame.
  Eigen::Isometry3d T_base_camera() const;
  /// Reflectance of a surface class at world (x, y) (the target region decides a crop's colour).
  Eigen::Vector3d colour(SurfaceClass c, const Eigen::Vector2d& world) const;
};

/// A simulated camera. Not thread-safe (owns its random generator and buffers).
class PinholeCamera {
 public:
  /// Validates the config (throws std::invalid_argument) and precomputes the pixel rays.
  PinholeCamera(const PinholeCameraConfig& config, std::uint64_t seed);

  /// Renders the view from robot pose T_world_base at `stamp`. Does not throw; a non-finite
  /// pose gives a sky-coloured image.
  core::CameraImage render(const RayCaster& world, const Eigen::Isometry3d& T_world_base,
                           double stamp);

  const PinholeCameraConfig& config() const { return config_; }

 private:
  /// Shadow rays: clears lit_[i] for hits that do not see the sun.
  void cast_shadows(const RayCaster& world, const Eigen::Vector3f& sun);
  /// Colour of pixel i into rgb (3 bytes).
  void shade(std::size_t i, std::uint8_t* rgb);

  PinholeCameraConfig config_;
  std::mt19937_64 rng_;
  std::uint64_t texture_seed_;
  core::CameraIntrinsics intrinsics_;
  Eigen::Isometry3d T_base_camera_;
  std::vector<Eigen::Vector3f> local_dirs_;  // optical frame, row-major pixels
  // Per-render buffers.
  std::vector<Eigen::Vector3f> origins_, dirs_, points_;
  std::vector<RayHit> hits_;
  std::vector<float> lambert_;
  std::vector<std::size_t> shadow_idx_;
};

}  // namespace rownav::sim
