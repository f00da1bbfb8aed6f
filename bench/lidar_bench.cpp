/// @file lidar_bench.cpp Ray casting and LiDAR simulation speed in a dense ("high canopy")
/// vineyard built here: 20 rows x 100 m, 2.5 m apart, foliage clumps every 0.15 m, trunks every
/// 1.2 m, posts every 5 m, 0.5 m ground grid. One core.
///   ./build/lidar_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "rownav/sim/lidar.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace {

using rownav::sim::SurfaceClass;
using rownav::sim::TriangleMesh;

constexpr int kRows = 20;
constexpr float kRowLength = 100.0f, kRowSpacing = 2.5f;

/// Unit icosahedron (20 faces).
TriangleMesh icosahedron() {
  TriangleMesh m;
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  // clang-format off
  const std::array<Eigen::Vector3f, 12> v{{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}}};
  // clang-format on
  for (const auto& p : v) m.add_vertex(p.normalized());
  const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                        {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                        {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                        {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (const auto& t3 : f) m.add_triangle(t3[0], t3[1], t3[2], SurfaceClass::canopy);
  return m;
}

/// Jittered ellipsoidal clump of radius r centred at c.
void add_clump(TriangleMesh& world, const TriangleMesh& ico, const Eigen::Vector3f& c, float r,
               std::mt19937_64& rng) {
  std::uniform_real_distribution<float> j(0.8f, 1.2f);
  const auto base = static_cast<std::uint32_t>(world.vertices.size());
  const Eigen::Vector3f scale(r * j(rng), r * j(rng), r * j(rng));
  for (const auto& v : ico.vertices) world.add_vertex(c + (scale.cwiseProduct(v) * j(rng)));
  for (const auto& t : ico.triangles)
    world.add_triangle(base + t[0], base + t[1], base + t[2], SurfaceClass::canopy);
}

/// Vertical prism with `sides` faces around (x, y) from z = 0 to h.
void add_prism(TriangleMesh& world, float x, float y, float r, float h, int sides,
               SurfaceClass label) {
  const auto base = static_cast<std::uint32_t>(world.vertices.size());
  for (int i = 0; i < sides; ++i) {
    const float a = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / sides;
    world.add_vertex({x + r * std::cos(a), y + r * std::sin(a), 0.0f});
    world.add_vertex({x + r * std::cos(a), y + r * std::sin(a), h});
  }
  for (int i = 0; i < sides; ++i) {
    const auto a = base + 2u * static_cast<std::uint32_t>(i);
    const auto b = base + 2u * static_cast<std::uint32_t>((i + 1) % sides);
    world.add_triangle(a, b, b + 1, label);
    world.add_triangle(a, b + 1, a + 1, label);
  }
}

void add_ground(TriangleMesh& world, float x0, float x1, float y0, float y1, float cell) {
  const int nx = static_cast<int>((x1 - x0) / cell), ny = static_cast<int>((y1 - y0) / cell);
  const auto base = static_cast<std::uint32_t>(world.vertices.size());
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) world.add_vertex({x0 + cell * i, y0 + cell * j, 0.0f});
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const auto a = base + static_cast<std::uint32_t>(i * (ny + 1) + j);
      const auto b = a + static_cast<std::uint32_t>(ny + 1);
      world.add_triangle(a, b, b + 1, SurfaceClass::ground);
      world.add_triangle(a, b + 1, a + 1, SurfaceClass::ground);
    }
}

TriangleMesh high_canopy_vineyard() {
  TriangleMesh world;
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const TriangleMesh ico = icosahedron();
  add_ground(world, -10.0f, kRowLength + 10.0f, -10.0f, kRowSpacing * kRows + 7.5f, 0.5f);
  for (int row = 0; row < kRows; ++row) {
    const float y = kRowSpacing * static_cast<float>(row);
    for (float x = 0.0f; x <= kRowLength; x += 0.15f)
      for (int k = 0; k < 2; ++k)
        add_clump(world, ico,
                  {x + 0.05f * (u(rng) - 0.5f), y + 0.3f * (u(rng) - 0.5f), 0.6f + 1.2f * u(rng)},
                  0.15f + 0.2f * u(rng), rng);
    for (float x = 0.6f; x < kRowLength; x += 1.2f)
      add_prism(world, x, y, 0.05f, 0.8f, 8, SurfaceClass::trunk);
    for (float x = 0.0f; x <= kRowLength + 0.01f; x += 5.0f)
      add_prism(world, x, y, 0.04f, 2.0f, 4, SurfaceClass::post);
  }
  return world;
}

const rownav::sim::RayCaster& world() {
  static const rownav::sim::RayCaster caster(high_canopy_vineyard());
  return caster;
}

/// Robot in the middle of corridor 9, driving along the rows at 1 m/s.
rownav::sim::PoseAt robot() {
  return [](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(50.0 + t, kRowSpacing * 9.5, 0.0);
    return T;
  };
}

rownav::sim::LidarConfig config(const char* preset, double foliage_pass) {
  rownav::sim::LidarConfig c = rownav::sim::lidar_preset(preset);
  c.mount_xyz = {0.3, 0.0, 0.6};
  c.foliage_pass_probability = foliage_pass;
  return c;
}

void sweep(benchmark::State& state, const char* preset, double foliage_pass) {
  const auto& w = world();
  rownav::sim::Lidar lidar(config(preset, foliage_pass), 1);
  const auto pose = robot();
  double t = 0.0;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto cloud = lidar.sweep(w, pose, t);
    points = cloud.size();
    benchmark::DoNotOptimize(cloud.points.data());
    t = std::fmod(t + 0.1, 20.0);  // stay inside the rows (x = 50..70 m)
  }
  const auto rays = double(lidar.config().columns) * lidar.config().rings;
  state.counters["triangles"] = double(w.triangle_count());
  state.counters["points"] = double(points);
  state.counters["rays/s"] =
      benchmark::Counter(rays, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Os1_64Sweep(benchmark::State& s) {
  sweep(s, "os1_64", 0.0);
}
void BM_Os1_64SweepFoliagePass(benchmark::State& s) {
  sweep(s, "os1_64", 0.3);
}
void BM_Os1_16Sweep(benchmark::State& s) {
  sweep(s, "os1_16", 0.0);
}
void BM_Vlp16Sweep(benchmark::State& s) {
  sweep(s, "vlp16", 0.0);
}

void BM_Lms1081Scan(benchmark::State& state) {
  const auto& w = world();
  rownav::sim::Lidar lidar(config("lms_1081", 0.0), 1);
  const auto pose = robot();
  double t = 0.0;
  for (auto _ : state) {
    const auto scan = lidar.scan(w, pose, t);
    benchmark::DoNotOptimize(scan.ranges.data());
    t = std::fmod(t + 0.04, 20.0);
  }
  state.counters["triangles"] = double(w.triangle_count());
}

/// Raw Embree cost of an OS1-64 sweep's 65,536 rays (no sensor model): batch vs one by one.
void raw_rays(benchmark::State& state, bool batch) {
  const auto& w = world();
  const auto c = config("os1_64", 0.0);
  const auto elev = c.ring_elevations();
  std::vector<Eigen::Vector3f> o, d;
  for (int col = 0; col < c.columns; ++col) {
    const double a = 2.0 * std::numbers::pi * col / c.columns;
    for (const double e : elev) {
      o.emplace_back(50.3f, float(kRowSpacing * 9.5), 0.6f);
      d.emplace_back(float(std::cos(e) * std::cos(a)), float(std::cos(e) * std::sin(a)),
                     float(std::sin(e)));
    }
  }
  std::vector<rownav::sim::RayHit> hits(o.size());
  for (auto _ : state) {
    if (batch) {
      w.cast_batch(o.data(), d.data(), o.size(), 0.0f, 120.0f, hits.data());
    } else {
      for (std::size_t i = 0; i < o.size(); ++i) hits[i] = w.cast(o[i], d[i], 0.0f, 120.0f);
    }
    benchmark::DoNotOptimize(hits.data());
  }
  state.counters["rays/s"] =
      benchmark::Counter(double(o.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_RawRays65kBatch16(benchmark::State& s) {
  raw_rays(s, true);
}
void BM_RawRays65kSingle(benchmark::State& s) {
  raw_rays(s, false);
}

}  // namespace

BENCHMARK(BM_Os1_64Sweep)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Os1_64SweepFoliagePass)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Os1_16Sweep)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Vlp16Sweep)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lms1081Scan)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RawRays65kBatch16)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RawRays65kSingle)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
