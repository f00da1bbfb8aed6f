// Issue 10: the row spacing every tracker reports is centre to centre, on thick (solid hedge)
// and thin canopies, with the robot off-centre and yawed; a missing row does not double it.
// Property tests over seeded random fields: a few LiDAR sweeps cast along a corridor go through
// the vineyard detection pipeline and each tracker with ground-truth odometry.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>

#include "rownav/detect/pipeline.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/simulator.hpp"
#include "rownav/track/row_geometry.hpp"

namespace rownav::test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const std::string kDetect = std::string(ROWNAV_SOURCE_DIR) + "/config/detect/vineyard.yaml";

struct Case {
  double spacing = 1.8, half_width = 0.25;  // [m] truth
  double lateral = 0.0, yaw = 0.0;          // [m], [rad] robot from the corridor centre line
  sim::CanopyShape shape = sim::CanopyShape::solid_hedge;
  sim::GrowthStage stage = sim::GrowthStage::medium;
  std::uint64_t seed = 1;
};

Case random_case(std::mt19937_64& rng, sim::CanopyShape shape) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Case c;
  c.spacing = 1.5 + 1.5 * u(rng);
  c.half_width = shape == sim::CanopyShape::solid_hedge ? 0.2 + 0.25 * u(rng) : 0.2 + 0.1 * u(rng);
  c.lateral = -0.3 + 0.6 * u(rng);
  c.yaw = (-10.0 + 20.0 * u(rng)) * kDeg;
  c.shape = shape;
  c.stage = u(rng) < 0.5 ? sim::GrowthStage::low : sim::GrowthStage::high;
  c.seed = rng();
  return c;
}

/// The last row_spacing of `tracker` after 12 sweeps 0.4 m apart along corridor 2 of 6 rows.
double tracked_spacing(const Case& c, const std::string& tracker_name) {
  sim::FieldConfig fc;
  fc.vineyard.rows = 6;
  fc.vineyard.row_length = 16.0;
  fc.vineyard.row_spacing = c.spacing;
  fc.vineyard.canopy_width = 2.0 * c.half_width;
  fc.vineyard.canopy_shape = c.shape;
  fc.vineyard.stage = c.stage;
  fc.vineyard.gap_count = 0;
  fc.vineyard.missing_plants_percent = 0.0;
  fc.seed = c.seed;
  const sim::Field field = sim::generate_field(fc);
  sim::SimConfig sc;
  sc.lidar.mount_xyz = {0.3, 0.0, 0.75};  // config/sensors/os1_16.yaml
  sc.seed = c.seed;
  const double y0 = 2.5 * c.spacing + c.lateral;  // corridor 2: between rows 2 and 3
  const core::Pose2 start(3.0, y0, c.yaw);
  sim::Simulator simulator(field, sim::RobotConfig{}, sc, start);
  sim::Lidar lidar(sc.lidar, c.seed);
  detect::DetectionPipeline pipeline =
      io::make_pipeline("hough_skew", kDetect, sc.lidar.T_base_lidar());
  auto tracker = io::make_tracker(tracker_name, "");
  double spacing = 0.0;
  for (int i = 0; i < 12; ++i) {
    const core::Pose2 T(start.x + 0.4 * i * std::cos(c.yaw), y0 + 0.4 * i * std::sin(c.yaw), c.yaw);
    const Eigen::Isometry3d T3 = simulator.pose3d(T);
    const core::PointCloud cloud = lidar.sweep(
        simulator.world(), [&](double) { return T3; }, 0.1 * i);
    core::RowObservation obs = pipeline.process(cloud);
    obs.stamp = 0.1 * (i + 1);
    const track::RowTracking t = tracker->update(obs, T);
    if (t.row_spacing > 0.0) spacing = t.row_spacing;
  }
  return spacing;
}

/// Runs `n` random cases of `shape` through every tracker; the error must stay within
/// `tol_spacing` x the spacing + `tol_half_width` x the canopy half width on each.
void check_random_fields(sim::CanopyShape shape, int n, double tol_spacing, double tol_half_width,
                         std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (int k = 0; k < n; ++k) {
    const Case c = random_case(rng, shape);
    for (const std::string t : {"model_matching", "line_ekf", "model_filter", "none"}) {
      const double s = tracked_spacing(c, t);
      EXPECT_NEAR(s, c.spacing, tol_spacing * c.spacing + tol_half_width * c.half_width)
          << t << ": spacing " << c.spacing << " m, half width " << c.half_width << " m, lateral "
          << c.lateral << " m, yaw " << c.yaw / kDeg << " deg, seed " << c.seed;
    }
  }
}

TEST(RowSpacing, CentreToCentreOnSolidHedges) {
  // Before issue 10 the trackers reported the face-to-face width: 2 x half width short
  // (0.4-0.9 m on 1.5-3 m spacings). The crown of an opaque mound is seen only from its near
  // side, so part of the bias remains (BENCHMARK.md, issue 10): within one half width + 3 %.
  check_random_fields(sim::CanopyShape::solid_hedge, 6, 0.03, 1.0, 10);
}

TEST(RowSpacing, CentreToCentreOnThinCanopies) {
  check_random_fields(sim::CanopyShape::clumps, 4, 0.08, 0.0, 20);
}

TEST(RowSpacing, RobustToAMissingRow) {
  // Centres of rows at -1.5 s, -0.5 s, 0.5 s, 2.5 s (the row at 1.5 s missing), shuffled.
  for (const double s : {1.5, 1.8, 2.4, 3.0}) {
    EXPECT_NEAR(track::robust_spacing({2.5 * s, -0.5 * s, 0.5 * s, -1.5 * s}), s, 1e-9);
    EXPECT_NEAR(track::robust_spacing({-0.5 * s, 1.5 * s}), 2.0 * s, 1e-9);  // alone: as seen
    EXPECT_NEAR(track::robust_spacing({-0.5 * s, 0.5 * s, 2.5 * s}), s, 1e-9);
  }
  EXPECT_EQ(track::robust_spacing({1.0}), 0.0);
}

core::RowObservation rows_at(double stamp, std::initializer_list<double> offsets) {
  core::RowObservation obs;
  obs.stamp = stamp;
  obs.status = core::DetectionStatus::ok;
  obs.confidence = 1.0;
  for (const double y : offsets) {
    core::RowLine r;
    r.line = core::Line2({0.0, y}, {1.0, 0.0});
    r.offset = y, r.x_min = -1.0, r.x_max = 6.0, r.support = 50;
    if (y < 0.0) obs.right = static_cast<int>(obs.rows.size());
    if (y > 0.0 && obs.left < 0) obs.left = static_cast<int>(obs.rows.size());
    obs.rows.push_back(r);
  }
  return obs;
}

/// A tracker fed straight rows (rows_at) at 10 Hz while the robot drives 0.7 m/s along x.
struct StraightDrive {
  explicit StraightDrive(const std::string& tracker) : tracker(io::make_tracker(tracker, "")) {}
  void step(std::initializer_list<double> rows) {
    ++k;
    t = tracker->update(rows_at(0.1 * k, rows), core::Pose2(0.07 * k, 0.0, 0.0));
  }
  std::unique_ptr<track::RowTracker> tracker;
  track::RowTracking t;
  int k = 0;
};

TEST(RowSpacing, AFrameThatSeesPastAGapInAFollowedRowLeavesTheSpacingAlone) {
  // zoo:1:31 (2.35 m rows, a 17 m gap in the left row of the first corridor): for 24 s the
  // frames saw the right row and the row beyond the gap, one spacing further. Taken as one
  // spacing, the spacing doubled to 4.5 m after half the median's window, the model filter's
  // initialisation window (0.9 x spacing) took the row beyond the gap as the followed left row,
  // and the robot turned into the gap (perception_lost). Every tracker; 1.6 m rows (zoo:1:5: the
  // row beyond, 2.4 m away, inside the model filter's 3 m initialisation window, is taken as a
  // model and must be let go for the near row when the gap ends), 2.35 m and 3.5 m rows; the gap
  // long enough to fill the median's window four times.
  // With a third row seen (the right corridor's far row) and without it: a frame of two rows
  // cannot tell one spacing from two by itself.
  for (const bool third : {true, false})
    for (const double s : {1.6, 2.35, 3.5})
      for (const std::string name : {"model_filter", "model_matching", "line_ekf"}) {
        StraightDrive d(name);
        const track::RowTracking& t = d.t;
        for (int i = 0; i < 60; ++i) d.step({-1.5 * s, -0.5 * s, 0.5 * s});
        ASSERT_NEAR(t.row_spacing, s, 0.02 * s) << name;
        for (int i = 0; i < 200; ++i) {
          if (third)
            d.step({-1.5 * s, -0.5 * s, 1.5 * s});
          else
            d.step({-0.5 * s, 1.5 * s});
        }
        EXPECT_NEAR(t.row_spacing, s, 0.05 * s) << name << ", " << s << " m rows, third " << third;
        if (t.left >= 0) {
          EXPECT_LT(t.rows[static_cast<std::size_t>(t.left)].offset, s) << name << ", " << s;
        }
        // The gap ends: the near row is followed again.
        for (int i = 0; i < 30; ++i) d.step({-1.5 * s, -0.5 * s, 0.5 * s, 1.5 * s});
        ASSERT_GE(t.left, 0) << name << ", " << s << " m rows, third " << third;
        EXPECT_NEAR(t.rows[static_cast<std::size_t>(t.left)].offset, 0.5 * s, 0.05 * s) << name;
      }
}

TEST(RowSpacing, ThePairsSeenWhileTurningAreNoCorridorToMeasureAGapAgainst) {
  // demo_vineyard: while turning the trackers followed pairs 0.35-0.6 m apart; the corridor
  // entered after the turn (1.8 m) must not read as a gap against them (only a width held for
  // settle_frames frames is a reference).
  for (const std::string name : {"model_filter", "model_matching", "line_ekf"}) {
    StraightDrive d(name);
    const track::RowTracking& t = d.t;
    for (int i = 0; i < 30; ++i) d.step({-0.2 - 0.05 * (i % 3), 0.15 + 0.05 * (i % 2)});
    d.tracker->reset();  // NavStack resets the tracker when a turn starts, not when it ends
    for (int i = 0; i < 30; ++i) d.step({-0.2 - 0.05 * (i % 3), 0.15 + 0.05 * (i % 2)});
    for (int i = 0; i < 80; ++i) d.step({-0.9, 0.9});
    EXPECT_GE(t.left, 0) << name;
    EXPECT_GE(t.right, 0) << name;
    EXPECT_NEAR(t.corridor_width, 1.8, 0.05) << name;
  }
}

TEST(RowSpacing, ModelMatchingSkipsAMissingRow) {
  // Four rows seen, the third missing: centres -2.7, -0.9, 0.9, 4.5 (spacing 1.8).
  auto tracker = io::make_tracker("model_matching", "");
  track::RowTracking t;
  for (int i = 0; i < 5; ++i) {
    core::RowObservation obs;
    obs.stamp = 0.1 * (i + 1);
    obs.status = core::DetectionStatus::ok;
    obs.confidence = 1.0;
    for (const double y : {-2.7, -0.9, 0.9, 4.5}) {
      core::RowLine r;
      r.line = core::Line2({0.0, y}, {1.0, 0.0});
      r.offset = y, r.x_min = -1.0, r.x_max = 6.0, r.support = 50;
      obs.rows.push_back(r);
    }
    obs.right = 1, obs.left = 2;
    t = tracker->update(obs, core::Pose2(0.1 * i, 0.0, 0.0));
  }
  EXPECT_NEAR(t.row_spacing, 1.8, 1e-6);
}

}  // namespace
}  // namespace rownav::test
