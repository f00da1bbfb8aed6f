#include "rownav/sim/ray_caster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

namespace rownav::sim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// Square [-half, half]^2 at height z, split in 2 x n x n triangles, normal +z.
TriangleMesh plane(float z, float half, int n, SurfaceClass label) {
  TriangleMesh m;
  const float step = 2.0f * half / static_cast<float>(n);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) m.add_vertex({-half + step * i, -half + step * j, z});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto a = static_cast<std::uint32_t>(i * (n + 1) + j);
      const auto b = a + static_cast<std::uint32_t>(n + 1);
      m.add_triangle(a, b, b + 1, label);
      m.add_triangle(a, b + 1, a + 1, label);
    }
  return m;
}

/// Axis-aligned box [lo, hi], 12 triangles.
TriangleMesh box(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, SurfaceClass label) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.add_vertex({(k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z()});
  const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& f : faces) {
    m.add_triangle(f[0], f[1], f[2], label);
    m.add_triangle(f[0], f[2], f[3], label);
  }
  return m;
}

/// Vertical cylinder of radius r around (cx, cy), z in [0, h], `sides` facets (no caps).
TriangleMesh cylinder(float cx, float cy, float r, float h, int sides, SurfaceClass label) {
  TriangleMesh m;
  for (int i = 0; i < sides; ++i) {
    const float a = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / sides;
    m.add_vertex({cx + r * std::cos(a), cy + r * std::sin(a), 0.0f});
    m.add_vertex({cx + r * std::cos(a), cy + r * std::sin(a), h});
  }
  for (int i = 0; i < sides; ++i) {
    const auto a = static_cast<std::uint32_t>(2 * i),
               b = static_cast<std::uint32_t>(2 * ((i + 1) % sides));
    m.add_triangle(a, b, b + 1, label);
    m.add_triangle(a, b + 1, a + 1, label);
  }
  return m;
}

TEST(RayCaster, RejectsEmptyOrInconsistentMesh) {
  EXPECT_THROW(RayCaster(TriangleMesh{}), std::invalid_argument);
  TriangleMesh m = plane(0.0f, 1.0f, 1, SurfaceClass::ground);
  m.labels.pop_back();
  EXPECT_THROW(RayCaster{m}, std::invalid_argument);
  TriangleMesh bad = plane(0.0f, 1.0f, 1, SurfaceClass::ground);
  bad.triangles[0][2] = 99;
  EXPECT_THROW(RayCaster{bad}, std::invalid_argument);
}

TEST(RayCaster, PlaneDistanceIsHeightOverSinDepression) {
  const float h = 0.6f;
  const RayCaster rc(plane(0.0f, 500.0f, 40, SurfaceClass::ground));
  EXPECT_EQ(rc.triangle_count(), 2u * 40u * 40u);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> dep(0.02f, 1.5f), az(-3.14f, 3.14f);
  std::vector<Eigen::Vector3f> o, d;
  for (int i = 0; i < 500; ++i) {
    const float e = dep(rng), a = az(rng);
    o.emplace_back(0.1f, -0.2f, h);
    d.emplace_back(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), -std::sin(e));
  }
  std::vector<RayHit> hits(o.size());
  rc.cast_batch(o.data(), d.data(), o.size(), 0.0f, 1000.0f, hits.data());
  for (std::size_t i = 0; i < o.size(); ++i) {
    const float expect = h / -d[i].z();
    ASSERT_TRUE(hits[i].hit()) << i;
    EXPECT_NEAR(hits[i].distance, expect, 1e-4f * expect + 1e-5f) << i;
    EXPECT_EQ(hits[i].label, SurfaceClass::ground);
    EXPECT_NEAR(hits[i].normal.z(), 1.0f, 1e-6f);
    const RayHit single = rc.cast(o[i], d[i], 0.0f, 1000.0f);
    EXPECT_FLOAT_EQ(single.distance, hits[i].distance);
  }
}

TEST(RayCaster, SkyMissesAndRangeLimits) {
  const RayCaster rc(plane(0.0f, 50.0f, 4, SurfaceClass::ground));
  const Eigen::Vector3f o(0, 0, 1);
  EXPECT_FALSE(rc.cast(o, Eigen::Vector3f(0, 0, 1), 0.0f, 100.0f).hit());
  EXPECT_EQ(rc.cast(o, Eigen::Vector3f(1, 0, 0), 0.0f, 100.0f).distance, kInf);
  EXPECT_NEAR(rc.cast(o, Eigen::Vector3f(0, 0, -1), 0.0f, 100.0f).distance, 1.0f, 1e-6f);
  EXPECT_FALSE(rc.cast(o, Eigen::Vector3f(0, 0, -1), 0.0f, 0.9f).hit());    // beyond t_max
  EXPECT_FALSE(rc.cast(o, Eigen::Vector3f(0, 0, -1), 1.1f, 100.0f).hit());  // before t_min
  const Eigen::Vector3f nan_o(std::nanf(""), 0, 1);
  EXPECT_FALSE(rc.cast(nan_o, Eigen::Vector3f(0, 0, -1), 0.0f, 100.0f).hit());
}

TEST(RayCaster, RaysBeyondEmbreesRangeMissInsteadOfAborting) {
  // Embree asserts on an origin component beyond ~1.8e18 (a LiDAR mounted at 1e19 m aborted
  // rownav, issue 13): such rays miss, in a packet too, and the others still hit.
  const RayCaster rc(plane(0.0f, 50.0f, 4, SurfaceClass::ground));
  const Eigen::Vector3f down(0, 0, -1);
  std::vector<Eigen::Vector3f> o(16, Eigen::Vector3f(0, 0, 1)), d(16, down);
  o[3] = Eigen::Vector3f(1e19f, 0, 1);
  o[7] = Eigen::Vector3f(0, -3e38f, 1);
  std::vector<RayHit> hits(16);
  rc.cast_batch(o.data(), d.data(), o.size(), 0.0f, 100.0f, hits.data());
  for (std::size_t i = 0; i < hits.size(); ++i) EXPECT_EQ(hits[i].hit(), i != 3 && i != 7) << i;
  EXPECT_FALSE(rc.cast(o[3], down, 0.0f, 100.0f).hit());
}

TEST(RayCaster, BoxFacesLabelsAndNormals) {
  TriangleMesh world = plane(0.0f, 50.0f, 4, SurfaceClass::ground);
  world.append(box({4.0f, -1.0f, 0.0f}, {5.0f, 1.0f, 2.0f}, SurfaceClass::post));
  world.append(cylinder(-3.0f, 0.0f, 0.5f, 3.0f, 512, SurfaceClass::trunk));
  const RayCaster rc(world);
  // Horizontal rays toward the box's -x face from the origin at z = 1: distance 4 / cos(a).
  for (float a = -0.2f; a <= 0.2f; a += 0.01f) {
    const RayHit hit = rc.cast({0, 0, 1}, {std::cos(a), std::sin(a), 0}, 0.0f, 100.0f);
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.distance, 4.0f / std::cos(a), 1e-4f);
    EXPECT_EQ(hit.label, SurfaceClass::post);
    EXPECT_NEAR(hit.normal.x(), -1.0f, 1e-5f);  // faces the ray
  }
  // Rays toward the cylinder from (0, y0): distance to a circle, cx - sqrt(r^2 - y0^2).
  for (float y0 = -0.4f; y0 <= 0.4f; y0 += 0.05f) {
    const RayHit hit = rc.cast({0, y0, 1}, {-1, 0, 0}, 0.0f, 100.0f);
    ASSERT_TRUE(hit.hit());
    const float expect = 3.0f - std::sqrt(0.25f - y0 * y0);
    EXPECT_NEAR(hit.distance, expect, 2e-3f);  // 512 facets: sagitta < 2e-5 m, ends flatter
    EXPECT_EQ(hit.label, SurfaceClass::trunk);
    EXPECT_NEAR(hit.normal.y(), y0 / 0.5f, 0.02f);
  }
  // A ray from inside the box sees the inside of the far face; normal still faces the ray.
  const RayHit inside = rc.cast({4.5f, 0, 1}, {1, 0, 0}, 0.0f, 100.0f);
  EXPECT_NEAR(inside.distance, 0.5f, 1e-5f);
  EXPECT_NEAR(inside.normal.x(), -1.0f, 1e-5f);
}

TEST(RayCaster, BatchMatchesSingleForAnySize) {
  TriangleMesh world = plane(0.0f, 20.0f, 8, SurfaceClass::ground);
  world.append(box({2, 2, 0}, {3, 3, 1}, SurfaceClass::obstacle));
  const RayCaster rc(world);
  std::mt19937_64 rng(3);
  std::normal_distribution<float> g;
  for (std::size_t n : {1u, 15u, 16u, 17u, 100u}) {
    std::vector<Eigen::Vector3f> o(n, Eigen::Vector3f(0, 0, 0.5f)), d(n);
    std::vector<float> tmin(n);
    for (std::size_t i = 0; i < n; ++i) {
      d[i] = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
      tmin[i] = 0.1f * static_cast<float>(i % 3);
    }
    std::vector<RayHit> a(n), b(n);
    rc.cast_batch(o.data(), d.data(), n, tmin.data(), 50.0f, a.data());
    for (std::size_t i = 0; i < n; ++i) {
      b[i] = rc.cast(o[i], d[i], tmin[i], 50.0f);
      EXPECT_EQ(a[i].hit(), b[i].hit());
      if (a[i].hit()) {
        EXPECT_FLOAT_EQ(a[i].distance, b[i].distance);
        EXPECT_EQ(a[i].label, b[i].label);
      }
    }
  }
}

TEST(RayCaster, ConcurrentConstCallsAgree) {
  TriangleMesh world = plane(0.0f, 20.0f, 16, SurfaceClass::ground);
  world.append(box({1, -1, 0}, {2, 1, 2}, SurfaceClass::post));
  const RayCaster rc(world);
  std::vector<Eigen::Vector3f> o(4096, Eigen::Vector3f(0, 0, 1)), d(4096);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const float a = 0.01f * static_cast<float>(i), e = -0.5f + 0.0002f * static_cast<float>(i);
    d[i] = Eigen::Vector3f(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
  }
  std::vector<RayHit> ref(d.size()), a(d.size()), b(d.size());
  rc.cast_batch(o.data(), d.data(), d.size(), 0.0f, 50.0f, ref.data());
  std::thread ta([&] { rc.cast_batch(o.data(), d.data(), d.size(), 0.0f, 50.0f, a.data()); });
  std::thread tb([&] { rc.cast_batch(o.data(), d.data(), d.size(), 0.0f, 50.0f, b.data()); });
  ta.join();
  tb.join();
  for (std::size_t i = 0; i < ref.size(); ++i) {
    ASSERT_EQ(a[i].distance, ref[i].distance) << i;
    ASSERT_EQ(b[i].distance, ref[i].distance) << i;
  }
}

TEST(RayCaster, IsMovable) {
  RayCaster a(plane(0.0f, 5.0f, 1, SurfaceClass::ground));
  RayCaster b(std::move(a));
  EXPECT_NEAR(b.cast({0, 0, 2}, {0, 0, -1}, 0.0f, 10.0f).distance, 2.0f, 1e-6f);
  EXPECT_EQ(b.triangle_count(), 2u);
}

}  // namespace
}  // namespace rownav::sim
