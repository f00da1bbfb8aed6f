/// @file lidar_presets.cpp LidarConfig: validation, derived geometry and the named presets.
#include "rownav/sim/lidar_presets.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rownav/core/angle.hpp"

namespace rownav::sim {

namespace {

/// Ouster OS1 rev. 6 datasheet: 1024 x 10 Hz, 0.3 m minimum range, ~1.5 cm range precision.
LidarConfig os1(int rings, double half_vfov_deg) {
  LidarConfig c;
  c.kind = LidarKind::spinning;
  c.columns = 1024;
  c.rings = rings;
  c.vertical_fov_min_deg = -half_vfov_deg;
  c.vertical_fov_max_deg = half_vfov_deg;
  c.rate_hz = 10.0;
  c.range_min = 0.3;
  c.range_max = 120.0;
  c.range_noise_std = 0.015;
  return c;
}

/// Velodyne VLP-16 datasheet: 16 lasers -15..+15 deg every 2 deg, 0.2 deg azimuth at 10 Hz,
/// 100 m, +-3 cm accuracy.
LidarConfig vlp16() {
  LidarConfig c;
  c.kind = LidarKind::spinning;
  c.columns = 1800;
  c.rings = 16;
  for (int r = 0; r < 16; ++r) c.vertical_angles_deg.push_back(-15.0 + 2.0 * r);
  c.vertical_fov_min_deg = -15.0;
  c.vertical_fov_max_deg = 15.0;
  c.rate_hz = 10.0;
  c.range_min = 0.4;
  c.range_max = 100.0;
  c.range_noise_std = 0.03;
  return c;
}

/// SICK 2D scanners: 270 deg fan, `beams` over it inclusive of both ends.
LidarConfig sick(int beams, double range_min, double range_max, double rate_hz, double noise) {
  LidarConfig c;
  c.kind = LidarKind::planar;
  c.columns = beams;
  c.rings = 1;
  c.vertical_fov_min_deg = 0.0;
  c.vertical_fov_max_deg = 0.0;
  c.horizontal_fov_deg = 270.0;
  c.rate_hz = rate_hz;
  c.range_min = range_min;
  c.range_max = range_max;
  c.range_noise_std = noise;
  return c;
}

}  // namespace

void LidarConfig::validate() const {
  using core::check;
  core::check_range(columns, 1, 65535, "columns");
  core::check_range(rings, 1, 65535, "rings");
  check(kind != LidarKind::planar || rings == 1, "rings", "must be 1 for a planar LiDAR");
  check(vertical_angles_deg.empty() || vertical_angles_deg.size() == std::size_t(rings),
        "vertical_angles_deg", "must be empty or hold one elevation per ring");
  for (std::size_t i = 0; i < vertical_angles_deg.size(); ++i) {
    core::check_range(vertical_angles_deg[i], -90.0, 90.0, "vertical_angles_deg");
    check(i == 0 || vertical_angles_deg[i] > vertical_angles_deg[i - 1], "vertical_angles_deg",
          "must be strictly ascending");
  }
  core::check_range(vertical_fov_min_deg, -90.0, 90.0, "vertical_fov_min_deg");
  core::check_range(vertical_fov_max_deg, -90.0, 90.0, "vertical_fov_max_deg");
  check(vertical_fov_max_deg > vertical_fov_min_deg || rings == 1 || !vertical_angles_deg.empty(),
        "vertical_fov_max_deg", "must be > vertical_fov_min_deg");
  check(horizontal_fov_deg > 0.0 && horizontal_fov_deg <= 360.0, "horizontal_fov_deg",
        "must be in (0, 360]");
  core::check_positive(rate_hz, "rate_hz");
  core::check_non_negative(range_min, "range_min");
  check(range_max > range_min && std::isfinite(range_max), "range_max",
        "must be finite and > range_min");
  core::check_non_negative(range_noise_std, "range_noise_std");
  core::check_range(dropout_probability, 0.0, 1.0, "dropout_probability");
  core::check_range(foliage_pass_probability, 0.0, 1.0, "foliage_pass_probability");
  core::check_non_negative(intensity_noise_std, "intensity_noise_std");
  check(std::isfinite(max_mount_offset) && max_mount_offset > 0.0, "max_mount_offset",
        "must be finite and > 0");
  check(mount_xyz.allFinite(), "mount_xyz", "must be finite");
  check(mount_xyz.cwiseAbs().maxCoeff() <= max_mount_offset, "mount_xyz",
        "every component must be within +-max_mount_offset = " +
            core::detail::show(max_mount_offset) + " m (got [" + core::detail::show(mount_xyz.x()) +
            ", " + core::detail::show(mount_xyz.y()) + ", " + core::detail::show(mount_xyz.z()) +
            "])");
  check(mount_rpy_deg.allFinite(), "mount_rpy_deg", "must be finite");
}

Eigen::Isometry3d LidarConfig::T_base_lidar() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(core::deg2rad(mount_rpy_deg.z()), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(core::deg2rad(mount_rpy_deg.y()), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(core::deg2rad(mount_rpy_deg.x()), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = mount_xyz;
  return T;
}

std::vector<double> LidarConfig::ring_elevations() const {
  std::vector<double> out(static_cast<std::size_t>(std::max(rings, 0)));
  for (std::size_t r = 0; r < out.size(); ++r) {
    if (!vertical_angles_deg.empty()) {
      out[r] = core::deg2rad(vertical_angles_deg[r]);
    } else if (rings == 1) {
      out[r] = core::deg2rad(0.5 * (vertical_fov_min_deg + vertical_fov_max_deg));
    } else {
      const double f = static_cast<double>(r) / (rings - 1);
      out[r] =
          core::deg2rad(vertical_fov_min_deg + f * (vertical_fov_max_deg - vertical_fov_min_deg));
    }
  }
  return out;
}

double LidarConfig::azimuth_increment() const {
  const double fov = core::deg2rad(horizontal_fov_deg);
  if (horizontal_fov_deg >= 360.0 - 1e-9) return fov / columns;
  return columns > 1 ? fov / (columns - 1) : 0.0;
}

std::vector<std::string> lidar_preset_names() {
  return {"os1_16", "os1_64", "vlp16", "sick_tim571", "sick_lms111", "lms_1081"};
}

LidarConfig lidar_preset(std::string_view name) {
  if (name == "os1_16") return os1(16, 16.6);
  if (name == "os1_64") return os1(64, 22.5);
  if (name == "vlp16") return vlp16();
  // TiM571: 0.33 deg, 15 Hz, 0.05-25 m, statistical error 20 mm.
  if (name == "sick_tim571") return sick(811, 0.05, 25.0, 15.0, 0.02);
  // LMS111: 0.5 deg, 25 Hz, 0.5-20 m, statistical error 12 mm.
  if (name == "sick_lms111") return sick(541, 0.5, 20.0, 25.0, 0.012);
  // LMS1xx at 0.25 deg / 25 Hz as on the Oz robot (real corn data set), 10 m useful range.
  if (name == "lms_1081") return sick(1081, 0.05, 10.0, 25.0, 0.012);
  std::string valid;
  for (const auto& n : lidar_preset_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("lidar preset '" + std::string(name) + "' unknown; valid: " + valid);
}

}  // namespace rownav::sim
