#include "rownav/sim/lidar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rownav/core/angle.hpp"

namespace rownav::sim {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kMaxFoliagePasses = 8;
constexpr float kPassEpsilon = 0.02f;       // [m] a passed ray continues this far past the leaf
constexpr int kKnotStride = 16;             // columns between exact PoseAt evaluations
constexpr std::size_t kPacket = 16;         // rays per Embree packet (RayCaster::cast_batch)
constexpr float kIntensityFalloff = 30.0f;  // [m] range at which intensity halves

bool is_foliage(SurfaceClass c) {
  return c == SurfaceClass::canopy || c == SurfaceClass::crown || c == SurfaceClass::weed ||
         c == SurfaceClass::crop;
}

/// Near-infrared reflectivity by surface class (0..1): leaves reflect NIR strongly, bark and
/// soil less, galvanised wire and posts most.
float reflectivity(SurfaceClass c) {
  switch (c) {
    case SurfaceClass::ground:
      return 0.25f;
    case SurfaceClass::trunk:
      return 0.35f;
    case SurfaceClass::canopy:
    case SurfaceClass::crown:
    case SurfaceClass::crop:
      return 0.5f;
    case SurfaceClass::weed:
      return 0.45f;
    case SurfaceClass::post:
      return 0.6f;
    case SurfaceClass::wire:
      return 0.8f;
    case SurfaceClass::obstacle:
      return 0.4f;
    case SurfaceClass::other:
      break;
  }
  return 0.3f;
}

/// Pose between two knots: translation lerped, rotation slerped.
Eigen::Isometry3f interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double f) {
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = qa.slerp(f, qb).toRotationMatrix();
  out.translation() = (1.0 - f) * a.translation() + f * b.translation();
  return out.cast<float>();
}

}  // namespace

Lidar::Lidar(const LidarConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed), T_base_lidar_(config.T_base_lidar()) {
  config_.validate();
  const double inc = config_.azimuth_increment();
  const double a0 = -0.5 * core::deg2rad(config_.horizontal_fov_deg);
  column_dt_ = inc / (2.0 * std::numbers::pi * config_.rate_hz);
  if (config_.horizontal_fov_deg >= 360.0 - 1e-9)
    column_dt_ = 1.0 / (config_.rate_hz * config_.columns);
  const auto elev = config_.ring_elevations();
  local_dirs_.reserve(std::size_t(config_.columns) * elev.size());
  for (int c = 0; c < config_.columns; ++c) {
    const double a = a0 + c * inc;
    for (const double e : elev)
      local_dirs_.emplace_back(static_cast<float>(std::cos(e) * std::cos(a)),
                               static_cast<float>(std::cos(e) * std::sin(a)),
                               static_cast<float>(std::sin(e)));
  }
  for (int r = 0; r < config_.rings; ++r) all_rings_.push_back(r);
  const auto flat = std::min_element(elev.begin(), elev.end(),
                                     [](double x, double y) { return std::abs(x) < std::abs(y); });
  planar_ring_ = {static_cast<int>(flat - elev.begin())};
  // Packets of pc columns x (16 / pc) rings, pc a power of two, a little wider in azimuth than
  // square: in the generated high-canopy vineyard (bench/sim_drive_bench.cpp) the OS1-64 sweep
  // took 10.1 ms with square patches and 9.8 ms with these (8 columns x 2 rings).
  const double ring_step =
      elev.size() > 1 ? (elev.back() - elev.front()) / double(elev.size() - 1) : 0.0;
  const double ideal = inc > 0.0 ? std::sqrt(double(kPacket) * ring_step / inc) : 1.0;
  packet_columns_ = 1;
  while (packet_columns_ < kPacket && double(packet_columns_) * 0.7 < ideal) packet_columns_ *= 2;
}

void Lidar::update_column_poses(const PoseAt& pose_at, double stamp) {
  const int cols = config_.columns;
  // T_world_lidar per column: exact at every kKnotStride-th column, interpolated in between.
  column_pose_.resize(std::size_t(cols));
  const bool moving = config_.motion_during_sweep;
  Eigen::Isometry3d k0 = pose_at(stamp) * T_base_lidar_, k1 = k0;
  for (int c0 = 0; c0 < cols; c0 += kKnotStride) {
    const int c1 = std::min(c0 + kKnotStride, cols - 1);
    if (moving && c0 > 0) k0 = k1;
    if (moving && c1 > c0) k1 = pose_at(stamp + c1 * column_dt_) * T_base_lidar_;
    for (int c = c0; c < std::min(c0 + kKnotStride, cols); ++c)
      column_pose_[std::size_t(c)] =
          moving && c1 > c0 ? interpolate(k0, k1, double(c - c0) / (c1 - c0)) : k0.cast<float>();
  }
}

void Lidar::cast_all(const RayCaster& world, const PoseAt& pose_at, double stamp,
                     const std::vector<int>& rings) {
  update_column_poses(pose_at, stamp);
  const std::size_t nsel = rings.size(), C = std::size_t(config_.columns), n = C * nsel;
  origins_.resize(n);
  dirs_.resize(n);
  hits_.resize(n);
  order_.resize(n);
  // Packet order: within each block of pc columns, ring by ring, so that a packet of 16 rays is
  // a compact pc x (16 / pc) patch of adjacent columns and rings (a few degrees wide) rather
  // than one column's fan of rings (tens of degrees): Embree's packet traversal then visits far
  // fewer BVH nodes (OS1-16 sweep 5.1 -> 2.6 ms in bench/lidar_bench.cpp).
  const std::size_t R = std::size_t(config_.rings);
  const std::size_t pc = nsel == 1 ? kPacket : packet_columns_;
  for (std::size_t b0 = 0; b0 < C; b0 += pc) {
    const std::size_t w = std::min(pc, C - b0);
    for (std::size_t j = 0; j < w; ++j) {
      const std::size_t c = b0 + j;
      const Eigen::Matrix3f rot = column_pose_[c].linear();
      const Eigen::Vector3f o = column_pose_[c].translation();
      for (std::size_t k = 0; k < nsel; ++k) {
        const std::size_t i = b0 * nsel + k * w + j;
        order_[c * nsel + k] = static_cast<std::uint32_t>(i);
        origins_[i] = o;
        dirs_[i] = rot * local_dirs_[c * R + std::size_t(rings[k])];
      }
    }
  }
  const auto t_max = static_cast<float>(config_.range_max);
  world.cast_batch(origins_.data(), dirs_.data(), n, 0.0f, t_max, hits_.data());
  if (config_.foliage_pass_probability > 0.0) pass_foliage(world);
  if (!obstacles_.empty()) cast_obstacles();
}

void Lidar::cast_obstacles() {
  for (std::size_t i = 0; i < hits_.size(); ++i)
    for (const auto& box : obstacles_) {
      const float reach = std::min(hits_[i].distance, static_cast<float>(config_.range_max));
      const auto h = intersect(box, origins_[i], dirs_[i], reach);
      if (!h || h->distance >= hits_[i].distance) continue;
      hits_[i].distance = h->distance;
      hits_[i].label = SurfaceClass::obstacle;
      hits_[i].normal = h->normal;
    }
}

void Lidar::pass_foliage(const RayCaster& world) {
  const std::size_t n = hits_.size();
  const auto t_max = static_cast<float>(config_.range_max);
  const auto p = static_cast<float>(config_.foliage_pass_probability);
  pass_idx_.resize(n);
  for (std::size_t i = 0; i < n; ++i) pass_idx_[i] = i;
  for (int round = 0; round < kMaxFoliagePasses && !pass_idx_.empty(); ++round) {
    std::size_t m = 0;  // compact to the rays that pass through a leaf this round
    for (const std::size_t i : pass_idx_)
      if (hits_[i].hit() && is_foliage(hits_[i].label) && uniform01() < p) pass_idx_[m++] = i;
    pass_idx_.resize(m);
    sub_origins_.resize(m);
    sub_dirs_.resize(m);
    sub_tmin_.resize(m);
    sub_hits_.resize(m);
    for (std::size_t j = 0; j < m; ++j) {
      sub_origins_[j] = origins_[pass_idx_[j]];
      sub_dirs_[j] = dirs_[pass_idx_[j]];
      sub_tmin_[j] = hits_[pass_idx_[j]].distance + kPassEpsilon;
    }
    world.cast_batch(sub_origins_.data(), sub_dirs_.data(), m, sub_tmin_.data(), t_max,
                     sub_hits_.data());
    for (std::size_t j = 0; j < m; ++j) hits_[pass_idx_[j]] = sub_hits_[j];
  }
}

float Lidar::gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_gaussian_;
  }
  const std::uint64_t bits = rng_();
  // u1 in (0, 1] so the log is finite; u2 in [0, 1).
  const float u1 = static_cast<float>((bits >> 40) + 1) * 0x1p-24f;
  const float u2 = static_cast<float>((bits >> 8) & 0xFFFFFFu) * 0x1p-24f;
  const float rad = std::sqrt(-2.0f * std::log(u1));
  const float a = 2.0f * std::numbers::pi_v<float> * u2;
  spare_gaussian_ = rad * std::sin(a);
  has_spare_ = true;
  return rad * std::cos(a);
}

float Lidar::measure(std::size_t i, float& intensity) {
  const RayHit& h = hits_[i];
  intensity = 0.0f;
  if (!h.hit()) return kInf;
  if (h.distance < config_.range_min) return std::numeric_limits<float>::quiet_NaN();
  if (config_.dropout_probability > 0.0 &&
      uniform01() < static_cast<float>(config_.dropout_probability))
    return kInf;
  float r = h.distance;
  if (config_.range_noise_std > 0.0) r += static_cast<float>(config_.range_noise_std) * gaussian();
  if (r < config_.range_min || r > config_.range_max) return kInf;
  const float cos_inc = std::abs(h.normal.dot(dirs_[i]));
  const float fall = r / kIntensityFalloff;
  float value = 255.0f * reflectivity(h.label) * (0.3f + 0.7f * cos_inc) / (1.0f + fall * fall);
  if (config_.intensity_noise_std > 0.0)
    value *= 1.0f + static_cast<float>(config_.intensity_noise_std) * gaussian();
  intensity = std::clamp(value, 0.0f, 255.0f);
  return r;
}

core::PointCloud Lidar::sweep(const RayCaster& world, const PoseAt& T_world_base_at, double stamp,
                              std::vector<SurfaceClass>* labels) {
  core::PointCloud cloud;
  cloud.stamp = stamp;
  cloud.has_intensity = cloud.has_ring = cloud.has_time = true;
  if (labels) labels->clear();
  cast_all(world, T_world_base_at, stamp, all_rings_);
  const std::size_t R = std::size_t(config_.rings);
  cloud.points.reserve(hits_.size());
  if (labels) labels->reserve(hits_.size());
  for (std::size_t i = 0; i < hits_.size(); ++i) {  // column-major output order
    float intensity = 0.0f;
    const std::size_t j = order_[i];
    const float r = measure(j, intensity);
    if (!std::isfinite(r)) continue;
    const Eigen::Vector3f p = local_dirs_[i] * r;
    core::PointXYZIRT& q = cloud.points.emplace_back();
    q.x = p.x();
    q.y = p.y();
    q.z = p.z();
    q.intensity = intensity;
    q.ring = static_cast<std::uint16_t>(i % R);
    q.column = static_cast<std::uint16_t>(i / R);
    q.time = static_cast<float>(static_cast<double>(i / R) * column_dt_);
    if (labels) labels->push_back(hits_[j].label);
  }
  return cloud;
}

core::Scan2D Lidar::scan(const RayCaster& world, const PoseAt& T_world_base_at, double stamp,
                         std::vector<SurfaceClass>* labels) {
  core::Scan2D s;
  s.stamp = stamp;
  s.angle_min = -0.5 * core::deg2rad(config_.horizontal_fov_deg);
  s.angle_increment = config_.azimuth_increment();
  s.time_increment = column_dt_;
  s.range_min = config_.range_min;
  s.range_max = config_.range_max;
  cast_all(world, T_world_base_at, stamp, planar_ring_);
  s.ranges.resize(hits_.size());
  s.intensities.resize(hits_.size());
  if (labels) labels->assign(hits_.size(), SurfaceClass::other);
  for (std::size_t i = 0; i < hits_.size(); ++i) {
    s.ranges[i] = measure(order_[i], s.intensities[i]);
    if (labels && std::isfinite(s.ranges[i])) (*labels)[i] = hits_[order_[i]].label;
  }
  return s;
}

}  // namespace rownav::sim
