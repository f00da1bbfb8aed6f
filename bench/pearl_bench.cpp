/// @file pearl_bench.cpp Per-frame cost of RUBY / OPAL / PEARL and sequential RANSAC on one
/// 1081-beam lms_1081 scan (mount 0.4 m) simulated in a vineyard (6 rows x 24 m, 2.2 m apart),
/// robot in corridor 2, points cropped to x in [0, 8] m, |y| <= 4 m; side by side with PCL's
/// SACSegmentation (SACMODEL_LINE, sequential extraction with the same iterations, distance and
/// min inliers as ransac_lines) on the same points; and both detectors over real corn_rows_2d
/// frames (with the rows found, so that two builds can be compared). One core.
///   ./build/pearl_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <pcl/ModelCoefficients.h>
#include <pcl/filters/extract_indices.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>

#include "rownav/detect/pearl.hpp"
#include "rownav/detect/ransac_lines.hpp"
#include "rownav/io/cloud_io.hpp"
#include "rownav/preprocess/preprocessor.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace {

using namespace rownav;

/// The cropped 2D points of one simulated scan (built once).
const std::vector<Eigen::Vector2f>& frame_points() {
  static const std::vector<Eigen::Vector2f> pts = [] {
    sim::FieldConfig fc;
    fc.kind = sim::FieldKind::vineyard;
    fc.vineyard.rows = 6;
    fc.vineyard.row_length = 24.0;
    fc.vineyard.row_spacing = 2.2;
    fc.vineyard.headland_width = 5.0;
    fc.seed = 3;
    const sim::Field field = sim::generate_field(fc);
    const sim::FieldTruth truth(field);
    const sim::RayCaster world(field.mesh);
    sim::LidarConfig lc = sim::lidar_preset("lms_1081");
    lc.mount_xyz = {0.3, 0.0, 0.4};
    sim::Lidar lidar(lc, 1);
    const auto& c = truth.corridor_centre(0, 2);
    const Eigen::Vector2d a = c[c.size() / 3], b = c[c.size() / 3 + 1];
    const core::Pose2 pose(a.x(), a.y(), std::atan2(b.y() - a.y(), b.x() - a.x()));
    const Eigen::Isometry3d T = pose.to_isometry();
    std::vector<Eigen::Vector2f> base;
    for (const auto& p : lidar
                             .scan(
                                 world, [&](double) { return T; }, 0.0)
                             .to_points())
      base.emplace_back(p.x() + 0.3f, p.y());
    preprocess::PreprocessConfig pc;
    pc.crop.x_min = 0.0;
    pc.crop.x_max = 8.0;
    pc.voxel.voxel_size = 0.0;
    preprocess::Preprocessor pre(pc);
    return pre.run(base).points;
  }();
  return pts;
}

void run_pearl(benchmark::State& state, detect::PearlVariant v) {
  detect::PearlConfig c;
  c.variant = v;
  detect::PearlDetector det(c);
  detect::DetectorInput in;
  in.points = frame_points();
  std::size_t rows = 0;
  for (auto _ : state) {
    const auto obs = det.detect(in);
    rows = obs.rows.size();
    benchmark::DoNotOptimize(rows);
  }
  state.counters["points"] = static_cast<double>(in.points.size());
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["iterations"] = det.last_iterations();
}

void BM_Ruby(benchmark::State& s) {
  run_pearl(s, detect::PearlVariant::ruby);
}
void BM_Opal(benchmark::State& s) {
  run_pearl(s, detect::PearlVariant::opal);
}
void BM_Pearl(benchmark::State& s) {
  run_pearl(s, detect::PearlVariant::pearl);
}

void BM_RansacLines(benchmark::State& state) {
  detect::RansacLinesDetector det;
  detect::DetectorInput in;
  in.points = frame_points();
  std::size_t rows = 0;
  for (auto _ : state) {
    rows = det.detect(in).rows.size();
    benchmark::DoNotOptimize(rows);
  }
  state.counters["points"] = static_cast<double>(in.points.size());
  state.counters["rows"] = static_cast<double>(rows);
}

/// PCL SACSegmentation, SACMODEL_LINE, sequential extraction (same stopping rules).
void BM_PclSacLines(benchmark::State& state) {
  const detect::RansacLinesConfig rc;
  pcl::PointCloud<pcl::PointXYZ>::Ptr all(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : frame_points()) all->push_back({p.x(), p.y(), 0.0f});
  std::size_t lines = 0;
  for (auto _ : state) {
    pcl::PointCloud<pcl::PointXYZ>::Ptr rest(new pcl::PointCloud<pcl::PointXYZ>(*all));
    pcl::SACSegmentation<pcl::PointXYZ> seg;
    seg.setModelType(pcl::SACMODEL_LINE);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setMaxIterations(rc.iterations);
    seg.setDistanceThreshold(rc.inlier_distance);
    lines = 0;
    for (int k = 0; k < rc.max_lines && static_cast<int>(rest->size()) >= rc.min_inliers; ++k) {
      pcl::ModelCoefficients coeff;
      pcl::PointIndices::Ptr inl(new pcl::PointIndices);
      seg.setInputCloud(rest);
      seg.segment(*inl, coeff);
      if (static_cast<int>(inl->indices.size()) < rc.min_inliers) break;
      ++lines;
      pcl::ExtractIndices<pcl::PointXYZ> ex;
      pcl::PointCloud<pcl::PointXYZ>::Ptr next(new pcl::PointCloud<pcl::PointXYZ>);
      ex.setInputCloud(rest);
      ex.setIndices(inl);
      ex.setNegative(true);
      ex.filter(*next);
      rest.swap(next);
    }
    benchmark::DoNotOptimize(lines);
  }
  state.counters["points"] = static_cast<double>(all->size());
  state.counters["rows"] = static_cast<double>(lines);
}

/// corn_rows_2d (real scans): every 32nd frame cropped to x in [0, 2.5] m (the row-crop config of
/// the tests), ~300 cluttered points each; time per frame = reported time / frames.
const std::vector<std::vector<Eigen::Vector2f>>& corn_frames() {
  static const std::vector<std::vector<Eigen::Vector2f>> frames = [] {
    const auto clouds =
        io::read_points_csv(std::string(ROWNAV_SHARED_DATA) + "/corn_rows_2d/scans.csv");
    std::vector<std::vector<Eigen::Vector2f>> out;
    for (std::size_t i = 0; i < clouds.size(); i += 32) {
      out.emplace_back();
      for (const auto& p : clouds[i].points)
        if (p.x >= 0.0f && p.x <= 2.5f && p.y >= -1.2f && p.y <= 1.0f)
          out.back().emplace_back(p.x, p.y);
    }
    return out;
  }();
  return frames;
}

template <class Detector>
void run_corn(benchmark::State& state, Detector& det, bool planar = false) {
  const auto& frames = corn_frames();
  const auto input = [planar](const std::vector<Eigen::Vector2f>& f) {
    detect::DetectorInput in;
    in.points = f;
    in.planar_scan = planar;
    return in;
  };
  for (auto _ : state)
    for (const auto& f : frames) benchmark::DoNotOptimize(det.detect(input(f)).rows.size());
  // The rows of one more pass, summed: equal sums (JSON output, full precision) between two
  // builds say that a speed-up did not change what is detected.
  double row_sum = 0.0, rows = 0.0;
  for (const auto& f : frames) {
    for (const auto& r : det.detect(input(f)).rows) {
      row_sum += r.offset + r.heading;
      rows += 1.0;
    }
  }
  state.counters["rows"] = rows;
  state.counters["row_sum"] = row_sum;
  state.counters["frames"] = static_cast<double>(frames.size());
  state.counters["per_frame_us"] = benchmark::Counter(
      static_cast<double>(frames.size()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_RubyCornRows(benchmark::State& s) {
  detect::PearlDetector det;
  run_corn(s, det);
}
/// The same frames flagged as a planar scan, as NavStack gives a 2D scanner's points
/// (planar_label_cost, the row-direction pick).
void BM_RubyCornRowsPlanar(benchmark::State& s) {
  detect::PearlDetector det;
  run_corn(s, det, true);
}
void BM_RansacLinesCornRows(benchmark::State& s) {
  detect::RansacLinesDetector det;
  run_corn(s, det);
}

BENCHMARK(BM_Ruby)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Opal)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Pearl)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RansacLines)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PclSacLines)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RubyCornRows)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RubyCornRowsPlanar)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RansacLinesCornRows)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
