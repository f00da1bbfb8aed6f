// End-of-row detection on synthetic vine rows (known row end) and on simulated OS1-16 frames of a
// generated vineyard, several distances before the row end.
#include "rownav/navigate/end_of_row.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace rownav::navigate {
namespace {

// Two vine rows at y = +-1 m (canopy 0.4 m wide, 0.3-1.8 m high, 150 points per metre and row)
// from x = -5 m to x = row_end, plus low weeds (z < 0.4 m) everywhere in the corridor and beyond.
core::PointCloud vine_rows(double row_end, bool weeds, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  core::PointCloud c;
  const double length = row_end + 5.0;
  for (const float side : {-1.0f, 1.0f})
    for (int i = 0; i < static_cast<int>(150 * length); ++i)
      c.points.push_back({float(-5.0 + length * u(rng)), side * 1.0f + 0.4f * (u(rng) - 0.5f),
                          0.3f + 1.5f * u(rng)});
  if (weeds)
    for (int i = 0; i < 3000; ++i)
      c.points.push_back({-5.0f + 20.0f * u(rng), 3.0f * (u(rng) - 0.5f), 0.4f * u(rng)});
  return c;
}

track::RowTracking no_tracking() {
  return {};
}

TEST(EndOfRow, MiddleOfTheRowIsNotTheEnd) {
  EndOfRowDetector d;
  for (int k = 0; k < 10; ++k) {
    const auto r = d.update(vine_rows(20.0, true, k), {}, no_tracking());
    EXPECT_FALSE(r.frame_positive);
    EXPECT_FALSE(r.end_detected);
    EXPECT_GT(r.left_points, d.config().point_threshold);
    EXPECT_GT(r.right_points, d.config().point_threshold);
  }
}

TEST(EndOfRow, DetectedWhenTheRowEndsTwoToFourMetresAhead) {
  // The robot drives at 0.5 m/s with 10 Hz frames: the row end comes 5 cm closer each frame.
  EndOfRowDetector d;
  double detected_at = -1.0;
  std::optional<double> estimate;
  for (int k = 0; k <= 160 && detected_at < 0.0; ++k) {
    const double row_end = 10.0 - 0.05 * k;
    const auto r = d.update(vine_rows(row_end, true, 100 + k), {}, no_tracking());
    if (r.end_detected) detected_at = row_end, estimate = r.distance_to_end;
  }
  std::printf("[ synthetic ] end declared with the row end %.2f m ahead (estimate %.2f m)\n",
              detected_at, estimate.value_or(-1.0));
  EXPECT_GE(detected_at, 2.0);
  EXPECT_LE(detected_at, 4.0);
  ASSERT_TRUE(estimate.has_value());
  EXPECT_NEAR(*estimate, detected_at, 0.2);
}

TEST(EndOfRow, LowWeedsDoNotHideTheEnd) {
  // Rows ended 1 m ahead; a dense weed carpet below 0.5 m fills the box: still the end.
  EndOfRowDetector d;
  EndOfRowResult r;
  for (int k = 0; k < 3; ++k) r = d.update(vine_rows(1.0, true, 7 + k), {}, no_tracking());
  EXPECT_TRUE(r.end_detected);
  EXPECT_EQ(r.box_points, 0);
}

TEST(EndOfRow, NeedsConsecutiveFramesAndLatches) {
  EndOfRowDetector d;
  EXPECT_FALSE(d.update(vine_rows(1.0, false, 1), {}, no_tracking()).end_detected);
  EXPECT_FALSE(d.update(vine_rows(20.0, false, 2), {}, no_tracking()).end_detected);  // resets
  EXPECT_FALSE(d.update(vine_rows(1.0, false, 3), {}, no_tracking()).end_detected);
  EXPECT_FALSE(d.update(vine_rows(1.0, false, 4), {}, no_tracking()).end_detected);
  EXPECT_TRUE(d.update(vine_rows(1.0, false, 5), {}, no_tracking()).end_detected);
  EXPECT_TRUE(d.update(vine_rows(20.0, false, 6), {}, no_tracking()).end_detected);  // latched
  d.reset();
  EXPECT_FALSE(d.update(vine_rows(20.0, false, 7), {}, no_tracking()).end_detected);
}

TEST(EndOfRow, CountJumpOfEq24) {
  EndOfRowDetector d;
  EXPECT_FALSE(d.update(vine_rows(20.0, false, 1), {}, no_tracking()).count_jump);
  EXPECT_FALSE(d.update(vine_rows(20.0, false, 2), {}, no_tracking()).count_jump);
  EXPECT_TRUE(d.update(vine_rows(3.5, false, 3), {}, no_tracking()).count_jump);
}

TEST(EndOfRow, PlanarScanRectangle) {
  // No cloud: the 2D points are counted in the whole rectangle (Bertoglio 2023 sec. II-C).
  std::vector<Eigen::Vector2f> in_row, ended;
  for (float x = -5.0f; x < 15.0f; x += 0.1f)
    in_row.push_back({x, 1.0f}), in_row.push_back({x, -1.0f});
  for (float x = -5.0f; x < 2.0f; x += 0.1f)
    ended.push_back({x, 1.0f}), ended.push_back({x, -1.0f});
  ended.push_back({std::nanf(""), 0.0f});
  EndOfRowDetector d;
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(d.update({}, in_row, no_tracking()).end_detected);
  EndOfRowResult r;
  for (int k = 0; k < 3; ++k) r = d.update({}, ended, no_tracking());
  EXPECT_TRUE(r.end_detected);
  ASSERT_TRUE(r.distance_to_end.has_value());
  EXPECT_NEAR(*r.distance_to_end, 1.9, 0.11);
}

TEST(EndOfRow, TrackedExtentCue) {
  track::RowTracking t;
  t.status = track::TrackStatus::tracking;
  t.rows.resize(2);
  t.right = 0, t.left = 1;
  t.rows[0].x_max = 2.5, t.rows[1].x_max = 2.7;
  EndOfRowDetector d;
  EndOfRowResult r;
  // A cloud full of points (e.g. a hedge beyond the headland) but the tracked rows end at 2.5 m.
  for (int k = 0; k < 3; ++k) r = d.update(vine_rows(20.0, false, k), {}, t);
  EXPECT_TRUE(r.end_detected);
  ASSERT_TRUE(r.distance_to_end.has_value());
  EXPECT_DOUBLE_EQ(*r.distance_to_end, 2.7);  // past both rows' ends
  t.status = track::TrackStatus::lost;        // a lost tracker's extent is not trusted
  EndOfRowDetector d2;
  for (int k = 0; k < 3; ++k) r = d2.update(vine_rows(20.0, false, k), {}, t);
  EXPECT_FALSE(r.end_detected);
}

// Two tracked rows with the given x_max (right, left).
track::RowTracking tracked_rows(double right_x_max, double left_x_max) {
  track::RowTracking t;
  t.status = track::TrackStatus::tracking;
  t.rows.resize(2);
  t.right = 0, t.left = 1;
  t.rows[0].x_max = right_x_max, t.rows[1].x_max = left_x_max;
  return t;
}

TEST(EndOfRow, GapInOneRowIsNotTheEnd) {
  // The left row's support stops at a 3-vine gap 1.5 m ahead; the right row goes on to 9 m.
  EndOfRowDetector d;
  EndOfRowResult r;
  for (int k = 0; k < 10; ++k) r = d.update(vine_rows(20.0, false, k), {}, tracked_rows(9.0, 1.5));
  EXPECT_FALSE(r.end_detected);
}

TEST(EndOfRow, SparseCanopyCountIsOverruledByRowsTrackedBeyondTheBox) {
  // Young shoots: too few points in the box for the count cue, but both rows are tracked to 9 m.
  core::PointCloud sparse = vine_rows(20.0, false, 3);
  sparse.points.resize(sparse.points.size() / 20);
  EndOfRowDetector d;
  EndOfRowResult r;
  for (int k = 0; k < 10; ++k) r = d.update(sparse, {}, tracked_rows(9.0, 8.5));
  EXPECT_LT(r.left_points, d.config().point_threshold);  // the count alone would say "end"
  EXPECT_FALSE(r.end_detected);
  EndOfRowDetector d2;  // without tracking the count decides
  for (int k = 0; k < 10; ++k) r = d2.update(sparse, {}, no_tracking());
  EXPECT_TRUE(r.end_detected);
}

TEST(EndOfRow, BadConfigNamesTheField) {
  EndOfRowConfig c;
  c.box_x_max = 1.0;
  try {
    EndOfRowDetector{c};
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("box_x_min"), std::string::npos);
  }
}

// One OS1-16 sweep in corridor 2 of a generated vineyard, `distance` [m] before the row end, in
// the base frame.
core::PointCloud sim_frame(const sim::Field& field, const sim::RayCaster& caster, double distance) {
  const auto centre =
      sim::FieldTruth(field).corridor_centre(0, 2);  // a copy: the truth is a temporary
  const Eigen::Vector2d end = centre.back();
  const Eigen::Vector2d tangent = (centre.back() - centre[centre.size() - 2]).normalized();
  const Eigen::Vector2d xy = end - distance * tangent;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(xy.x(), xy.y(), field.terrain.height(xy.x(), xy.y()));
  T.linear() = Eigen::AngleAxisd(std::atan2(tangent.y(), tangent.x()), Eigen::Vector3d::UnitZ())
                   .toRotationMatrix();
  const auto config = sim::lidar_preset("os1_16");
  sim::Lidar lidar(config, 5);
  core::PointCloud cloud = lidar.sweep(
      caster, [&](double) { return T; }, 0.0);
  const Eigen::Isometry3f T_bl = config.T_base_lidar().cast<float>();
  for (auto& p : cloud.points) {
    const Eigen::Vector3f q = T_bl * Eigen::Vector3f(p.x, p.y, p.z);
    p.x = q.x(), p.y = q.y(), p.z = q.z();
  }
  return cloud;
}

TEST(EndOfRowSim, SimulatedVineyardFrames) {
  sim::FieldConfig f;
  f.vineyard.rows = 5;
  f.vineyard.row_length = 20.0;
  const sim::Field field = sim::generate_field(f);
  const sim::RayCaster caster(field.mesh);
  track::RowTracking t;
  t.row_spacing = field.row_spacing;
  for (const double distance : {10.0, 7.0, 5.0, 4.0, 2.5, 1.5}) {
    EndOfRowDetector d;
    const core::PointCloud cloud = sim_frame(field, caster, distance);
    EndOfRowResult r;
    for (int k = 0; k < d.config().confirm_frames; ++k) r = d.update(cloud, {}, t);
    std::printf("[ sim os1_16 ] row end %.1f m ahead: box %d (L %d R %d), end %d, est %.2f m\n",
                distance, r.box_points, r.left_points, r.right_points, int(r.end_detected),
                r.distance_to_end.value_or(-1.0));
    // Within the row (end beyond the box) never; with the end before the box's near edge, yes.
    if (distance >= d.config().box_x_max) {
      EXPECT_FALSE(r.end_detected) << distance;
    }
    if (distance <= 2.5) {
      EXPECT_TRUE(r.end_detected) << distance;
      ASSERT_TRUE(r.distance_to_end.has_value());
      EXPECT_NEAR(*r.distance_to_end, distance, 0.5) << distance;
    }
  }
}

}  // namespace
}  // namespace rownav::navigate

namespace rownav::navigate {
namespace {

// A planar scan of two rows' faces at y = +-0.3 m from x = 0 to row_end, ~200 points a metre.
std::vector<Eigen::Vector2f> planar_rows(double row_end) {
  std::vector<Eigen::Vector2f> pts;
  for (double x = 0.3; x < row_end; x += 0.005)
    for (const double y : {-0.3, 0.3}) pts.emplace_back(float(x), float(y));
  return pts;
}

TEST(EndOfRow, PlanarScanEmptiedByTheRowEndIsTheEnd) {
  EndOfRowConfig c;
  c.box_x_min = 1.0, c.box_x_max = 2.0;
  EndOfRowDetector d(c);
  EndOfRowResult r;
  const auto pts = planar_rows(0.8);  // the rows end before the box: open ground ahead
  for (int k = 0; k < c.confirm_frames; ++k) r = d.update(core::PointCloud{}, pts, no_tracking());
  EXPECT_TRUE(r.end_detected);
}

TEST(EndOfRow, PlanarScanShadowedByAWeedAheadIsNoEvidence) {
  // A weed 0.4 m ahead in the lane blocks the beams towards the box: the box is empty because
  // it is unseen, not because the rows ended (issue 11).
  EndOfRowConfig c;
  c.box_x_min = 1.0, c.box_x_max = 2.0;
  EndOfRowDetector d(c);
  auto pts = planar_rows(0.8);
  for (double y = -0.45; y <= 0.45; y += 0.005) pts.emplace_back(0.4f, float(y));
  EndOfRowResult r;
  for (int k = 0; k < 2 * c.confirm_frames; ++k)
    r = d.update(core::PointCloud{}, pts, no_tracking());
  EXPECT_FALSE(r.frame_positive);
  EXPECT_FALSE(r.end_detected);
}

TEST(EndOfRow, APlanarBoxIsShadowedAsSeenFromTheScannerNotFromTheBase) {
  // A weed touching a scanner at the robot's front (x = 0.35 m): from the scanner it hides the
  // whole box, from the base origin a few degrees of it (issue 11).
  EndOfRowConfig c;
  c.box_x_min = 1.0, c.box_x_max = 2.0;
  std::vector<Eigen::Vector2f> pts;  // rows 1.5 m apart ending 0.8 m ahead, the weed
  for (double x = 0.3; x < 0.8; x += 0.005)
    for (const double y : {-0.75, 0.75}) pts.emplace_back(float(x), float(y));
  // one return per beam of a 0.25 deg scanner 0.07 m away
  for (double y = -0.06; y <= 0.06; y += 0.0003) pts.emplace_back(0.42f, float(y));
  EndOfRowDetector from_base(c), from_scanner(c);
  EndOfRowResult rb, rs;
  for (int k = 0; k < 2 * c.confirm_frames; ++k) {
    rb = from_base.update(core::PointCloud{}, pts, no_tracking());
    rs = from_scanner.update(core::PointCloud{}, pts, no_tracking(),
                             Eigen::Vector3f(0.35f, 0.0f, 0.0f));
  }
  EXPECT_TRUE(rb.end_detected);  // the old reading: the box empty, so the row ended
  EXPECT_FALSE(rs.frame_positive);
  EXPECT_FALSE(rs.end_detected);
}

TEST(EndOfRow, ABlindPlanarFrameNeitherConfirmsNorClearsTheEnd) {
  // The scanner inside a weed taller than its mount: almost no returns anywhere, the rows beside
  // the robot gone too. At a row end they are still seen (issue 11).
  EndOfRowConfig c;
  c.box_x_min = 1.0, c.box_x_max = 2.0;
  EndOfRowDetector d(c);
  const auto in_row = planar_rows(5.0), at_end = planar_rows(0.8);
  const std::vector<Eigen::Vector2f> blind{{0.35f, 0.0f}};
  for (int k = 0; k < 10; ++k)
    EXPECT_FALSE(d.update(core::PointCloud{}, in_row, no_tracking()).frame_positive);
  for (int k = 0; k < 2 * c.confirm_frames; ++k) {
    const auto r = d.update(core::PointCloud{}, blind, no_tracking());
    EXPECT_TRUE(r.blind);
    EXPECT_FALSE(r.frame_positive);
    EXPECT_FALSE(r.end_detected);
  }
  // Evidence before a blind spell still counts after it: the count is kept, not reset.
  EXPECT_FALSE(d.update(core::PointCloud{}, at_end, no_tracking()).blind);
  d.update(core::PointCloud{}, blind, no_tracking());
  EndOfRowResult r;
  for (int k = 1; k < c.confirm_frames; ++k)
    r = d.update(core::PointCloud{}, at_end, no_tracking());
  EXPECT_TRUE(r.end_detected);
  // With the test off the same blind frames are an empty box.
  c.blind_near_ratio = 0.0;
  EndOfRowDetector off(c);
  for (int k = 0; k < 10; ++k) off.update(core::PointCloud{}, in_row, no_tracking());
  for (int k = 0; k < c.confirm_frames; ++k)
    r = off.update(core::PointCloud{}, blind, no_tracking());
  EXPECT_TRUE(r.end_detected);
}

// A 16-ring sweep (+-16.6 deg, 2.2 deg apart, azimuth +-40 deg every 0.5 deg) from a sensor
// 0.75 m above flat, bare ground at base x = 0.3 m (the rows have ended), levelled, with the
// robot pitched up by `pitch_deg`: only the ground hits of the downward rings.
core::PointCloud bare_ground_sweep(double pitch_deg) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  core::PointCloud c;
  for (int ring = 0; ring < 16; ++ring) {
    const double down = (16.6 - 2.2 * ring - pitch_deg) * kDeg;  // ray slope below horizontal
    if (down <= 0.0) continue;
    const double d = 0.75 / std::tan(down);
    for (double a = -40.0; a <= 40.0; a += 0.5)
      c.points.push_back(
          {float(0.3 + d * std::cos(a * kDeg)), float(d * std::sin(a * kDeg)), 0.0f});
  }
  return c;
}

TEST(EndOfRow, ASweepWhoseRaysPassOverTheBandNeitherConfirmsNorClearsTheEnd) {
  // Row-crop box (config/navigate/row_crop.yaml): band 0.3-0.9 m, 1-2 m ahead. Level, the lowest
  // ring comes down to 0.3 m at x = 1.81 m: the box is seen, and empty. Pitched up 5 deg it is
  // still 0.40 m high at the box's far edge: a 0.3-0.45 m crop there would not be seen.
  EndOfRowConfig c;
  c.band_z_min = 0.3, c.band_z_max = 0.9, c.box_x_min = 1.0, c.box_x_max = 2.0;
  const Eigen::Vector3f sensor(0.3f, 0.0f, 0.75f);
  const core::PointCloud level = bare_ground_sweep(0.0), pitched = bare_ground_sweep(5.0);
  EndOfRowDetector d(c);
  for (int k = 0; k < 10; ++k) {
    const auto r = d.update(pitched, {}, no_tracking(), sensor);
    EXPECT_TRUE(r.blind);
    EXPECT_FALSE(r.box_seen);
    EXPECT_FALSE(r.end_detected);
  }
  // Level, pitched, level, level: the pitched sweep does not clear the count.
  EXPECT_FALSE(d.update(level, {}, no_tracking(), sensor).end_detected);
  EXPECT_TRUE(d.update(pitched, {}, no_tracking(), sensor).blind);
  EXPECT_FALSE(d.update(level, {}, no_tracking(), sensor).end_detected);
  const auto r = d.update(level, {}, no_tracking(), sensor);
  EXPECT_FALSE(r.blind);
  EXPECT_TRUE(r.end_detected);
  // Without the check the pitched sweeps are an empty box (the behaviour before issue 10's fix).
  c.check_view = false;
  EndOfRowDetector unchecked(c);
  EndOfRowResult u;
  for (int k = 0; k < c.confirm_frames; ++k)
    u = unchecked.update(pitched, {}, no_tracking(), sensor);
  EXPECT_TRUE(u.end_detected);
}

TEST(EndOfRow, ASensorBelowTheBandIsNotJudgedByTheView) {
  EndOfRowConfig c;
  c.band_z_min = 0.3, c.band_z_max = 0.9, c.box_x_min = 1.0, c.box_x_max = 2.0;
  EndOfRowDetector d(c);
  EndOfRowResult r;
  for (int k = 0; k < c.confirm_frames; ++k)
    r = d.update(bare_ground_sweep(5.0), {}, no_tracking(), Eigen::Vector3f(0.3f, 0.0f, 0.2f));
  EXPECT_FALSE(r.blind);
  EXPECT_TRUE(r.end_detected);
}

TEST(EndOfRow, ShadowSettingsAreValidated) {
  EndOfRowConfig c;
  c.max_shadowed = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = EndOfRowConfig{};
  c.shadow_bin_deg = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = EndOfRowConfig{};
  c.blind_near_ratio = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = EndOfRowConfig{};
  c.blind_history = 0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = EndOfRowConfig{};
  c.shadow_link = -0.1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = EndOfRowConfig{};
  c.shadow_wall = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::navigate
