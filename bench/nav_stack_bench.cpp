/// @file nav_stack_bench.cpp Per-frame cost of navigate::NavStack (the whole chain: levelling,
/// preprocessing, hough_skew, model_filter, end of row, navigator, stanley, limits) on a
/// simulated OS1-16 and OS1-64 sweep in a 20-row x 100 m high-canopy vineyard, beside a
/// reference pass that only reads every point of the same sweep once (the memory limit).
/// Issue 14 target: an OS1-64 frame <= 5x that reference, one core. Per-frame p50 / p99 are
/// counters (one frame per iteration).
///   ./build/nav_stack_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "bench_vineyard.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/navigate/nav_stack.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace {

namespace sim = rownav::sim;
namespace nav = rownav::navigate;
using rownav::core::PointCloud;

struct Sweep {
  PointCloud cloud;  // LiDAR frame, per-point times
  Eigen::Isometry3d T_base_lidar;
};

const Sweep& sweep(const std::string& preset) {
  static std::map<std::string, Sweep> cache;
  if (auto it = cache.find(preset); it != cache.end()) return it->second;
  const auto& v = rownav::bench::bench_vineyard();
  const sim::RayCaster& caster = *v.caster;
  const sim::PoseAt& pose = v.pose;
  const auto lidar = sim::lidar_preset(preset);
  Sweep s{sim::Lidar(lidar, 1).sweep(caster, pose, 0.0), lidar.T_base_lidar()};
  return cache.emplace(preset, std::move(s)).first->second;
}

nav::NavStack make_stack(const Sweep& s, bool check_view) {
  nav::NavStackConfig config;
  config.end_of_row.check_view = check_view;  // issue 10's view check, on by default
  nav::NavStackParts parts;
  parts.pipeline = std::make_unique<rownav::detect::DetectionPipeline>(rownav::io::make_pipeline(
      "hough_skew", std::string(ROWNAV_SOURCE_DIR) + "/config/detect/vineyard.yaml",
      s.T_base_lidar));
  parts.tracker = rownav::io::make_tracker("model_filter", "");
  parts.controller = rownav::io::make_controller("stanley", "");
  return nav::NavStack(config, std::move(parts));
}

/// One frame per iteration: the encoders and IMU of 0.1 s, the sweep, the command.
void BM_NavStackFrame(benchmark::State& state, const std::string& preset, bool check_view) {
  const Sweep& s = sweep(preset);
  nav::NavStack stack = make_stack(s, check_view);
  std::vector<double> ms;
  double t = 0.0;
  std::size_t frames_ok = 0;
  for (auto _ : state) {
    state.PauseTiming();
    PointCloud c = s.cloud;  // the adapter's conversion is not the stack's cost
    t += 0.1;
    c.stamp = t;
    state.ResumeTiming();
    const auto t0 = std::chrono::steady_clock::now();
    stack.on_encoders({t, 0, 0, 0.0});
    for (int k = 0; k < 10; ++k) {
      rownav::core::ImuSample imu;
      imu.stamp = t + 0.01 * k;
      imu.linear_acceleration = {0.0, 0.0, 9.81};
      stack.on_imu(imu);
    }
    stack.on_cloud(std::move(c));
    const auto out = stack.command(t + 0.1);
    benchmark::DoNotOptimize(out.cmd);
    frames_ok += out.frame && out.frame->observation.status == rownav::core::DetectionStatus::ok;
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  state.counters["p50_ms"] = ms[ms.size() / 2];
  state.counters["p99_ms"] = ms[std::min(ms.size() - 1, ms.size() * 99 / 100)];
  state.counters["points"] = double(s.cloud.size());
  state.counters["ok_frames"] = double(frames_ok) / double(ms.size());
}

/// The memory limit: every point of the sweep read once.
void BM_ReadEveryPoint(benchmark::State& state, const std::string& preset) {
  const Sweep& s = sweep(preset);
  for (auto _ : state) {
    float sum = 0.0f;
    for (const auto& p : s.cloud.points) sum += p.x + p.y + p.z + p.intensity;
    benchmark::DoNotOptimize(sum);
  }
  state.counters["points"] = double(s.cloud.size());
}

BENCHMARK_CAPTURE(BM_NavStackFrame, os1_16, std::string("os1_16"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_NavStackFrame, os1_64, std::string("os1_64"), true)
    ->Unit(benchmark::kMillisecond);
// The same without the end of row's view check: its per-frame cost (issue 14).
BENCHMARK_CAPTURE(BM_NavStackFrame, os1_64_no_view_check, std::string("os1_64"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadEveryPoint, os1_16, std::string("os1_16"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ReadEveryPoint, os1_64, std::string("os1_64"))->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
