#include "rownav/sim/robot.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "rownav/sim/scripted_path.hpp"

namespace rownav::sim {
namespace {

RobotConfig ideal_skid() {
  RobotConfig c;
  c.x_icr = 0.5 * c.track_width;
  c.alpha = 1.0;
  c.slip_noise = 0.0;
  return c;
}

Robot run(const RobotConfig& c, const core::Twist2& cmd, double seconds, std::uint64_t seed = 1) {
  Robot r(c, seed, core::Pose2());
  for (int i = 0; i < static_cast<int>(std::lround(seconds / 0.01)); ++i) r.step(cmd, 0.01);
  return r;
}

TEST(Robot, StraightWithIdealParameters) {
  const RobotConfig c = ideal_skid();
  const Robot r = run(c, {1.0, 0.0, 0.0}, 10.0);
  // 1 s of acceleration at 1 m/s^2 loses 0.5 m against a constant 1 m/s.
  EXPECT_NEAR(r.state().pose.x, 9.5, 0.02);
  EXPECT_NEAR(r.state().pose.y, 0.0, 1e-9);
  EXPECT_NEAR(r.state().pose.theta, 0.0, 1e-9);
  EXPECT_NEAR(r.state().stamp, 10.0, 1e-9);
  EXPECT_NEAR(r.state().left_wheel_angle * c.wheel_radius, r.state().pose.x, 1e-6);
  EXPECT_NEAR(r.state().right_wheel_speed * c.wheel_radius, 1.0, 1e-9);
}

TEST(Robot, SkidSteerYawRateFollowsIcrModel) {
  RobotConfig c;  // x_icr 0.40, alpha 0.90: Bertoglio 2023 eq. (2)
  c.slip_noise = 0.0;
  const Robot r = run(c, {0.5, 0.0, 0.5}, 3.0);
  const double expected = c.alpha * (0.5 * c.track_width) / c.x_icr;  // 0.61875
  EXPECT_NEAR(r.state().twist.omega / 0.5, expected, 1e-9);
  EXPECT_NEAR(r.state().twist.v / 0.5, c.alpha, 1e-9);
  // Commanded track speeds use the nominal model: V_r - V_l = omega * track.
  const double dv = (r.state().right_wheel_speed - r.state().left_wheel_speed) * c.wheel_radius;
  EXPECT_NEAR(dv, 0.5 * c.track_width, 1e-9);
}

TEST(Robot, SlipNoiseMakesRealisticHeadingDrift) {
  RobotConfig c = ideal_skid();
  c.slip_noise = 0.02;
  const Robot r = run(c, {1.0, 0.0, 0.0}, 20.0, 3);
  EXPECT_GT(std::abs(r.state().pose.theta), 1e-4);  // noise acts
  EXPECT_LT(std::abs(r.state().pose.theta), 0.3);   // but stays a small drift
  EXPECT_NEAR(r.state().pose.x, 19.5, 0.3);
}

TEST(Robot, ClampsSpeedYawRateAndAcceleration) {
  const RobotConfig c = ideal_skid();
  Robot r(c, 1, core::Pose2());
  r.step({5.0, 0.0, 5.0}, 0.1);
  EXPECT_NEAR(r.state().twist.v, c.max_accel * 0.1, 1e-9);
  EXPECT_NEAR(r.state().twist.omega, c.max_yaw_accel * 0.1, 1e-9);
  for (int i = 0; i < 300; ++i) r.step({5.0, 0.0, 5.0}, 0.01);
  EXPECT_NEAR(r.state().twist.v, c.max_speed, 1e-9);
  EXPECT_NEAR(r.state().twist.omega, c.max_yaw_rate, 1e-9);
  for (int i = 0; i < 500; ++i) r.step({-5.0, 0.0, 0.0}, 0.01);
  EXPECT_NEAR(r.state().twist.v, -c.max_reverse_speed, 1e-9);
}

TEST(Robot, AckermannRespectsMinimumTurnRadiusAndSteeringRate) {
  RobotConfig c;
  c.drive = DriveKind::ackermann;
  c.wheelbase = 1.2;
  c.max_steer_deg = 25.0;
  c.alpha = 1.0;
  c.slip_noise = 0.0;
  Robot r(c, 1, core::Pose2());
  r.step({1.0, 0.0, 3.0}, 0.1);
  EXPECT_NEAR(r.state().steering_angle, core::deg2rad(c.max_steer_rate_deg) * 0.1, 1e-9);
  for (int i = 0; i < 1000; ++i) r.step({1.0, 0.0, 3.0}, 0.01);
  const double radius = r.state().twist.v / r.state().twist.omega;
  EXPECT_NEAR(radius, c.min_turn_radius(), 1e-6);
  EXPECT_NEAR(c.min_turn_radius(), 1.2 / std::tan(core::deg2rad(25.0)), 1e-12);
  // A car cannot turn on the spot.
  Robot s(c, 1, core::Pose2());
  for (int i = 0; i < 100; ++i) s.step({0.0, 0.0, 1.0}, 0.01);
  EXPECT_EQ(s.state().pose.theta, 0.0);
}

TEST(Robot, DeterministicForASeed) {
  RobotConfig c;
  const Robot a = run(c, {1.0, 0.0, 0.2}, 5.0, 42), b = run(c, {1.0, 0.0, 0.2}, 5.0, 42);
  const Robot d = run(c, {1.0, 0.0, 0.2}, 5.0, 43);
  EXPECT_EQ(a.state().pose.x, b.state().pose.x);
  EXPECT_EQ(a.state().pose.theta, b.state().pose.theta);
  EXPECT_NE(a.state().pose.x, d.state().pose.x);
}

TEST(Robot, BadInputDoesNotThrowOrMove) {
  Robot r(RobotConfig{}, 1, core::Pose2(1.0, 2.0, 0.5));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.step({nan, 0.0, nan}, 0.1);
  r.step({1.0, 0.0, 0.0}, -1.0);
  r.step({1.0, 0.0, 0.0}, nan);
  EXPECT_EQ(r.state().pose.x, 1.0);
  EXPECT_EQ(r.state().pose.y, 2.0);
}

TEST(Robot, ValidateNamesTheField) {
  RobotConfig c;
  c.track_width = -1.0;
  try {
    c.validate();
    FAIL() << "expected a throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("track_width"), std::string::npos);
  }
}

TEST(Robot, FootprintCornersInWorld) {
  RobotConfig c;  // length 0.9, width 0.6, base_to_front 0.45
  const Robot r(c, 1, core::Pose2(2.0, 1.0, M_PI / 2));
  const auto f = r.footprint_world();
  EXPECT_NEAR(f[1].x(), 2.3, 1e-9);  // front right: x + w/2 ... rotated by 90 deg
  EXPECT_NEAR(f[1].y(), 1.45, 1e-9);
  EXPECT_NEAR(f[3].x(), 1.7, 1e-9);
  EXPECT_NEAR(f[3].y(), 0.55, 1e-9);
}

/// Minimal reader for the config files' field types: checks that the YAML keys are exactly the
/// fields() names and fills the struct.
struct YamlReader {
  const YAML::Node& node;
  std::set<std::string> seen;
  template <class T>
  void operator()(std::string_view name, T& value) {
    const std::string key(name);
    seen.insert(key);
    ASSERT_TRUE(node[key].IsDefined()) << "missing " << key;
    if constexpr (core::NamedEnum<T>) {
      ASSERT_TRUE(core::enum_from_name(node[key].as<std::string>(), value)) << key;
    } else if constexpr (std::is_same_v<T, std::vector<Eigen::Vector2d>>) {
      value.clear();
      for (const auto& p : node[key]) value.emplace_back(p[0].as<double>(), p[1].as<double>());
    } else {
      value = node[key].as<T>();
    }
  }
};

template <class C>
C load(const std::string& file) {
  const YAML::Node node = YAML::LoadFile(std::string(ROWNAV_SOURCE_DIR) + "/config/" + file);
  C c;
  YamlReader r{node, {}};
  C::fields(c, r);
  for (const auto& kv : node)
    EXPECT_TRUE(r.seen.count(kv.first.as<std::string>())) << file << ": " << kv.first;
  EXPECT_EQ(r.seen.size(), node.size()) << file;
  c.validate();
  return c;
}

TEST(ConfigFiles, RobotsAndPathUseExactlyTheFieldNames) {
  const auto skid = load<RobotConfig>("robots/skid_steer.yaml");
  EXPECT_EQ(skid.drive, DriveKind::skid_steer);
  EXPECT_EQ(skid.x_icr, RobotConfig{}.x_icr);
  const auto diff = load<RobotConfig>("robots/differential.yaml");
  EXPECT_EQ(diff.drive, DriveKind::differential);
  const auto car = load<RobotConfig>("robots/car_like.yaml");
  EXPECT_EQ(car.drive, DriveKind::ackermann);
  EXPECT_NEAR(car.min_turn_radius(), 3.0, 0.1);
  const auto path = load<PathConfig>("paths/three_corridors.yaml");
  EXPECT_EQ(path.corridors, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(path.turn, TurnStyle::u_turn);
  EXPECT_TRUE(path.waypoints.empty());
}

}  // namespace
}  // namespace rownav::sim
