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
