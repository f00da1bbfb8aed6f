// A 2D scanner on rough, sloped ground that rownav's own fields do not have: zoo:7:5 (a random
// narrow vineyard, 1.77 m rows, slopes -6.0 / 0.8 deg, ground roughness 0.03 m at 2 m), the LMS1xx
// 0.40 m above it on the differential robot, started 0.15 m off-centre and yawed 8 deg, closed
// loop through two corridors (issue 11). The ground pitches the scan plane into itself 2-3 m
// ahead, across the lane: read as an empty end-of-row box this declared the row end at the first
// bump, 1.5 m into the row, for both detectors. The test asserts the mission as a user would
// judge it. Of the 16 runs of BENCHMARK.md's 2D zoo set (8 zoo:7 vineyards x pearl,
// parallel_lines) 5 succeed; the others fail and are listed there, not here (zoo:7:0, 6, 10, 11,
// 15 both; zoo:7:1 parallel_lines): tracker loss on the roughest ground, weeds taller than the
// scanner, and a headland turn planned with the face-to-face corridor width as the spacing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "rownav/core/angle.hpp"
#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/mission_io.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_zoo.hpp"

namespace rownav::io {
namespace {

const std::filesystem::path kConfig = std::filesystem::path(ROWNAV_SOURCE_DIR) / "config";

RunSummary run_rough_2d(const std::string& detector) {
  const sim::FieldConfig fc = sim::zoo_field(5, 7);
  const sim::Field field = build_field(fc, kConfig / "fields");
  ClosedLoopSetup s;
  s.field = &field;
  s.robot = load_config<sim::RobotConfig>(kConfig / "robots" / "differential.yaml");
  s.sensors = load_sim_config(kConfig / "sensors" / "lms_1081.yaml");
  s.sensors.seed = 3;
  s.mission = load_mission(kConfig / "missions" / "two_corridors.yaml");
  s.nav = load_config<navigate::NavStackConfig>(kConfig / "navigate" / "vineyard.yaml");
  s.detect_config = kConfig / "detect" / "vineyard.yaml";
  s.detector = detector;
  s.make_tracker = [] { return make_tracker("model_filter", ""); };
  s.make_controller = [] { return make_controller("lookahead_pid", ""); };
  s.time_limit = 600.0;
  s.start_offset = 0.15;
  s.start_yaw = core::deg2rad(8.0);
  return summarize(run_closed_loop(s), sim::FieldTruth(field), s.mission.block);
}

class RoughGround2D : public ::testing::TestWithParam<std::string> {};

TEST_P(RoughGround2D, ServesBothCorridorsWithoutEndingARowAtABump) {
  const RunSummary s = run_rough_2d(GetParam());
  EXPECT_TRUE(s.success) << s.stop_reason;
  EXPECT_EQ(s.corridors_served, s.corridors_planned);
  EXPECT_EQ(s.wrong_entries, 0);
  EXPECT_EQ(s.plants_crushed, 0);
  EXPECT_FALSE(s.collision);
}

INSTANTIATE_TEST_SUITE_P(Zoo7Field5, RoughGround2D,
                         ::testing::Values(std::string("pearl"), std::string("parallel_lines")),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace rownav::io
