// Whole-simulation speed: issue 2 asks that a 120 s drive with an OS1-16 at 10 Hz be simulated in
// at most 12 s of wall time on one core, in the benchmark vineyard (20 rows x 100 m, high canopy).
#include <benchmark/benchmark.h>

#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/scripted_path.hpp"
#include "rownav/sim/simulator.hpp"

namespace {

using namespace rownav;

const sim::Field& bench_field() {
  static const sim::Field field = [] {
    sim::FieldConfig f;
    f.vineyard.rows = 20;
    f.vineyard.row_length = 100.0;
    f.vineyard.row_spacing = 2.0;
    f.vineyard.stage = sim::GrowthStage::high;
    f.vineyard.weeds = sim::WeedLevel::some;
    return sim::generate_field(f);
  }();
  return field;
}

// Counts frames so the optimiser cannot drop the sweeps.
struct CountingSink : sim::SimSink {
  std::size_t points = 0;
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>&) override {
    points += c.size();
  }
};

void BM_Drive120sOs1_16(benchmark::State& state) {
  const sim::Field& field = bench_field();
  const sim::FieldTruth truth(field);
  sim::PathConfig path_config;
  path_config.corridors = {9};
  path_config.speed = 0.8;  // 120 s of driving along a 100 m corridor
  const sim::RobotConfig robot;
  const auto path = sim::build_path(truth, path_config, robot);
  for (auto _ : state) {
    sim::SimConfig sensors;
    sensors.lidar = sim::lidar_preset("os1_16");
    const Eigen::Vector2d d = path[1].p - path[0].p;
    sim::Simulator simulator(field, robot, sensors,
                             {path[0].p.x(), path[0].p.y(), std::atan2(d.y(), d.x())});
    sim::PathFollower driver(path);
    CountingSink sink;
    while (simulator.time() < 120.0 && !driver.done())
      simulator.step(driver.command(simulator.robot_state().pose), sink);
    state.counters["sim_s"] = simulator.time();
    state.counters["points_per_sweep"] = static_cast<double>(sink.points) / (simulator.time() * 10);
  }
}
BENCHMARK(BM_Drive120sOs1_16)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// One sweep / scan in the generated benchmark vineyard (the lidar bench uses its own scene).
void sweep_in_bench_field(benchmark::State& state, const char* preset) {
  const sim::Field& field = bench_field();
  const sim::FieldTruth truth(field);
  const auto& c = truth.corridor_centre(0, 9);
  const Eigen::Vector2d p = c[c.size() / 2], d = c[c.size() / 2 + 1] - p;
  sim::SimConfig sensors;
  sensors.lidar = sim::lidar_preset(preset);
  const sim::Simulator simulator(field, sim::RobotConfig{}, sensors,
                                 {p.x(), p.y(), std::atan2(d.y(), d.x())});
  const Eigen::Isometry3d T = simulator.pose3d({p.x(), p.y(), std::atan2(d.y(), d.x())});
  const sim::PoseAt pose = [&](double) { return T; };
  sim::Lidar lidar(sensors.lidar, 1);
  std::size_t n = 0;
  for (auto _ : state) {
    if (sensors.lidar.kind == sim::LidarKind::spinning) {
      n = lidar.sweep(simulator.world(), pose, 0.0).size();
    } else {
      n = lidar.scan(simulator.world(), pose, 0.0).to_points().size();
    }
    benchmark::DoNotOptimize(n);
  }
  state.counters["points"] = static_cast<double>(n);
  state.counters["triangles"] = static_cast<double>(field.mesh.triangle_count());
}
void BM_GeneratedFieldOs1_64(benchmark::State& s) { sweep_in_bench_field(s, "os1_64"); }
void BM_GeneratedFieldOs1_16(benchmark::State& s) { sweep_in_bench_field(s, "os1_16"); }
void BM_GeneratedFieldLms1081(benchmark::State& s) { sweep_in_bench_field(s, "lms_1081"); }
BENCHMARK(BM_GeneratedFieldOs1_64)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GeneratedFieldOs1_16)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GeneratedFieldLms1081)->Unit(benchmark::kMicrosecond);

void BM_BuildBenchField(benchmark::State& state) {
  for (auto _ : state) {
    sim::FieldConfig f;
    f.vineyard.rows = 20;
    f.vineyard.row_length = 100.0;
    f.vineyard.stage = sim::GrowthStage::high;
    const sim::Field field = sim::generate_field(f);
    state.counters["triangles"] = static_cast<double>(field.mesh.triangle_count());
  }
}
BENCHMARK(BM_BuildBenchField)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
