#include "rownav/io/cloud_registration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rownav/core/angle.hpp"

namespace rownav::io {
namespace {

/// Two vine rows (foliage and posts, 2 m apart, 12 m long), ground and a hedge across the row
/// ends: structured in x and y so a planar transform is observable.
core::PointCloud vineyard_cloud(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  core::PointCloud c;
  auto add = [&](double x, double y, double z) {
    core::PointXYZIRT p;
    p.x = static_cast<float>(x);
    p.y = static_cast<float>(y);
    p.z = static_cast<float>(z);
    c.points.push_back(p);
  };
  for (int i = 0; i < 4000; ++i) {
    const double x = -6.0 + 12.0 * u(rng);
    add(x, (i % 2 ? 1.0 : -1.0) + 0.2 * (u(rng) - 0.5), 0.5 + 1.2 * u(rng));
  }
  for (int k = 0; k < 5; ++k)  // posts every 3 m: fix the position along the rows
    for (int i = 0; i < 200; ++i) {
      const double a = 2.0 * M_PI * u(rng);
      add(-6.0 + 3.0 * k + 0.05 * std::cos(a), 1.0 + 0.05 * std::sin(a), 2.0 * u(rng));
      add(-4.5 + 3.0 * k + 0.05 * std::cos(a), -1.0 + 0.05 * std::sin(a), 2.0 * u(rng));
    }
  for (int i = 0; i < 2000; ++i) add(-6.0 + 12.0 * u(rng), -3.0 + 6.0 * u(rng), 0.0);
  // A headland hedge across the row ends: fixes x even at the coarse NDT resolution.
  for (int i = 0; i < 1500; ++i) add(6.5 + 0.3 * u(rng), -3.0 + 6.0 * u(rng), 1.5 * u(rng));
  return c;
}

core::PointCloud moved(const core::PointCloud& in, const core::Pose2& T) {
  core::PointCloud out = in;
  for (auto& p : out.points) {
    const Eigen::Vector2d q = T * Eigen::Vector2d(p.x, p.y);
    p.x = static_cast<float>(q.x());
    p.y = static_cast<float>(q.y());
  }
  return out;
}

class Registration : public ::testing::TestWithParam<RegistrationMethod> {};

TEST_P(Registration, RecoversSmallPlanarMotion) {
  const core::PointCloud target = vineyard_cloud(5);
  const core::Pose2 T_target_source(0.15, -0.08, core::deg2rad(2.0));
  // source = the target seen from the moved pose: target = T * source.
  const core::PointCloud source = moved(target, T_target_source.inverse());
  RegistrationConfig c;
  c.method = GetParam();
  c.max_iterations = 50;
  const RegistrationResult r = refine(source, target, {}, c);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.T_target_source.x, T_target_source.x, 0.03);
  EXPECT_NEAR(r.T_target_source.y, T_target_source.y, 0.03);
  EXPECT_NEAR(core::angle_diff(r.T_target_source.theta, T_target_source.theta), 0.0,
              core::deg2rad(0.5));
  EXPECT_GE(r.fitness, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Methods, Registration,
                         ::testing::Values(RegistrationMethod::ndt, RegistrationMethod::icp),
                         [](const auto& info) { return std::string(core::enum_name(info.param)); });

TEST(RegistrationNone, ReturnsGuessAndHandlesDegenerateInput) {
  const core::PointCloud cloud = vineyard_cloud(1);
  const core::Pose2 guess(1.0, 2.0, 0.3);
  RegistrationConfig c;  // method none by default
  const auto r = refine(cloud, cloud, guess, c);
  EXPECT_FALSE(r.converged);
  EXPECT_DOUBLE_EQ(r.T_target_source.x, 1.0);
  c.method = RegistrationMethod::ndt;
  core::PointCloud nan_cloud;
  nan_cloud.points.resize(50);
  for (auto& p : nan_cloud.points) p.x = std::nanf("");
  const auto d = refine(nan_cloud, cloud, guess, c);
  EXPECT_FALSE(d.converged);
  EXPECT_DOUBLE_EQ(d.T_target_source.theta, guess.theta);
}

}  // namespace
}  // namespace rownav::io
