#pragma once
/// @file lidar.hpp Simulated LiDARs: spinning multi-beam (Ouster, Velodyne) and planar (SICK).
///
/// Realism modelled: range noise, dropouts, minimum range (a closer surface still blocks the
/// beam), foliage pass-through (leaf gaps), intensity from the surface class, incidence angle and
/// range, and motion during the sweep (each column cast from the pose at its own time).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/obstacle_box.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Scanner geometry.
enum class LidarKind : std::uint8_t { planar, spinning };

/// LiDAR model. Columns sweep counter-clockwise (seen from above) from azimuth
/// -horizontal_fov/2; a full 360 deg sweep has columns at fov / columns spacing, a partial one
/// (planar 270 deg) includes both ends, fov / (columns - 1).
struct LidarConfig {
  LidarKind kind = LidarKind::spinning;  ///< planar: one horizontal beam fan, rings must be 1
  int columns = 1024;  ///< [-] azimuth steps per revolution (planar: beams), 1..65535
  int rings = 16;      ///< [-] vertical beams (planar: 1), 1..65535; ring 0 is the lowest
  double vertical_fov_min_deg = -16.6;  ///< [deg] lowest ring elevation (evenly spaced rings)
  double vertical_fov_max_deg = 16.6;   ///< [deg] highest ring elevation
  /// [deg] explicit ring elevations, strictly ascending, one per ring (VLP-16 style); empty:
  /// evenly spaced over [vertical_fov_min_deg, vertical_fov_max_deg].
  std::vector<double> vertical_angles_deg;
  double horizontal_fov_deg = 360.0;  ///< [deg] swept azimuth range (planar scanners: 270)
  double rate_hz = 10.0;              ///< [Hz] revolutions (scans) per second
  double range_min = 0.3;             ///< [m] closer returns are dropped (the beam is blocked)
  double range_max = 100.0;           ///< [m] farthest return
  double range_noise_std = 0.01;      ///< [m] gaussian range noise
  double dropout_probability = 0.0;   ///< [-] chance a return is lost, per return
  /// [-] chance a ray passes through a canopy / crown / weed / crop triangle (leaf gaps) and
  /// continues, drawn at every foliage surface it meets (at most 8 passes).
  double foliage_pass_probability = 0.0;
  double intensity_noise_std = 0.05;             ///< [-] relative gaussian noise on intensity
  Eigen::Vector3d mount_xyz{0.3, 0.0, 0.6};      ///< [m] T_base_lidar translation
  Eigen::Vector3d mount_rpy_deg{0.0, 0.0, 0.0};  ///< [deg] T_base_lidar roll, pitch, yaw
  /// [m] largest |mount_xyz| component accepted. A LiDAR sits on the robot, within a few metres
  /// of its base; a far-off mount is a typo, and rays cast from ~1e19 m make Embree abort.
  double max_mount_offset = 100.0;
  /// Pose interpolated per column (rolling shutter); false: every column uses the pose at
  /// the sweep stamp.
  bool motion_during_sweep = true;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("kind", s.kind);
    v("columns", s.columns);
    v("rings", s.rings);
    v("vertical_fov_min_deg", s.vertical_fov_min_deg);
    v("vertical_fov_max_deg", s.vertical_fov_max_deg);
    v("vertical_angles_deg", s.vertical_angles_deg);
    v("horizontal_fov_deg", s.horizontal_fov_deg);
    v("rate_hz", s.rate_hz);
    v("range_min", s.range_min);
    v("range_max", s.range_max);
    v("range_noise_std", s.range_noise_std);
    v("dropout_probability", s.dropout_probability);
    v("foliage_pass_probability", s.foliage_pass_probability);
    v("intensity_noise_std", s.intensity_noise_std);
    v("mount_xyz", s.mount_xyz);
    v("mount_rpy_deg", s.mount_rpy_deg);
    v("max_mount_offset", s.max_mount_offset);
    v("motion_during_sweep", s.motion_during_sweep);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
  /// Mounting transform: LiDAR frame to base frame (rotation Rz(yaw) Ry(pitch) Rx(roll)).
  Eigen::Isometry3d T_base_lidar() const;
  /// [rad] elevation of every ring, ring 0 first.
  std::vector<double> ring_elevations() const;
  /// [rad] azimuth step between adjacent columns.
  double azimuth_increment() const;
};

/// Pose source: T_world_base at absolute time t [s] (the simulator interpolates the robot
/// trajectory, terrain z / roll / pitch included). A Lidar evaluates it at the sweep stamp and
/// every 16th column (and the last), and interpolates the columns in between (lerp + slerp).
using PoseAt = std::function<Eigen::Isometry3d(double t)>;

/// A simulated LiDAR. Not thread-safe (owns its random generator); use one per thread.
class Lidar {
 public:
  /// Validates the config (throws std::invalid_argument) and precomputes the ray directions.
  Lidar(const LidarConfig& config, std::uint64_t seed);

  /// One revolution starting at `stamp`, in the LiDAR frame of each point's own measurement
  /// time. Column c is measured at stamp + c * azimuth_increment / (2 pi rate_hz) (= c / (rate_hz
  /// * columns) for 360 deg), which is each point's `time`; `ring` and `column` filled; points
  /// ordered by column then ring; rays without a return omitted. `labels` (optional) receives
  /// the surface class of every point (ground truth). Does not throw.
  core::PointCloud sweep(const RayCaster& world, const PoseAt& T_world_base_at, double stamp,
                         std::vector<SurfaceClass>* labels = nullptr);

  /// One planar scan in the LiDAR frame, beams counter-clockwise from -fov/2; no return = +inf,
  /// a surface closer than range_min = NaN. For a spinning config, the ring nearest to 0 deg
  /// elevation is used. `labels` (optional) gets one class per beam (`other` without a return).
  /// Does not throw.
  core::Scan2D scan(const RayCaster& world, const PoseAt& T_world_base_at, double stamp,
                    std::vector<SurfaceClass>* labels = nullptr);

  const LidarConfig& config() const { return config_; }

  /// Boxes outside the static scene (a walking person) that the next sweeps / scans also hit,
  /// labelled `obstacle`; empty: none (the default).
  void set_obstacles(std::vector<ObstacleBox> boxes) { obstacles_ = std::move(boxes); }

 private:
  /// Replaces a hit by a nearer one on an obstacle box.
  void cast_obstacles();
  /// Casts every (column, ring in `rings`) ray into hits_ (foliage passes included).
  void cast_all(const RayCaster& world, const PoseAt& pose_at, double stamp,
                const std::vector<int>& rings);
  /// T_world_lidar of every column into column_pose_ (PoseAt at knots, interpolated between).
  void update_column_poses(const PoseAt& pose_at, double stamp);
  /// Re-casts rays that pass through foliage (leaf gaps), in rounds, from just past the leaf.
  void pass_foliage(const RayCaster& world);
  /// Applies min range, dropout and noise to hits_[i]: measured range [m], +inf without a
  /// return (miss, dropout, beyond range_max), NaN when the surface is closer than range_min.
  float measure(std::size_t i, float& intensity);
  /// Uniform in [0, 1) from 24 bits of rng_.
  float uniform01() { return static_cast<float>(rng_() >> 40) * 0x1p-24f; }
  /// Standard normal by Box-Muller, two values per draw of rng_ (half the cost of
  /// std::normal_distribution's one draw per uniform; the sensor model draws one or two a ray).
  float gaussian();

  LidarConfig config_;
  std::mt19937_64 rng_;
  Eigen::Isometry3d T_base_lidar_;
  double column_dt_ = 0.0;                   // [s] between columns
  std::size_t packet_columns_ = 16;          // columns in one 16-ray packet (see cast_all)
  std::vector<Eigen::Vector3f> local_dirs_;  // column-major: [c * rings + r], LiDAR frame
  std::vector<int> all_rings_;               // 0..rings-1
  std::vector<int> planar_ring_;             // the ring scan() uses
  // Per-call buffers, kept to avoid allocations per frame.
  std::vector<Eigen::Vector3f> origins_, dirs_, sub_origins_, sub_dirs_;
  std::vector<float> sub_tmin_;
  std::vector<RayHit> hits_, sub_hits_;
  std::vector<std::size_t> pass_idx_;
  std::vector<std::uint32_t> order_;  // column-major ray (c * rings + k) -> position in the cast
  std::vector<Eigen::Isometry3f> column_pose_;  // T_world_lidar of each column
  std::vector<ObstacleBox> obstacles_;
  float spare_gaussian_ = 0.0f;  // second Box-Muller value, used by the next gaussian()
  bool has_spare_ = false;
};

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::LidarKind> {
  using E = rownav::sim::LidarKind;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::planar, "planar"}, {E::spinning, "spinning"}}};
};
