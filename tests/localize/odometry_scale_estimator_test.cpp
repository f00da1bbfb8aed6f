#include "rownav/localize/odometry_scale_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "localize/scale_scene.hpp"
#include "rownav/core/angle.hpp"

namespace rownav::localize {
namespace {

using testing::RowKind;

struct Drive {
  double alpha = 1.0;  // the odometry's alpha at the end
  int updates = 0;
  OdometryScaleEstimator estimator;
};

// Frames every 0.1 m of a weaving drive down a random corridor; the drive train's true alpha is
// `true_alpha`, the odometry starts with alpha 1 and takes every update the estimator returns.
Drive drive(std::uint32_t seed, RowKind kind, double true_alpha, double metres,
            double weave_deg = 3.0) {
  std::mt19937 rng(seed);
  const auto scene = testing::make_corridor(rng, kind);
  Drive d;
  core::Pose2 truth(0.0, 0.1 * scene.width, 0.0), odometry;
  const double step = 0.1;
  for (int i = 0; i * step < metres; ++i) {
    // Heading from the gyro (exact); distance read with the odometry's alpha.
    const double heading = core::deg2rad(weave_deg) * std::sin(i * step / 3.0);
    const core::Pose2 inc(step, 0.0, heading - truth.theta);
    truth = truth * inc;
    odometry = odometry * core::Pose2(step * d.alpha / true_alpha, 0.0, inc.theta);
    const auto points = testing::observe(scene, kind, truth, rng);
    if (const auto a = d.estimator.add_frame(points, odometry, d.alpha)) d.alpha = *a, ++d.updates;
  }
  return d;
}

TEST(OdometryScaleEstimator, LearnsTheDriveTrainsAlphaOnRandomCorridorsWhileWeaving) {
  for (const std::uint32_t seed : {1u, 2u, 3u, 4u, 5u})
    for (const double alpha : {0.85, 0.92, 1.08}) {
      const Drive d = drive(seed, RowKind::vines, alpha, 40.0);
      EXPECT_NEAR(d.alpha, alpha, 0.01) << "seed " << seed << ", alpha " << alpha;
      EXPECT_GE(d.updates, 1);
    }
}

TEST(OdometryScaleEstimator, ARightAlphaIsLeftAlone) {
  const Drive d = drive(6, RowKind::vines, 1.0, 40.0);
  EXPECT_EQ(d.updates, 0);
  EXPECT_DOUBLE_EQ(d.alpha, 1.0);
}

TEST(OdometryScaleEstimator, ARowWithoutTextureOrWithRepeatingPlantsChangesNothing) {
  // A solid hedge says nothing about the distance along it; 0.2 m plants make every match
  // ambiguous at a 1 m baseline. Either way the odometry keeps the alpha it has.
  for (const RowKind kind : {RowKind::solid_hedge, RowKind::plants_every_20cm}) {
    const Drive d = drive(7, kind, 0.9, 30.0);
    EXPECT_EQ(d.updates, 0) << static_cast<int>(kind);
    EXPECT_DOUBLE_EQ(d.alpha, 1.0);
  }
}

TEST(OdometryScaleEstimator, FramesThatTurnMoreThanTheLimitAreNoStretch) {
  OdometryScaleEstimator e;
  std::mt19937 rng(8);
  const auto scene = testing::make_corridor(rng, RowKind::vines);
  core::Pose2 pose;
  for (int i = 0; i < 100; ++i) {  // 0.1 m and 1 deg a frame: 6 deg over a 0.6 m stretch
    pose = pose * core::Pose2(0.1, 0.0, core::deg2rad(1.0));
    EXPECT_FALSE(e.add_frame(testing::observe(scene, RowKind::vines, pose, rng), pose, 1.0));
  }
  EXPECT_EQ(e.matches(), 0);
}

TEST(OdometryScaleConfig, ValidateNamesTheField) {
  OdometryScaleConfig c;
  c.min_samples = c.window + 1;
  try {
    c.validate();
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("min_samples"), std::string::npos) << e.what();
  }
  c = {};
  c.match.resolution = -1.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::localize
