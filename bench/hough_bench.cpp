/// @file hough_bench.cpp Per-frame cost of the hough_skew and parallel_lines row detectors, and of
/// PCL's SACSegmentation (SACMODEL_PARALLEL_LINE, two lines: fit, remove inliers, fit again) on
/// the same points. Frame: an OS1-64 sweep from the simulator in a 20-row x 100 m high-canopy
/// vineyard, robot in corridor 9, preprocessed by preprocess::Preprocessor (voxel 0.15 m).
/// "Detector" benchmarks time detect() only; "Full" ones time preprocessing + detect().
///   ./build/hough_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <pcl/ModelCoefficients.h>
#include <pcl/filters/extract_indices.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>
#include <numbers>

#include "rownav/detect/hough_skew.hpp"
#include "rownav/detect/parallel_lines.hpp"
#include "rownav/preprocess/preprocessor.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/vineyard.hpp"

namespace {

using namespace rownav;

/// The simulated OS1-64 frame in the base frame, built once.
const core::PointCloud& frame() {
  static const core::PointCloud cloud = [] {
    sim::FieldConfig fc;
    fc.vineyard.rows = 20;
    fc.vineyard.row_length = 100.0;
    fc.vineyard.stage = sim::GrowthStage::high;
    const sim::Field field = sim::generate_field(fc);
    const sim::FieldTruth ft(field);
    const auto& c = ft.corridor_centre(0, 9);
    const std::size_t mid = c.size() / 2;
    const Eigen::Vector2d t = (c[mid + 1] - c[mid]).normalized();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(c[mid].x(), c[mid].y(), 0.0);
    T.linear() = Eigen::AngleAxisd(std::atan2(t.y(), t.x()) + 3.0 * std::numbers::pi / 180.0,
                                   Eigen::Vector3d::UnitZ()).toRotationMatrix();
    sim::LidarConfig lc = sim::lidar_preset("os1_64");
    lc.motion_during_sweep = false;
    sim::Lidar lidar(lc, 1);
    const sim::RayCaster caster(field.mesh);
    core::PointCloud out = lidar.sweep(caster, [&](double) { return T; }, 0.0);
    const Eigen::Isometry3f B = lc.T_base_lidar().cast<float>();
    for (auto& p : out.points) {
      const Eigen::Vector3f b = B * Eigen::Vector3f(p.x, p.y, p.z);
      p.x = b.x(), p.y = b.y(), p.z = b.z();
    }
    return out;
  }();
  return cloud;
}

preprocess::PreprocessConfig preprocess_config() {
  preprocess::PreprocessConfig pc;
  pc.voxel.voxel_size = 0.15;  // Nehme 2021 sec. 4
  return pc;
}

template <class Detector>
void detector_only(benchmark::State& state) {
  preprocess::Preprocessor pre(preprocess_config());
  pre.run(frame());
  const detect::DetectorInput in = pre.input(0.0);
  Detector det;
  int rows = 0;
  for (auto _ : state) {
    const auto obs = det.detect(in);
    rows = static_cast<int>(obs.rows.size());
    benchmark::DoNotOptimize(obs.heading);
  }
  state.counters["points"] = double(in.points.size());
  state.counters["rows"] = rows;
}

template <class Detector>
void full(benchmark::State& state) {
  preprocess::Preprocessor pre(preprocess_config());
  Detector det;
  for (auto _ : state) {
    pre.run(frame());
    const auto obs = det.detect(pre.input(0.0));
    benchmark::DoNotOptimize(obs.heading);
  }
  state.counters["cloud"] = double(frame().size());
}

/// PCL: two parallel lines (axis x +- 20 deg), the second after removing the first's inliers.
void pcl_two_lines(benchmark::State& state, pcl::SacModel model) {
  preprocess::Preprocessor pre(preprocess_config());
  pre.run(frame());
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : pre.input(0.0).points) cloud->push_back({p.x(), p.y(), 0.0f});
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  seg.setModelType(model);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(0.2);
  seg.setMaxIterations(500);
  seg.setOptimizeCoefficients(true);
  seg.setAxis(Eigen::Vector3f::UnitX());
  seg.setEpsAngle(20.0 * std::numbers::pi / 180.0);
  pcl::ExtractIndices<pcl::PointXYZ> extract;
  pcl::PointCloud<pcl::PointXYZ>::Ptr rest(new pcl::PointCloud<pcl::PointXYZ>);
  for (auto _ : state) {
    pcl::PointIndices::Ptr inliers(new pcl::PointIndices);
    pcl::ModelCoefficients coeffs;
    seg.setInputCloud(cloud);
    seg.segment(*inliers, coeffs);
    extract.setInputCloud(cloud);
    extract.setIndices(inliers);
    extract.setNegative(true);
    extract.filter(*rest);
    seg.setInputCloud(rest);
    seg.segment(*inliers, coeffs);
    benchmark::DoNotOptimize(coeffs.values.data());
  }
  state.counters["points"] = double(cloud->size());
}

void BM_Preprocess(benchmark::State& state) {
  preprocess::Preprocessor pre(preprocess_config());
  for (auto _ : state) benchmark::DoNotOptimize(pre.run(frame()).points.data());
  state.counters["cloud"] = double(frame().size());
}
void BM_HoughSkewDetector(benchmark::State& s) { detector_only<detect::HoughSkewDetector>(s); }
void BM_ParallelLinesDetector(benchmark::State& s) {
  detector_only<detect::ParallelLinesDetector>(s);
}
void BM_HoughSkewFull(benchmark::State& s) { full<detect::HoughSkewDetector>(s); }
void BM_ParallelLinesFull(benchmark::State& s) { full<detect::ParallelLinesDetector>(s); }
void BM_PclSacParallelLineTwo(benchmark::State& s) {
  pcl_two_lines(s, pcl::SACMODEL_PARALLEL_LINE);
}
void BM_PclSacLineTwo(benchmark::State& s) { pcl_two_lines(s, pcl::SACMODEL_LINE); }

}  // namespace

BENCHMARK(BM_Preprocess)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HoughSkewDetector)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ParallelLinesDetector)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HoughSkewFull)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ParallelLinesFull)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PclSacParallelLineTwo)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PclSacLineTwo)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
