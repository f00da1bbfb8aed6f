// A closed-loop run and the replay of its own recording give the same commands, call by call
// (issue 14: the stack that is measured is the stack a recording drives).
#include <gtest/gtest.h>

#include "common/cli_runner.hpp"
#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/recording_replay.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar_presets.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

sim::FieldConfig small_vineyard() {
  sim::FieldConfig f;
  f.kind = sim::FieldKind::vineyard;
  f.vineyard.rows = 4;
  f.vineyard.row_length = 15.0;
  f.vineyard.row_spacing = 1.8;
  f.seed = 3;
  return f;
}

/// Runs `setup` recording its inputs into `dir`, replays them into a fresh stack built the same
/// way and expects every command to be the same bit for bit.
void expect_replay_equal(ClosedLoopSetup setup, const fs::path& dir) {
  setup.record_inputs = dir;
  const RunResult run = run_closed_loop(setup);
  const Recording rec = read_recording(dir);
  const auto stack = make_nav_stack(setup, run.order);
  const auto cmds = replay_input_log(rec, *stack);
  ASSERT_GT(cmds.size(), 100u);
  std::size_t moving = 0;
  for (const auto& c : cmds) {
    ASSERT_EQ(c.live.v, c.replayed.v) << c.stamp;
    ASSERT_EQ(c.live.omega, c.replayed.omega) << c.stamp;
    ASSERT_EQ(c.live_state, c.replayed_state) << c.stamp;
    moving += c.live.v != 0.0;
  }
  EXPECT_GT(moving, cmds.size() / 2);  // the run drove: the comparison is not of zeros
}

ClosedLoopSetup setup_for(const sim::Field& field) {
  ClosedLoopSetup s;
  s.field = &field;
  s.mission.corridors = {0, 1};
  s.detect_config = std::string(ROWNAV_SOURCE_DIR) + "/config/detect/vineyard.yaml";
  s.make_tracker = [] { return make_tracker("model_filter", ""); };
  s.make_controller = [] { return make_controller("stanley", ""); };
  return s;
}

TEST(InputReplay, AThreeDLidarRunAndTheReplayOfItsRecordingGiveTheSameCommands) {
  const sim::Field field = build_field(small_vineyard(), ".");
  ClosedLoopSetup s = setup_for(field);
  s.time_limit = 8.0;  // OS1-16 sweeps are large: 80 of them, levelled by the IMU
  test::TempDir t("replay3d");
  expect_replay_equal(s, t / "rec");
}

TEST(InputReplay, ATwoDScannerMissionAndTheReplayOfItsRecordingGiveTheSameCommands) {
  const sim::Field field = build_field(small_vineyard(), ".");
  ClosedLoopSetup s = setup_for(field);
  s.sensors.lidar = sim::lidar_preset("lms_1081");
  s.detector = "parallel_lines";
  s.time_limit = 60.0;  // through the headland turn
  test::TempDir t("replay2d");
  expect_replay_equal(s, t / "rec");
}

}  // namespace
}  // namespace rownav::io
