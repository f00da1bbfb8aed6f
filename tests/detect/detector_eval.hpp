#pragma once
// Shared scoring of row detectors against known truth for the detector tests: synthetic scenes,
// simulated LiDAR frames and the real corn data (corn_rows_2d).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "../common/synthetic_rows.hpp"
#include "rownav/detect/row_detector.hpp"
#include "rownav/io/cloud_io.hpp"
#include "rownav/io/row_labels.hpp"
#include "rownav/preprocess/preprocessor.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace rownav::test {

constexpr double kDeg = std::numbers::pi / 180.0;

/// Heading error [deg] and lateral errors [m] at x = 0 of the corridor rows.
struct CorridorError {
  bool found = false;  // both corridor rows detected
  double heading_deg = 1e9, left = 1e9, right = 1e9;
  double centre = 1e9;  // corridor centre (mean of the two rows) at x = 0
  double worst() const { return std::max(left, right); }
};

/// Truth corridor rows: nearest truth lines with y(0) >= 0 (left) and < 0 (right).
inline CorridorError corridor_error(const core::RowObservation& obs,
                                    const std::vector<core::Line2>& truth) {
  CorridorError e;
  const core::Line2* tl = nullptr;
  const core::Line2* tr = nullptr;
  for (const auto& t : truth) {
    const double y = t.y_at(0.0);
    if (y >= 0.0 && (!tl || y < tl->y_at(0.0))) tl = &t;
    if (y < 0.0 && (!tr || y > tr->y_at(0.0))) tr = &t;
  }
  if (tl) e.heading_deg = std::abs(obs.heading - tl->heading()) / kDeg;
  if (obs.left < 0 || obs.right < 0 || !tl || !tr) return e;
  e.found = true;
  e.left = std::abs(obs.rows[std::size_t(obs.left)].line.y_at(0.0) - tl->y_at(0.0));
  e.right = std::abs(obs.rows[std::size_t(obs.right)].line.y_at(0.0) - tr->y_at(0.0));
  e.centre = std::abs(obs.rows[std::size_t(obs.left)].line.y_at(0.0) +
                      obs.rows[std::size_t(obs.right)].line.y_at(0.0) - tl->y_at(0.0) -
                      tr->y_at(0.0)) / 2.0;
  return e;
}

inline detect::DetectorInput input_of(const SyntheticScene& s) {
  detect::DetectorInput in;
  in.points = s.points;
  return in;
}

/// Degenerate frames every detector must survive with status no_rows or degraded.
inline std::vector<std::vector<Eigen::Vector2f>> degenerate_frames() {
  std::vector<std::vector<Eigen::Vector2f>> f;
  f.push_back({});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  f.push_back(std::vector<Eigen::Vector2f>(500, Eigen::Vector2f(nan, nan)));
  f.push_back({Eigen::Vector2f(2.0f, 0.5f)});
  std::vector<Eigen::Vector2f> collinear, field, wall, inf;
  for (int i = 0; i < 400; ++i) collinear.emplace_back(0.5f + 0.02f * i, 0.3f + 0.01f * i);
  f.push_back(collinear);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> ux(0.3f, 8.0f), uy(-4.0f, 4.0f);
  for (int i = 0; i < 3000; ++i) field.emplace_back(ux(rng), uy(rng));
  f.push_back(field);
  for (int i = 0; i < 800; ++i) wall.emplace_back(7.0f + 0.01f * std::sin(float(i)), -4.0f + 0.01f * i);
  f.push_back(wall);
  for (int i = 0; i < 50; ++i) inf.emplace_back(std::numeric_limits<float>::infinity(), 1.0f);
  f.push_back(inf);
  return f;
}

/// One simulated OS1-16 frame in corridor `corridor` of a 6-row vineyard, robot turned by
/// `heading_offset`; the cloud is preprocessed (defaults) into `pre`.
// The clean-ish sweep both two-line and multi-line detectors must pass (the accuracy
// bounds): headings -15..15 deg, three spacings, off-centre robot, canopy 0.3 m, noise, gaps,
// weeds and outliers. `rows_expected` > 0 also checks the number of rows returned.
template <class Detector>
void sweep_cleanish(Detector& det, const char* name, std::size_t rows_expected = 0) {
  double worst_heading = 0.0, worst_lat = 0.0;
  for (const double spacing : {0.75, 1.8, 2.8})
    for (int h = -15; h <= 15; h += 5)
      for (const double off : {-0.2, 0.0, 0.15}) {
        SyntheticRows s;
        s.rows = 4, s.spacing = spacing, s.heading = h * kDeg, s.offset = off * spacing;
        s.gap_probability = 0.1, s.weeds = 60, s.outliers = 30;
        s.seed = std::uint64_t(100 + h);
        const auto scene = make_rows(s);
        const auto obs = det.detect(input_of(scene));
        const auto e = corridor_error(obs, scene.truth);
        SCOPED_TRACE(testing::Message() << "spacing " << spacing << " heading " << h << " off " << off);
        ASSERT_EQ(obs.status, core::DetectionStatus::ok);
        if (rows_expected > 0) {
          EXPECT_EQ(obs.rows.size(), rows_expected);
        }
        EXPECT_LT(e.heading_deg, 0.5);
        EXPECT_LT(e.worst(), 0.03);
        worst_heading = std::max(worst_heading, e.heading_deg);
        worst_lat = std::max(worst_lat, e.worst());
      }
  std::printf("[%s synthetic clean-ish] worst heading %.3f deg, worst lateral %.1f mm\n", name,
              worst_heading, 1000 * worst_lat);
}

// Hard scenes (3 cm noise, 30 % gaps, 300 outliers, dense weeds): returns how many of the 12
// corridors come out right (heading < 1.5 deg, rows < 8 cm) and prints the figures.
template <class Detector>
int sweep_hard(Detector& det, const char* name) {
  int ok = 0, n = 0;
  double worst_heading = 0.0, worst_lat = 0.0;
  for (const double spacing : {0.75, 1.8, 2.8})
    for (int h = -15; h <= 15; h += 10) {
      SyntheticRows s;
      s.rows = 5, s.spacing = spacing, s.heading = h * kDeg, s.offset = 0.25 * spacing;
      s.noise = 0.03, s.gap_probability = 0.3, s.outliers = 300;
      s.weeds = static_cast<int>(100 * spacing);  // same weed density per m2 for every spacing
      s.seed = std::uint64_t(7 + h);
      const auto scene = make_rows(s);
      const auto e = corridor_error(det.detect(input_of(scene)), scene.truth);
      ++n;
      if (!e.found || e.heading_deg > 1.5 || e.worst() > 0.08) continue;
      ++ok;
      worst_heading = std::max(worst_heading, e.heading_deg);
      worst_lat = std::max(worst_lat, e.worst());
    }
  std::printf("[%s synthetic hard] %d / %d corridors right (heading < 1.5 deg, rows < 8 cm); "
              "among them worst heading %.3f deg, worst lateral %.1f mm\n", name, ok, n,
              worst_heading, 1000 * worst_lat);
  return ok;
}

struct SimFrame {
  sim::GroundTruth truth;
  core::PointCloud cloud_base;
};

inline SimFrame sim_frame(const sim::Field& field, int corridor, double heading_offset,
                          double lateral_offset, const char* preset = "os1_16") {
  const sim::FieldTruth ft(field);
  const auto& c = ft.corridor_centre(0, corridor);
  const std::size_t mid = c.size() / 2;
  const Eigen::Vector2d t = (c[mid + 1] - c[mid]).normalized();
  const Eigen::Vector2d p = c[mid] + lateral_offset * Eigen::Vector2d(-t.y(), t.x());
  const core::Pose2 pose(p.x(), p.y(), std::atan2(t.y(), t.x()) + heading_offset);
  SimFrame f;
  f.truth = ft.at(pose, 0.0);
  sim::LidarConfig lc = sim::lidar_preset(preset);
  lc.motion_during_sweep = false;
  sim::Lidar lidar(lc, 3);
  const sim::RayCaster caster(field.mesh);
  const auto pose_at = [&](double) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(pose.x, pose.y, 0.0);
    T.linear() = Eigen::AngleAxisd(pose.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
  f.cloud_base = lidar.sweep(caster, pose_at, 0.0);
  const Eigen::Isometry3f T = lc.T_base_lidar().cast<float>();
  for (auto& q : f.cloud_base.points) {
    const Eigen::Vector3f b = T * Eigen::Vector3f(q.x, q.y, q.z);
    q.x = b.x(), q.y = b.y(), q.z = b.z();
  }
  f.cloud_base.frame_id = "base";
  return f;
}

/// Truth lines (base frame) of a simulated frame, to score with corridor_error.
inline std::vector<core::Line2> truth_lines(const sim::GroundTruth& gt) {
  std::vector<core::Line2> out;
  for (const auto& r : gt.rows) out.push_back(r.line_base);
  return out;
}

/// Statistics of a detector over the real corn data set.
struct CornStats {
  int frames = 0, lines = 0, detected = 0;
  double median_lat_05 = 0, median_lat_15 = 0, median_heading_deg = 0;
};

inline double median(std::vector<double> v) {
  if (v.empty()) return 1e9;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Runs a detector over corn_rows_2d (x cropped to [0, 2.5] m) and scores both labelled lines.
template <class Detector>
CornStats corn_stats(Detector& det) {
  const std::string dir = std::string(ROWNAV_SHARED_DATA) + "/corn_rows_2d/";
  const auto clouds = io::read_points_csv(dir + "scans.csv");
  const auto labels = io::read_row_labels(dir + "labels.csv");
  preprocess::PreprocessConfig pc;
  pc.crop.x_min = 0.0, pc.crop.x_max = 2.5, pc.crop.y_min = -1.2, pc.crop.y_max = 1.2;
  pc.voxel.voxel_size = 0.0;  // 2D scans are already sparse
  preprocess::Preprocessor pre(pc);
  CornStats s;
  std::vector<double> lat05, lat15, head;
  std::vector<Eigen::Vector2f> pts;
  for (const auto& c : clouds) {
    const auto it = labels.find(static_cast<std::int64_t>(c.stamp));
    if (it == labels.end()) continue;
    pts.clear();
    for (const auto& p : c.points) pts.emplace_back(p.x, p.y);
    pre.run(pts);
    const auto obs = det.detect(pre.input(c.stamp));
    ++s.frames;
    for (int side = 0; side < 2; ++side) {
      const core::Line2 truth = (side == 0 ? it->second.left : it->second.right).line();
      ++s.lines;
      const int idx = side == 0 ? obs.left : obs.right;
      if (idx < 0) continue;
      ++s.detected;
      const auto& l = obs.rows[std::size_t(idx)].line;
      lat05.push_back(std::abs(l.y_at(0.5) - truth.y_at(0.5)));
      lat15.push_back(std::abs(l.y_at(1.5) - truth.y_at(1.5)));
      double dh = std::abs(l.heading() - truth.heading());
      head.push_back(std::min(dh, std::numbers::pi - dh) / kDeg);
    }
  }
  s.median_lat_05 = median(lat05), s.median_lat_15 = median(lat15);
  s.median_heading_deg = median(head);
  std::printf("[corn_rows_2d] %d frames, %d / %d lines detected (%.1f %%); median lateral error "
              "%.1f cm at x = 0.5 m, %.1f cm at 1.5 m; median heading error %.2f deg\n",
              s.frames, s.detected, s.lines, 100.0 * s.detected / std::max(1, s.lines),
              100 * s.median_lat_05, 100 * s.median_lat_15, s.median_heading_deg);
  return s;
}

}  // namespace rownav::test
