/// @file preprocess_bench.cpp Preprocessing speed on a simulated OS1-64 frame (65,536 rays) in a
/// 20-row x 100 m high-canopy vineyard (sim::generate_field, robot mid-corridor 9), and rownav's
/// voxel grid / outlier filters side by side with PCL's on the same points. One core.
///   ./build/preprocess_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <pcl/filters/radius_outlier_removal.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "bench_vineyard.hpp"
#include "rownav/preprocess/preprocessor.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace {

namespace rp = rownav::preprocess;
namespace sim = rownav::sim;

struct Data {
  rownav::core::PointCloud frame;            // OS1-64, base frame
  std::vector<Eigen::Vector2f> scan_points;  // lms_1081 scan (1081 beams), base frame
};

const Data& data() {
  static const Data d = [] {
    const auto& v = rownav::bench::bench_vineyard();
    const sim::RayCaster& caster = *v.caster;
    const sim::PoseAt& pose = v.pose;
    Data out;
    const auto os1 = sim::lidar_preset("os1_64");
    out.frame = sim::Lidar(os1, 1).sweep(caster, pose, 0.0);
    const Eigen::Isometry3f T = os1.T_base_lidar().cast<float>();
    for (auto& p : out.frame.points) {
      const Eigen::Vector3f q = T * Eigen::Vector3f(p.x, p.y, p.z);
      p.x = q.x(), p.y = q.y(), p.z = q.z();
    }
    out.frame.frame_id = "base";
    const auto lms = sim::lidar_preset("lms_1081");
    const auto scan = sim::Lidar(lms, 1).scan(caster, pose, 0.0);
    const Eigen::Isometry3f Ts = lms.T_base_lidar().cast<float>();
    for (const auto& p : scan.to_points())
      out.scan_points.push_back((Ts * Eigen::Vector3f(p.x(), p.y(), 0.0f)).head<2>());
    return out;
  }();
  return d;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const rownav::core::PointCloud& c) {
  auto out = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  out->reserve(c.size());
  for (const auto& p : c.points) out->push_back({p.x, p.y, p.z});
  return out;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const std::vector<Eigen::Vector2f>& pts) {
  auto out = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (const auto& p : pts) out->push_back({p.x(), p.y(), 0.0f});
  return out;
}

void BM_Chain(benchmark::State& state) {
  const auto& d = data();  // simulated before the timing
  rp::Preprocessor pre{rp::PreprocessConfig{}};
  std::size_t kept = 0;
  for (auto _ : state) kept = pre.run(d.frame).cloud.size();
  state.counters["points_in"] = double(d.frame.size());
  state.counters["kept"] = double(kept);
}

// The default chain's steps one at a time on copies (0 crop, 1 ground estimate, 2 height band,
// 3 voxel grid of the band), to see where BM_Chain spends its time.
void BM_ChainStep(benchmark::State& state) {
  const auto& d = data();
  const rp::PreprocessConfig c;
  const rp::CropBox box(c.crop);
  rp::GroundEstimator ground(c.ground);
  rp::VoxelGrid grid(c.voxel);
  std::vector<rownav::core::PointXYZIRT> cropped, band, out;
  const auto crop = [&] {
    cropped.clear();
    for (const auto& p : d.frame.points)
      if (p.finite() && box.contains(p.x, p.y, p.z)) cropped.push_back(p);
  };
  crop();
  ground.estimate(cropped);
  rp::height_band(cropped, ground, c.height, band);
  for (auto _ : state) {
    switch (state.range(0)) {
      case 0: crop(); break;
      case 1: benchmark::DoNotOptimize(ground.estimate(cropped)); break;
      case 2: rp::height_band(cropped, ground, c.height, band); break;
      default: grid.filter(band, out);
    }
    benchmark::ClobberMemory();
  }
  state.counters["cropped"] = double(cropped.size());
  state.counters["band"] = double(band.size());
}

void BM_ChainScan(benchmark::State& state) {
  const auto& d = data();
  rp::PreprocessConfig c;
  c.use_scan = true;
  rp::Preprocessor pre(c);
  std::size_t kept = 0;
  for (auto _ : state) kept = pre.run(d.frame).points.size();
  state.counters["kept"] = double(kept);
}

void BM_VoxelGridRownav(benchmark::State& state) {
  const auto& d = data();
  rp::VoxelGrid grid(rp::VoxelGridConfig{0.15, 1});
  std::vector<rownav::core::PointXYZIRT> out;
  for (auto _ : state) {
    grid.filter(d.frame.points, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["voxels"] = double(out.size());
}

void BM_VoxelGridPcl(benchmark::State& state) {
  const auto cloud = to_pcl(data().frame);
  pcl::VoxelGrid<pcl::PointXYZ> vg;
  vg.setLeafSize(0.15f, 0.15f, 0.15f);
  vg.setInputCloud(cloud);
  pcl::PointCloud<pcl::PointXYZ> out;
  for (auto _ : state) vg.filter(out);
  state.counters["voxels"] = double(out.size());
}

void BM_VoxelGridPclWithConversion(benchmark::State& state) {
  const auto& d = data();
  pcl::VoxelGrid<pcl::PointXYZ> vg;
  vg.setLeafSize(0.15f, 0.15f, 0.15f);
  pcl::PointCloud<pcl::PointXYZ> out;
  for (auto _ : state) {
    vg.setInputCloud(to_pcl(d.frame));
    vg.filter(out);
  }
  state.counters["voxels"] = double(out.size());
}

void BM_RadiusOutlierRownav(benchmark::State& state) {
  const auto& pts = data().scan_points;
  rp::RadiusOutlier f(rp::RadiusOutlierConfig{true, 0.3, 2});
  std::vector<Eigen::Vector2f> out;
  for (auto _ : state) f.filter(pts, out);
  state.counters["points_in"] = double(pts.size());
  state.counters["kept"] = double(out.size());
}

void BM_RadiusOutlierPcl(benchmark::State& state) {
  const auto cloud = to_pcl(data().scan_points);
  pcl::RadiusOutlierRemoval<pcl::PointXYZ> f;
  f.setRadiusSearch(0.3);
  f.setMinNeighborsInRadius(2);
  f.setInputCloud(cloud);
  pcl::PointCloud<pcl::PointXYZ> out;
  for (auto _ : state) f.filter(out);
  state.counters["kept"] = double(out.size());
}

void BM_StatisticalOutlierRownav(benchmark::State& state) {
  const auto& pts = data().scan_points;
  rp::StatisticalOutlier f(rp::StatisticalOutlierConfig{true, 8, 1.0});
  std::vector<Eigen::Vector2f> out;
  for (auto _ : state) f.filter(pts, out);
  state.counters["points_in"] = double(pts.size());
  state.counters["kept"] = double(out.size());
}

void BM_StatisticalOutlierPcl(benchmark::State& state) {
  const auto cloud = to_pcl(data().scan_points);
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> f;
  f.setMeanK(8);
  f.setStddevMulThresh(1.0);
  f.setInputCloud(cloud);
  pcl::PointCloud<pcl::PointXYZ> out;
  for (auto _ : state) f.filter(out);
  state.counters["kept"] = double(out.size());
}

}  // namespace

BENCHMARK(BM_Chain)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ChainStep)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ChainScan)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VoxelGridRownav)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VoxelGridPcl)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VoxelGridPclWithConversion)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RadiusOutlierRownav)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RadiusOutlierPcl)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StatisticalOutlierRownav)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StatisticalOutlierPcl)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
