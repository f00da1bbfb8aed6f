#include "rownav/sim/ray_caster.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace rownav::sim {

namespace {

constexpr int kPacket = 16;

/// Embree asserts (and aborts) on a ray whose origin or direction component exceeds its
/// FLT_LARGE (1.844e18): such rays miss instead. Inputs are bounded long before (a LiDAR mount
/// within LidarConfig::max_mount_offset, a layout within LayoutLimits::max_extent); this is the
/// last guard, so no input reaches the assertion.
constexpr float kMaxRayCoordinate = 1e18f;

bool castable(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir) {
  return origin.allFinite() && dir.allFinite() &&
         origin.cwiseAbs().maxCoeff() <= kMaxRayCoordinate &&
         dir.cwiseAbs().maxCoeff() <= kMaxRayCoordinate;
}

/// Flush-to-zero / denormals-are-zero for the duration of a query, as Embree recommends
/// (denormals slow traversal down); the caller's floating-point mode is restored afterwards.
class FlushDenormals {
 public:
#if defined(__SSE__)
  FlushDenormals() : saved_(_mm_getcsr()) {
    _mm_setcsr(saved_ | 0x8040u);
  }  // FTZ | DAZ
  ~FlushDenormals() {
    _mm_setcsr(saved_);
  }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned saved_;
#endif
};

void throw_on_error(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("RayCaster: Embree error ") + std::to_string(e) + " in " +
                             what);
}

void check_mesh(const TriangleMesh& world) {
  if (world.empty()) throw std::invalid_argument("RayCaster: world mesh has no triangles");
  if (world.labels.size() != world.triangles.size())
    throw std::invalid_argument("RayCaster: world mesh labels (" +
                                std::to_string(world.labels.size()) + ") != triangles (" +
                                std::to_string(world.triangles.size()) + ")");
  const auto nv = world.vertices.size();
  for (const auto& t : world.triangles)
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
      throw std::invalid_argument("RayCaster: world mesh triangle index out of range");
}

/// Unit normal of a counter-clockwise triangle (zero when degenerate).
Eigen::Vector3f unit_normal(const TriangleMesh& m, const std::array<std::uint32_t, 3>& t) {
  const Eigen::Vector3f n =
      (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
  const float len = n.norm();
  return len > 0.0f && std::isfinite(len) ? Eigen::Vector3f(n / len) : Eigen::Vector3f::Zero();
}

}  // namespace

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<SurfaceClass> labels;
  std::vector<Eigen::Vector3f> normals;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void build(const TriangleMesh& world) {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("RayCaster: rtcNewDevice failed");
    scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          world.vertices.size()));
    auto* idx = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), world.triangles.size()));
    if (!v || !idx) {
      rtcReleaseGeometry(geom);
      throw_on_error(device, "rtcSetNewGeometryBuffer");
      throw std::runtime_error("RayCaster: geometry buffer allocation failed");
    }
    for (std::size_t i = 0; i < world.vertices.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = world.vertices[i][k];
    normals.resize(world.triangles.size());
    for (std::size_t i = 0; i < world.triangles.size(); ++i) {
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = world.triangles[i][k];
      normals[i] = unit_normal(world, world.triangles[i]);
    }
    labels = world.labels;
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    throw_on_error(device, "rtcCommitScene");
  }

  /// Fills a RayHit from an Embree primitive id and the ray direction.
  void fill(unsigned prim, float t, const Eigen::Vector3f& dir, RayHit& out) const {
    out.distance = t;
    out.label = labels[prim];
    const Eigen::Vector3f& n = normals[prim];
    out.normal = n.dot(dir) > 0.0f ? Eigen::Vector3f(-n) : n;
  }

  void cast16(const Eigen::Vector3f* o, const Eigen::Vector3f* d, int count, const float* t_min,
              float t_min_all, float t_max, RayHit* out) const;
};

void RayCaster::Impl::cast16(const Eigen::Vector3f* o, const Eigen::Vector3f* d, int count,
                             const float* t_min, float t_min_all, float t_max, RayHit* out) const {
  alignas(64) int valid[kPacket];
  alignas(64) RTCRayHit16 rh;
  for (int i = 0; i < kPacket; ++i) {
    const int j = i < count ? i : count - 1;
    const float tn = t_min ? t_min[j] : t_min_all;
    valid[i] = i < count && castable(o[j], d[j]) && tn <= t_max ? -1 : 0;
    // An inactive lane still holds a well-formed ray: Debian's Embree 3.13.5 asserts on every
    // lane's ray in its coherent packet path, not only on the active ones (issue 13: a LiDAR
    // mounted at 1e19 m aborted the simulator).
    const Eigen::Vector3f org = valid[i] ? o[j] : Eigen::Vector3f::Zero();
    const Eigen::Vector3f dir = valid[i] ? d[j] : Eigen::Vector3f::UnitZ();
    rh.ray.org_x[i] = org.x();
    rh.ray.org_y[i] = org.y();
    rh.ray.org_z[i] = org.z();
    rh.ray.dir_x[i] = dir.x();
    rh.ray.dir_y[i] = dir.y();
    rh.ray.dir_z[i] = dir.z();
    rh.ray.tnear[i] = valid[i] ? tn : 0.0f;
    rh.ray.tfar[i] = valid[i] ? t_max : 0.0f;
    rh.ray.time[i] = 0.0f;
    rh.ray.mask[i] = 0xFFFFFFFFu;
    rh.ray.id[i] = static_cast<unsigned>(i);
    rh.ray.flags[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect16(valid, scene, &ctx, &rh);
  for (int i = 0; i < count; ++i) {
    out[i] = RayHit{};
    if (valid[i] && rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID)
      fill(rh.hit.primID[i], rh.ray.tfar[i], d[i], out[i]);
  }
}

RayCaster::RayCaster(const TriangleMesh& world) : impl_(std::make_unique<Impl>()) {
  check_mesh(world);
  impl_->build(world);
}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

RayHit RayCaster::cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& unit_dir, float t_min,
                       float t_max) const {
  RayHit out;
  if (!castable(origin, unit_dir) || !(t_min <= t_max)) return out;
  RTCRayHit rh;
  rh.ray.org_x = origin.x();
  rh.ray.org_y = origin.y();
  rh.ray.org_z = origin.z();
  rh.ray.dir_x = unit_dir.x();
  rh.ray.dir_y = unit_dir.y();
  rh.ray.dir_z = unit_dir.z();
  rh.ray.tnear = t_min;
  rh.ray.tfar = t_max;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  const FlushDenormals ftz;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
    impl_->fill(rh.hit.primID, rh.ray.tfar, unit_dir, out);
  return out;
}

void RayCaster::cast_batch(const Eigen::Vector3f* origins, const Eigen::Vector3f* unit_dirs,
                           std::size_t n, float t_min, float t_max, RayHit* out) const {
  const FlushDenormals ftz;
  for (std::size_t i = 0; i < n; i += kPacket) {
    const int count = static_cast<int>(std::min<std::size_t>(kPacket, n - i));
    impl_->cast16(origins + i, unit_dirs + i, count, nullptr, t_min, t_max, out + i);
  }
}

void RayCaster::cast_batch(const Eigen::Vector3f* origins, const Eigen::Vector3f* unit_dirs,
                           std::size_t n, const float* t_min, float t_max, RayHit* out) const {
  const FlushDenormals ftz;
  for (std::size_t i = 0; i < n; i += kPacket) {
    const int count = static_cast<int>(std::min<std::size_t>(kPacket, n - i));
    impl_->cast16(origins + i, unit_dirs + i, count, t_min + i, 0.0f, t_max, out + i);
  }
}

std::size_t RayCaster::triangle_count() const {
  return impl_->labels.size();
}

}  // namespace rownav::sim
