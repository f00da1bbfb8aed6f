/// @file camera_bench.cpp Speed of the camera labelling chain (issue 12, Emmi 2021 Fig. 2b):
/// rendering the simulated pinhole camera, the excess-green detector, and labelling an OS1-64
/// sweep by the boxes, in the two-cabbage-field scene of the vision tests (tests/vision/
/// field_scene.hpp: 2 x 5 rows x 30 m, ~1,300 plants, weeds). One core.
///   ./build/camera_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/vision/camera_labeller.hpp"
#include "rownav/vision/excess_green_detector.hpp"
#include "vision/field_scene.hpp"

namespace {

using namespace rownav;

const vision::test::FieldScene& scene() {
  static const auto s = vision::test::make_field_scene(1);
  return s;
}

/// Renders one image; arguments: width, height, shadows (0 / 1).
void BM_CameraRender(benchmark::State& st) {
  const auto& s = scene();
  auto c = s.camera();
  c.width = static_cast<int>(st.range(0));
  c.height = static_cast<int>(st.range(1));
  c.shadows = st.range(2) != 0;
  sim::PinholeCamera cam(c, 1);
  const Eigen::Isometry3d T = s.pose(3, 10.0, 0.3);
  for (auto _ : st) benchmark::DoNotOptimize(cam.render(*s.world, T, 0.0).rgb.data());
  st.counters["Mpix/s"] = benchmark::Counter(double(c.width) * c.height * st.iterations() / 1e6,
                                             benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CameraRender)
    ->Args({320, 240, 0})
    ->Args({320, 240, 1})
    ->Args({752, 480, 1})
    ->Unit(benchmark::kMillisecond);

/// Excess-green detection of one 320 x 240 image.
void BM_ExcessGreenDetect(benchmark::State& st) {
  const auto& s = scene();
  sim::PinholeCamera cam(s.camera(), 1);
  const auto img = cam.render(*s.world, s.pose(3, 10.0, 0.3), 0.0);
  vision::ExcessGreenDetector det;
  std::vector<vision::Detection> out;
  for (auto _ : st) {
    det.detect(img, out);
    benchmark::DoNotOptimize(out.data());
  }
  st.counters["boxes"] = static_cast<double>(out.size());
}
BENCHMARK(BM_ExcessGreenDetect)->Unit(benchmark::kMillisecond);

/// Labelling one OS1-64 sweep (base frame) by the boxes of one image.
void BM_CameraLabel(benchmark::State& st) {
  const auto& s = scene();
  const Eigen::Isometry3d T = s.pose(3, 10.0, 0.3);
  sim::PinholeCamera cam(s.camera(), 1);
  const auto img = cam.render(*s.world, T, 0.0);
  vision::ExcessGreenDetector det;
  vision::CameraLabeller labeller;
  labeller.set_image(img, det);
  sim::LidarConfig lc = sim::lidar_preset("os1_64");
  sim::Lidar lidar(lc, 1);
  const auto cloud = lidar.sweep(*s.world, [&](double) { return T; }, 0.0);
  std::vector<Eigen::Vector3f> pts;
  const Eigen::Isometry3f T_base_lidar = lc.T_base_lidar().cast<float>();
  for (const auto& p : cloud.points) pts.push_back(T_base_lidar * Eigen::Vector3f(p.x, p.y, p.z));
  std::vector<map::PointLabel> labels;
  for (auto _ : st) {
    labeller.label(pts, labels);
    benchmark::DoNotOptimize(labels.data());
  }
  st.counters["points"] = static_cast<double>(pts.size());
  st.counters["boxes"] = static_cast<double>(labeller.detections().size());
}
BENCHMARK(BM_CameraLabel)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
