/// @file cluster_bench.cpp cluster_rows (DBSCAN with a grid or a nanoflann kd-tree) and PCL's
/// EuclideanClusterExtraction (kd-tree) on the same points: an OS1-64 frame simulated in a
/// 20-row x 100 m high-canopy vineyard, robot in corridor 9, after preprocess::Preprocessor
/// (voxel_size 0.15). cone_rect on a simulated lms_1081 scan in the same corridor. One core.
///   ./build/cluster_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <cmath>

#include "rownav/detect/cluster_rows.hpp"
#include "rownav/detect/cone_rect.hpp"
#include "rownav/preprocess/preprocessor.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace {

using namespace rownav;

struct Scene {
  core::PointCloud cloud_base;             // OS1-64 frame, base frame
  std::vector<Eigen::Vector2f> scan_base;  // lms_1081 scan, base frame
};

Eigen::Isometry3d corridor_pose(const sim::FieldTruth& truth) {
  const auto& c = truth.corridor_centre(0, 9);
  const std::size_t i = c.size() / 2;
  const Eigen::Vector2d d = c[i + 1] - c[i];
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(c[i].x(), c[i].y(), 0.0);
  T.linear() = Eigen::AngleAxisd(std::atan2(d.y(), d.x()), Eigen::Vector3d::UnitZ()).matrix();
  return T;
}

const Scene& scene() {
  static const Scene s = [] {
    sim::FieldConfig f;
    f.kind = sim::FieldKind::vineyard;
    f.vineyard.rows = 20;
    f.vineyard.row_length = 100;
    f.vineyard.stage = sim::GrowthStage::high;
    const sim::Field field = sim::generate_field(f);
    const sim::FieldTruth truth(field);
    const Eigen::Isometry3d T = corridor_pose(truth);
    const sim::RayCaster caster(field.mesh);
    auto pose_at = [&](double) { return T; };
    Scene out;
    const auto os1 = sim::lidar_preset("os1_64");
    out.cloud_base = sim::Lidar(os1, 1).sweep(caster, pose_at, 0.0);
    const Eigen::Isometry3f T_bl = os1.T_base_lidar().cast<float>();
    for (auto& p : out.cloud_base.points) {
      const Eigen::Vector3f q = T_bl * Eigen::Vector3f(p.x, p.y, p.z);
      p.x = q.x(), p.y = q.y(), p.z = q.z();
    }
    const auto lms = sim::lidar_preset("lms_1081");
    const Eigen::Isometry3f T_bs = lms.T_base_lidar().cast<float>();
    for (const auto& p : sim::Lidar(lms, 1).scan(caster, pose_at, 0.0).to_points()) {
      const Eigen::Vector3f q = T_bs * Eigen::Vector3f(p.x(), p.y(), 0.0f);
      out.scan_base.emplace_back(q.x(), q.y());
    }
    return out;
  }();
  return s;
}

preprocess::PreprocessConfig pre_config() {
  preprocess::PreprocessConfig c;
  c.voxel.voxel_size = 0.15;
  return c;
}

const std::vector<Eigen::Vector2f>& points() {
  static const std::vector<Eigen::Vector2f> p = [] {
    preprocess::Preprocessor pre(pre_config());
    return pre.run(scene().cloud_base).points;
  }();
  return p;
}

void BM_Preprocess(benchmark::State& st) {  // the preprocessing share of the full cost
  const auto& cloud = scene().cloud_base;   // simulated before the timing
  preprocess::Preprocessor pre(pre_config());
  for (auto _ : st) benchmark::DoNotOptimize(pre.run(cloud).points.data());
  st.counters["points"] = static_cast<double>(pre.run(cloud).points.size());
}

void BM_Preprocess_ClusterRows(benchmark::State& st) {  // full per-frame cost
  scene();                                              // simulated before the timing
  preprocess::Preprocessor pre(pre_config());
  detect::ClusterRowsDetector d;
  for (auto _ : st) {
    pre.run(scene().cloud_base);
    benchmark::DoNotOptimize(d.detect(pre.input(0.0)));
  }
  st.counters["raw_points"] = static_cast<double>(scene().cloud_base.size());
}

void BM_ClusterRows(benchmark::State& st) {
  detect::ClusterRowsConfig c;
  c.neighbour_search =
      st.range(0) ? detect::NeighbourSearch::kd_tree : detect::NeighbourSearch::grid;
  detect::ClusterRowsDetector d(c);
  detect::DetectorInput in;
  in.points = points();
  std::size_t rows = 0;
  for (auto _ : st) rows = d.detect(in).rows.size();
  st.counters["points"] = static_cast<double>(in.points.size());
  st.counters["rows"] = static_cast<double>(rows);
}

void BM_Dbscan(benchmark::State& st) {
  detect::Dbscan db;
  const auto search =
      st.range(0) ? detect::NeighbourSearch::kd_tree : detect::NeighbourSearch::grid;
  for (auto _ : st) benchmark::DoNotOptimize(db.run(points(), 0.35, 4, search).data());
  st.counters["clusters"] = db.cluster_count();
}

// PCL's Euclidean clustering (kd-tree, tolerance = eps, min size = min_cluster_points) on the
// same points at z = 0: the clustering step only, no regression.
void BM_PclEuclideanClusters(benchmark::State& st) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : points()) cloud->push_back({p.x(), p.y(), 0.0f});
  std::size_t n = 0;
  for (auto _ : st) {
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    tree->setInputCloud(cloud);
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(0.35);
    ec.setMinClusterSize(5);
    ec.setSearchMethod(tree);
    ec.setInputCloud(cloud);
    std::vector<pcl::PointIndices> clusters;
    ec.extract(clusters);
    n = clusters.size();
  }
  st.counters["clusters"] = static_cast<double>(n);
}

void BM_ConeRect(benchmark::State& st) {
  detect::ConeRectDetector d;
  detect::DetectorInput in;
  in.points = scene().scan_base;
  in.planar_scan = st.range(0) != 0;  // planar: the row direction and the nearest-row step-in
  core::RowObservation o;
  for (auto _ : st) o = d.detect(in);
  st.counters["points"] = static_cast<double>(in.points.size());
  st.counters["ok"] = o.status == core::DetectionStatus::ok;
}

}  // namespace

BENCHMARK(BM_Preprocess)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Preprocess_ClusterRows)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ClusterRows)->Arg(0)->Arg(1)->ArgName("kd_tree")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dbscan)->Arg(0)->Arg(1)->ArgName("kd_tree")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PclEuclideanClusters)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ConeRect)->Arg(0)->Arg(1)->ArgName("planar")->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
