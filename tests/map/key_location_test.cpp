// Key location projection (Emmi 2021 eq. (2)-(3), Fig. 3) and the validity rules.
#include "rownav/map/key_location.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "rownav/map/place_estimator.hpp"

#include "map/map_scene.hpp"

namespace rownav::map {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::vector<RowCluster> rows_of(const test::SynthScene& s, const core::Pose2& T,
                                std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  LabelledClusters c;
  const auto f = test::scan(s, T, rng);
  c.add(f.points, f.labels, T);
  return c.update(T);
}

const KeyLocation* find(const std::vector<KeyLocation>& ks, KeyType t) {
  for (const auto& k : ks)
    if (k.type == t) return &k;
  return nullptr;
}

TEST(KeyLocation, ExitIsTheLaneCentreAtTheLastPlants) {
  test::SynthScene s;
  s.rows = test::block(1, 1.0, -5.0, 2.0);
  const core::Pose2 T(0.0, 0.45, 0.0);  // 5 cm right of the lane centre
  KeyLocator k;
  const auto valid = k.update(rows_of(s, T, 1), T);
  const KeyLocation* exit = find(valid, KeyType::exit);
  ASSERT_NE(exit, nullptr);
  EXPECT_EQ(exit->side, KeySide::middle);
  // The scanner sees the last plants' near sides (plant radius 0.12 m, noise 1 cm): the exit
  // lies within a radius and noise of the last plant centres.
  EXPECT_NEAR(exit->p.x(), 2.0, 0.2);
  EXPECT_LT(exit->p.x(), 2.0 + 0.02);
  EXPECT_NEAR(exit->p.y(), 0.5, 0.03);
  EXPECT_NEAR(exit->v.x(), 1.0, 1e-3);
}

TEST(KeyLocation, EntryIsTheLaneCentreAtTheFirstPlants) {
  test::SynthScene s;
  s.rows = test::block(1, 1.0, 0.0, 10.0);
  const core::Pose2 T(-1.5, 0.5, 0.0);
  KeyLocator k;
  const auto valid = k.update(rows_of(s, T, 2), T);
  const KeyLocation* entry = find(valid, KeyType::entry);
  ASSERT_NE(entry, nullptr);
  EXPECT_NEAR(entry->p.x(), 0.0, 0.15);
  EXPECT_NEAR(entry->p.y(), 0.5, 0.03);
}

// The rows' lines lie on the plants' faces seen from the lane, so d is half the free width
// between them; 0.3 m more row spacing gives 0.15 m more d, and the exit stays centred.
TEST(KeyLocation, HalfWidthFollowsTheRowCentroids) {
  std::array<double, 2> d{};
  for (int i = 0; i < 2; ++i) {
    const double w = i == 0 ? 1.0 : 1.3;
    test::SynthScene s;
    s.rows = test::block(1, w, -3.0, 3.0);
    const core::Pose2 T(0.0, w / 2, 0.0);
    KeyLocator k;  // a priori lane width 1.0 m
    const auto valid = k.update(rows_of(s, T, 3), T);
    d[static_cast<std::size_t>(i)] = k.half_width();
    const KeyLocation* exit = find(valid, KeyType::exit);
    ASSERT_NE(exit, nullptr);
    EXPECT_NEAR(exit->p.y(), w / 2, 0.03);
    k.reset();
    EXPECT_DOUBLE_EQ(k.half_width(), 0.5);
  }
  EXPECT_NEAR(d[1] - d[0], 0.15, 0.02);
  EXPECT_LT(d[0], 0.5);  // free width < row spacing
}

TEST(KeyLocation, OneSidedRowGivesASideKeyLocationAtTheAlleyCentre) {
  test::SynthScene s;
  s.rows = {{0.0, -3.0, 2.0, PointLabel::crop, {}}};
  const core::Pose2 T(0.0, -0.5, 0.0);  // in the alley right of the row
  KeyLocator k;
  const auto valid = k.update(rows_of(s, T, 4), T);
  const KeyLocation* exit = find(valid, KeyType::exit);
  ASSERT_NE(exit, nullptr);
  EXPECT_EQ(exit->side, KeySide::left);
  // d from the row's seen face: within a plant radius (0.12 m) of the alley centre line y = -0.5.
  EXPECT_NEAR(exit->p.y(), -0.5, 0.12);
}

class KeyRules : public ::testing::Test {
 protected:
  KeyLocation key(double x, double y, double heading_deg, KeyType t = KeyType::exit) const {
    KeyLocation k;
    k.type = t;
    k.p = {x, y};
    k.v = {std::cos(heading_deg * kDeg), std::sin(heading_deg * kDeg)};
    return k;
  }
  KeyLocator locator;
  core::Pose2 robot{0.0, 0.0, 0.0};
};

TEST_F(KeyRules, AheadAlignedAndNearIsValid) {
  EXPECT_EQ(locator.check(key(3.0, 0.1, 5.0), robot), KeyVerdict::valid);
}
TEST_F(KeyRules, BehindTheRobotIsInvalid) {
  EXPECT_EQ(locator.check(key(-0.2, 0.0, 0.0), robot), KeyVerdict::behind);
}
TEST_F(KeyRules, FartherThanTheHeadlandIsInvalid) {
  EXPECT_EQ(locator.check(key(6.5, 0.0, 0.0), robot), KeyVerdict::too_far);
}
TEST_F(KeyRules, OrientationBeyondTenDegreesIsInvalid) {
  EXPECT_EQ(locator.check(key(3.0, 0.0, 9.0), robot), KeyVerdict::valid);
  EXPECT_EQ(locator.check(key(3.0, 0.0, 11.0), robot), KeyVerdict::misoriented);
}
TEST_F(KeyRules, AlignmentBeyondFortyCentimetresIsInvalid) {
  EXPECT_EQ(locator.check(key(3.0, 0.39, 0.0), robot), KeyVerdict::valid);
  EXPECT_EQ(locator.check(key(3.0, 0.41, 0.0), robot), KeyVerdict::misaligned);
}
TEST_F(KeyRules, EntryOrientationGateCanBeTurnedOff) {
  KeyLocationConfig cfg;
  cfg.gate_entry_by_robot = false;
  const KeyLocator loose(cfg);
  EXPECT_EQ(loose.check(key(3.0, 0.0, 30.0, KeyType::entry), robot), KeyVerdict::valid);
  EXPECT_EQ(locator.check(key(3.0, 0.0, 30.0, KeyType::entry), robot), KeyVerdict::misoriented);
}

TEST(KeyLocation, SetLaneWidthRescalesDWithinTheNewBounds) {
  KeyLocationConfig cfg;  // a priori 1 m: d = 0.5 m
  KeyLocator locator(cfg);
  EXPECT_DOUBLE_EQ(locator.half_width(), 0.5);
  EXPECT_TRUE(locator.set_lane_width(1.8));  // a measured row spacing
  EXPECT_DOUBLE_EQ(locator.half_width(), 0.9);
  EXPECT_DOUBLE_EQ(locator.config().lane_width, 1.8);
  locator.reset();  // a new local frame starts from the new a priori width
  EXPECT_DOUBLE_EQ(locator.half_width(), 0.9);
  for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_FALSE(locator.set_lane_width(bad)) << bad;
  EXPECT_DOUBLE_EQ(locator.config().lane_width, 1.8);
}

TEST(PlaceEstimator, SetLaneWidthReachesTheKeyLocations) {
  PlaceEstimator est;
  EXPECT_TRUE(est.set_lane_width(2.5));
  EXPECT_DOUBLE_EQ(est.config().key_locations.lane_width, 2.5);
  EXPECT_FALSE(est.set_lane_width(std::nan("")));
  EXPECT_DOUBLE_EQ(est.config().key_locations.lane_width, 2.5);
}

TEST(KeyLocation, ConfigValidationNamesTheField) {
  KeyLocationConfig cfg;
  cfg.max_orientation_deg = 120.0;
  EXPECT_THROW(cfg.validate(), std::invalid_argument);
  try {
    cfg.validate();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_orientation_deg"), std::string::npos);
  }
}

}  // namespace
}  // namespace rownav::map
