// Per-frame cost of the row trackers (target <= 0.1 ms): a synthetic 4-row corridor observed
// with noise while the robot drives at 1 m/s, 10 Hz.
#include <benchmark/benchmark.h>

#include <numbers>
#include <random>

#include "rownav/io/tracker_registry.hpp"
#include "track/synthetic_corridor.hpp"

namespace {

void BM_Tracker(benchmark::State& state, const std::string& name) {
  auto tracker = rownav::io::make_tracker(name, {});
  rownav::test::CorridorScene scene;
  scene.noise_offset = 0.03, scene.noise_heading = 0.01;
  std::mt19937_64 rng(1);
  std::vector<rownav::core::RowObservation> frames;
  std::vector<rownav::core::Pose2> poses;
  for (int i = 0; i < 1000; ++i) {
    const double t = 0.1 * i;
    poses.emplace_back(t, 0.1 * std::sin(0.2 * t), 0.02 * std::cos(0.2 * t));
    frames.push_back(rownav::test::observe(scene, poses.back(), t, rng));
  }
  std::size_t i = 0;
  double offset = 0.0;  // stamps keep increasing across the cycles
  for (auto _ : state) {
    auto obs = frames[i];
    obs.stamp += offset;
    rownav::core::Pose2 T = poses[i];
    T.x += offset;
    benchmark::DoNotOptimize(tracker->update(obs, T));
    if (++i == frames.size()) i = 0, offset += 100.0;
  }
}

BENCHMARK_CAPTURE(BM_Tracker, model_matching, std::string("model_matching"));
BENCHMARK_CAPTURE(BM_Tracker, line_ekf, std::string("line_ekf"));
BENCHMARK_CAPTURE(BM_Tracker, model_filter, std::string("model_filter"));

}  // namespace

BENCHMARK_MAIN();
