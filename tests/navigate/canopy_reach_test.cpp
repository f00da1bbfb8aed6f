// Issue 10: the followed rows' canopy at the robot's flanks is no obstacle; a person is.
#include "rownav/navigate/canopy_reach.hpp"

#include <gtest/gtest.h>

#include "common/flat_ground.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace rownav::navigate {
namespace {

using test::flat_ground;
using test::pt;

constexpr double kHalfWidth = 0.3;  // [m] a 0.6 m robot
constexpr double kFront = 0.45;     // [m] base origin to the front
// The obstacle band of these scenes: 0.3-2.5 m above the ground, no robot top (the rows'
// points stand at 0.5 m).
const HeightBand kBand{0.3, 2.5, std::numeric_limits<double>::infinity()};

/// Where the robot stands in the corridor: offset from the centre line (left +) and yaw.
struct Pose {
  double offset = 0.0, yaw = 0.0;
  Eigen::Vector2f to_base(double x_c, double u) const {  // corridor (x, u) -> base
    const double dx = x_c, du = u - offset, c = std::cos(yaw), s = std::sin(yaw);
    return {static_cast<float>(c * dx + s * du), static_cast<float>(-s * dx + c * du)};
  }
  core::Line2 centre_base() const {
    const Eigen::Vector2f p = to_base(0.0, 0.0), q = to_base(1.0, 0.0);
    return {p.cast<double>(), (q - p).cast<double>()};
  }
};

/// One frame of two rows whose canopy reaches into the corridor in clumps: each clump's inner
/// edge lies `deepest`..`deepest` + 0.3 m from the centre line (corridor frame, x from -4 to
/// +1 m), at 0.5 m above the ground.
core::PointCloud clumpy_rows(double deepest, const Pose& pose, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  core::PointCloud c;
  for (double side : {-1.0, 1.0})
    for (double x0 = -4.0; x0 < 1.0; x0 += 0.4 + 0.4 * u(rng)) {
      const double edge = deepest + 0.3 * u(rng) * u(rng);  // deep clumps are rare
      for (double dx = 0.0; dx < 0.3; dx += 0.05)
        for (double du = 0.0; du < 0.4; du += 0.1) {
          const Eigen::Vector2f b = pose.to_base(x0 + dx, side * (edge + du));
          c.points.push_back(pt(b.x(), b.y(), 0.5f));
        }
    }
  return c;
}

/// A person (0.3 m wide) ahead of the front, across u in [u0, u0 + 0.3] of the corridor.
std::vector<Eigen::Vector2f> person_ahead(double u0, const Pose& pose) {
  std::vector<Eigen::Vector2f> out;
  for (double du = 0.0; du <= 0.3 + 1e-9; du += 0.05)
    out.push_back(pose.to_base(kFront + 0.3, u0 + du));
  return out;
}

CanopyReachEstimator driven(double deepest, const Pose& pose, std::uint64_t seed, int frames) {
  const auto ground = flat_ground();
  std::mt19937_64 rng(seed);
  CanopyReachEstimator canopy;
  for (int f = 0; f < frames; ++f)
    canopy.update(clumpy_rows(deepest, pose, rng), ground, kBand, pose.centre_base(), kFront);
  return canopy;
}

TEST(CanopyReach, TheRowsClumpsAtTheFlanksAreDroppedAndAPersonInThePathIsKept) {
  // Random corridors: canopy reaching 0.25-0.45 m from the centre (a 0.6 m robot's flanks at
  // 0.3 m), the robot off-centre and yawed.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> reach(0.25, 0.45), off(-0.03, 0.03), yaw(-0.05, 0.05);
  for (int trial = 0; trial < 20; ++trial) {
    const double deepest = reach(rng);
    const Pose pose{off(rng), yaw(rng)};
    const auto canopy = driven(deepest, pose, 100 + static_cast<std::uint64_t>(trial), 80);
    for (double side : {-1.0, 1.0}) {
      EXPECT_GE(canopy.reach(side), deepest - 1e-6) << trial;  // never deeper than the canopy
      EXPECT_LT(canopy.reach(side), deepest + 0.1) << trial;   // its deep clumps, not its mean
    }
    // A clump ahead as deep as the deepest beside, at either flank: canopy.
    std::vector<Eigen::Vector2f> flank = {pose.to_base(kFront + 0.3, deepest),
                                          pose.to_base(kFront + 0.3, -deepest)};
    canopy.drop_canopy(flank, pose.centre_base(), kHalfWidth);
    EXPECT_TRUE(flank.empty()) << trial;
    // A person across the robot's path, no nearer the rows than their canopy less the margin:
    // kept in full.
    auto person = person_ahead(-0.15, pose);
    const auto n = person.size();
    canopy.drop_canopy(person, pose.centre_base(), kHalfWidth);
    EXPECT_EQ(person.size(), n) << trial;
  }
}

TEST(CanopyReach, SomethingReachingFurtherInThanTheCanopyIsKept) {
  const Pose pose;
  const auto canopy = driven(0.45, pose, 1, 80);
  // 0.25 m from the centre: inside the footprint's outer half, but 0.2 m deeper than any clump
  // driven beside (more than the 0.1 m margin).
  std::vector<Eigen::Vector2f> box = {pose.to_base(kFront + 0.2, 0.25),
                                      pose.to_base(kFront + 0.2, -0.25)};
  canopy.drop_canopy(box, pose.centre_base(), kHalfWidth);
  EXPECT_EQ(box.size(), 2u);
}

TEST(CanopyReach, NeverDeeperIntoTheFootprintThanMaxIntrusion) {
  // Canopy that reaches 0.05 m from the centre line (a hedge over a narrow robot path): points
  // in the footprint's inner half stay obstacles whatever was measured.
  const Pose pose;
  const auto canopy = driven(0.05, pose, 2, 80);
  std::vector<Eigen::Vector2f> pts = {pose.to_base(kFront + 0.2, 0.1),
                                      pose.to_base(kFront + 0.2, 0.2)};
  canopy.drop_canopy(pts, pose.centre_base(), kHalfWidth);
  ASSERT_EQ(pts.size(), 1u);
  EXPECT_NEAR(pts[0].y(), 0.1f, 1e-6f);
}

TEST(CanopyReach, NothingMeasuredDropsNothingAndAStrayFrameDoesNotSetTheReach) {
  const auto ground = flat_ground();
  const Pose pose;
  CanopyReachEstimator canopy;
  std::vector<Eigen::Vector2f> flank = {pose.to_base(kFront + 0.3, 0.28)};
  canopy.drop_canopy(flank, pose.centre_base(), kHalfWidth);
  EXPECT_EQ(flank.size(), 1u);  // no frame yet
  // 60 frames of canopy 0.6 m out, one frame with a clump 0.1 m from the centre.
  std::mt19937_64 rng(3);
  for (int f = 0; f < 60; ++f)
    canopy.update(clumpy_rows(0.6, pose, rng), ground, kBand, pose.centre_base(), kFront);
  auto stray = clumpy_rows(0.6, pose, rng);
  for (int k = 0; k < 20; ++k) stray.points.push_back(pt(-1.0f, 0.1f, 0.5f));
  canopy.update(stray, ground, kBand, pose.centre_base(), kFront);
  EXPECT_GT(canopy.reach(1.0), 0.55);
  canopy.drop_canopy(flank, pose.centre_base(), kHalfWidth);
  EXPECT_EQ(flank.size(), 1u);  // 0.28 m is 0.3 m deeper than this canopy
  canopy.reset();
  EXPECT_TRUE(std::isinf(canopy.reach(1.0)));
}

TEST(CanopyReach, DisabledNonFiniteOrNoCorridorChangesNothing) {
  const auto ground = flat_ground();
  const Pose pose;
  std::mt19937_64 rng(4);
  CanopyReachConfig off;
  off.enabled = false;
  CanopyReachEstimator disabled(off);
  for (int f = 0; f < 40; ++f)
    disabled.update(clumpy_rows(0.25, pose, rng), ground, kBand, pose.centre_base(), kFront);
  std::vector<Eigen::Vector2f> flank = {pose.to_base(kFront + 0.3, 0.28)};
  disabled.drop_canopy(flank, pose.centre_base(), kHalfWidth);
  EXPECT_EQ(flank.size(), 1u);

  auto canopy = driven(0.25, pose, 5, 40);
  auto bad = clumpy_rows(0.25, pose, rng);
  bad.points.push_back(pt(std::nanf(""), 0.0f, 0.5f));
  bad.points.push_back(pt(-1.0f, INFINITY, 0.5f));
  canopy.update(bad, ground, kBand, pose.centre_base(), kFront);
  EXPECT_TRUE(std::isfinite(canopy.reach(1.0)));
  core::Line2 none;
  none.point = Eigen::Vector2d::Constant(std::nan(""));
  canopy.drop_canopy(flank, none, kHalfWidth);  // no corridor: nothing is the rows'
  EXPECT_EQ(flank.size(), 1u);
  canopy.update(bad, ground, kBand, none, kFront);  // and the corridor's history is forgotten
  EXPECT_TRUE(std::isinf(canopy.reach(1.0)));
}

TEST(CanopyReach, ConfigValidationNamesTheField) {
  CanopyReachConfig c;
  c.max_intrusion = 1.5;
  try {
    c.validate();
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_intrusion"), std::string::npos);
  }
  c = {};
  c.frame_quantile = -0.1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = {};
  c.frames = 0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::navigate
