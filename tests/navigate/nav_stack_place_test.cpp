// navigate::NavStack with the map stage (issue 12): labelled or unlabelled frames in, the place
// and the key locations out of command().
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "common/planar_scan.hpp"
#include "map/map_scene.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/navigate/nav_stack.hpp"
#include "rownav/track/raw_corridor.hpp"

namespace rownav::navigate {
namespace {

constexpr double kSpacing = 1.8;  // [m] rows y = 0, 1.8, 3.6, 5.4; the robot in the middle lane
constexpr double kLaneY = 2.7;
constexpr double kRowEnd = 12.0;  // [m] rows from x = 0 to 12
constexpr double kRowZ = 0.5;     // [m] height of the row points (inside the default band)

map::test::SynthScene scene() {
  map::test::SynthScene s;
  s.rows = map::test::block(3, kSpacing, 0.0, kRowEnd);
  s.range = 6.0;
  return s;
}

NavStack make_stack(bool enabled, double a_priori_lane_width = kSpacing) {
  NavStackConfig c;
  c.stack.mode = StackMode::track;
  c.stack.odometry = OdometryInput::external;
  c.stack.level_by_gravity = false;
  c.place.enabled = enabled;
  c.place.estimator.key_locations.lane_width = a_priori_lane_width;
  NavStackParts parts;
  parts.pipeline =
      std::make_unique<detect::DetectionPipeline>(io::make_pipeline("parallel_lines", ""));
  parts.tracker = std::make_unique<track::RawCorridorTracker>();
  return NavStack(c, std::move(parts));
}

/// The labelled frame as a 3D cloud (base = LiDAR frame): the row points at kRowZ, plus a
/// ground grid at z = 0 labelled ground.
std::pair<core::PointCloud, std::vector<map::PointLabel>> cloud_of(const map::test::Frame& f,
                                                                   double stamp) {
  constexpr float kGridStep = 0.25f, kGridHalf = 6.0f;
  std::pair<core::PointCloud, std::vector<map::PointLabel>> out;
  auto& [cloud, labels] = out;
  cloud.stamp = stamp;
  for (std::size_t i = 0; i < f.points.size(); ++i) {
    cloud.points.push_back({f.points[i].x(), f.points[i].y(), static_cast<float>(kRowZ)});
    labels.push_back(f.labels[i]);
  }
  for (float x = -kGridHalf; x <= kGridHalf; x += kGridStep)
    for (float y = -kGridHalf; y <= kGridHalf; y += kGridStep) {
      cloud.points.push_back({x, y, 0.0f});
      labels.push_back(map::PointLabel::ground);
    }
  return out;
}

enum class Input { labelled_cloud, unlabelled_cloud, scan };

/// Drives the middle lane from x = -3 to 15 at 0.5 m/s, a frame every 0.1 s; every command.
std::vector<NavCommand> drive(NavStack& s, Input input) {
  constexpr double kStep = 0.05, kX0 = -3.0, kX1 = 15.0, kPeriod = 0.1;
  const auto sc = scene();
  std::mt19937_64 rng(12);
  std::vector<NavCommand> out;
  double t = 0.0;
  for (double x = kX0; x <= kX1; x += kStep, t += kPeriod) {
    const core::Pose2 T(x, kLaneY, 0.0);
    s.on_odometry({t, T, core::Twist2{kStep / kPeriod, 0.0}});
    const auto f = map::test::scan(sc, T, rng);
    if (input == Input::scan) {
      s.on_scan(test::planar_scan(f.points, t));
    } else {
      auto [cloud, labels] = cloud_of(f, t);
      if (input == Input::unlabelled_cloud) labels.clear();
      s.on_cloud(std::move(cloud), std::move(labels));
    }
    out.push_back(s.command(t));
  }
  return out;
}

/// The places of the commands, consecutive repeats removed.
std::vector<map::Place> sequence(const std::vector<NavCommand>& cmds) {
  std::vector<map::Place> seq;
  for (const auto& c : cmds)
    if (seq.empty() || seq.back() != c.place) seq.push_back(c.place);
  return seq;
}

std::vector<PlaceKey> keys(const std::vector<NavCommand>& cmds) {
  std::vector<PlaceKey> k;
  for (const auto& c : cmds) k.insert(k.end(), c.key_locations.begin(), c.key_locations.end());
  return k;
}

const std::vector<map::Place> kLaneThenHeadland{map::Place::headland, map::Place::lane,
                                                map::Place::headland};

void expect_row_end_keys(const std::vector<PlaceKey>& k) {
  ASSERT_EQ(k.size(), 2u);
  EXPECT_EQ(k[0].to, map::Place::lane);
  EXPECT_EQ(k[1].to, map::Place::headland);
  // The odometry frame is the world here: the lane centre at the row ends.
  EXPECT_NEAR(k[0].key.p.x(), 0.0, 0.3);
  EXPECT_NEAR(k[1].key.p.x(), kRowEnd, 0.3);
  for (const auto& key : k) EXPECT_NEAR(key.key.p.y(), kLaneY, 0.1);
}

TEST(NavStackPlace, LabelledCloudsGiveHeadlandLaneHeadlandAndTheRowEndKeys) {
  NavStack s = make_stack(true);
  const auto cmds = drive(s, Input::labelled_cloud);
  EXPECT_EQ(sequence(cmds), kLaneThenHeadland);
  expect_row_end_keys(keys(cmds));
  int frames = 0;
  for (const auto& c : cmds) frames += c.frame && c.frame->place ? 1 : 0;
  EXPECT_EQ(frames, static_cast<int>(cmds.size()));
  // In the middle of the lane the place is the lane.
  EXPECT_EQ(cmds[cmds.size() / 2].place, map::Place::lane);
}

TEST(NavStackPlace, WithoutLabelsTheDetectedRowsAreTheCrop) {
  for (const Input input : {Input::unlabelled_cloud, Input::scan}) {
    NavStack s = make_stack(true);
    const auto cmds = drive(s, input);
    EXPECT_EQ(sequence(cmds), kLaneThenHeadland) << static_cast<int>(input);
    expect_row_end_keys(keys(cmds));
  }
}

TEST(NavStackPlace, TheLaneWidthIsTheTrackersRowSpacing) {
  NavStack s = make_stack(true, 1.0);  // a priori 1 m; the rows are 1.8 m apart
  const auto cmds = drive(s, Input::labelled_cloud);
  ASSERT_NE(s.place_estimator(), nullptr);
  // The last spacing the tracker measured following both rows (the raw corridor tracker's is
  // face to face here: the plants' near sides, 2 x 0.12 m less than 1.8 m).
  double measured = 0.0;
  for (const auto& c : cmds) {
    const auto& t = c.frame ? c.frame->tracking : std::nullopt;
    if (t && t->status == track::TrackStatus::tracking && t->left >= 0 && t->right >= 0 &&
        t->row_spacing > 0.0)
      measured = t->row_spacing;
  }
  EXPECT_GT(measured, 1.4);
  EXPECT_DOUBLE_EQ(s.place_estimator()->config().key_locations.lane_width, measured);
  EXPECT_EQ(sequence(cmds), kLaneThenHeadland);
}

TEST(NavStackPlace, DisabledByDefaultAndThenSilent) {
  EXPECT_FALSE(NavStackConfig{}.place.enabled);
  NavStack s = make_stack(false);
  EXPECT_EQ(s.place_estimator(), nullptr);
  for (const auto& c : drive(s, Input::labelled_cloud)) {
    EXPECT_EQ(c.place, map::Place::unknown);
    EXPECT_TRUE(c.key_locations.empty());
    if (c.frame) {
      EXPECT_FALSE(c.frame->place.has_value());
    }
  }
}

void expect_invalid(const NavStackConfig& c, const std::string& field) {
  NavStackParts parts;
  parts.pipeline =
      std::make_unique<detect::DetectionPipeline>(io::make_pipeline("parallel_lines", ""));
  parts.tracker = std::make_unique<track::RawCorridorTracker>();
  try {
    NavStack s(c, std::move(parts));
    FAIL() << "accepted " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(NavStackPlace, ConfigValidationNamesTheField) {
  NavStackConfig c;
  c.stack.mode = StackMode::track;
  NavStackConfig band = c;
  band.place.band_z_max = band.place.band_z_min;
  expect_invalid(band, "place.band_z_max");
  NavStackConfig margin = c;
  margin.place.row_margin = -0.1;
  expect_invalid(margin, "place.row_margin");
  NavStackConfig width = c;
  width.place.estimator.key_locations.lane_width = 0.0;
  expect_invalid(width, "place.estimator.key_locations.lane_width");
}

TEST(GeometricLabel, PointsOfADetectedRowAreCropTheRestGround) {
  core::RowObservation obs;
  core::RowLine left;  // fitted face 0.9 m left, centre line 0.2 m beyond it, 0.25 m half width
  left.line = core::Line2({0.0, 0.9}, {1.0, 0.0});
  left.offset = 0.9;
  left.centre_shift = 0.2;
  left.half_width = 0.25;
  obs.rows.push_back(left);
  constexpr double kMargin = 0.1;
  EXPECT_EQ(geometric_label({2.0f, 1.1f}, obs, kMargin), map::PointLabel::crop);    // centre
  EXPECT_EQ(geometric_label({2.0f, 1.4f}, obs, kMargin), map::PointLabel::crop);    // outer edge
  EXPECT_EQ(geometric_label({2.0f, 0.8f}, obs, kMargin), map::PointLabel::crop);    // inner edge
  EXPECT_EQ(geometric_label({2.0f, 1.5f}, obs, kMargin), map::PointLabel::ground);  // past it
  EXPECT_EQ(geometric_label({2.0f, 0.6f}, obs, kMargin), map::PointLabel::ground);  // corridor
  EXPECT_EQ(geometric_label({2.0f, 1.7f}, obs, kMargin), map::PointLabel::ground);  // beyond
  EXPECT_EQ(geometric_label({2.0f, 1.1f}, core::RowObservation{}, kMargin),
            map::PointLabel::ground);  // no rows detected: nothing is crop
}

}  // namespace
}  // namespace rownav::navigate
