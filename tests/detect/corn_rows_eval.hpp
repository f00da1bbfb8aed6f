#pragma once
// Evaluation of a row detector on ../shared/data/corn_rows_2d (1630 real 2D LiDAR frames in maize
// with hand-labelled left / right rows, ~0.7 m apart): one config for all frames, crop x in
// [0, 2.5] m. Errors of the detected corridor rows against the labelled lines at x = 0.5 and
// 1.5 m, heading errors, share of labelled lines detected; corridor centre (offset at x = 0,
// heading) against the labelled centre. The trivial baseline (rows at y = +-0.35 m straight
// ahead) is measured alongside.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "rownav/detect/row_detector.hpp"
#include "rownav/io/cloud_io.hpp"
#include "rownav/io/row_labels.hpp"
#include "rownav/preprocess/preprocessor.hpp"

namespace rownav::test {

struct CornStats {
  std::vector<double> lat05, lat15, heading;  // per labelled line that was detected [m], [rad]
  std::vector<double> centre, centre_heading;  // per frame with a corridor [m], [rad]
  int lines = 0, detected = 0, frames = 0, corridors = 0;
};

inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}
inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  const auto k = static_cast<long>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

inline std::filesystem::path corn_dir() {
#ifdef ROWNAV_SHARED_DATA
  return std::filesystem::path(ROWNAV_SHARED_DATA) / "corn_rows_2d";
#else
  return "../shared/data/corn_rows_2d";
#endif
}

inline void add_line(CornStats& s, const core::RowObservation& obs, int index,
                     const core::Segment2& label) {
  ++s.lines;
  if (index < 0) return;
  const auto& r = obs.rows[static_cast<std::size_t>(index)];
  const core::Line2 l = label.line();
  if (std::abs(r.line.y_at(0.5) - l.y_at(0.5)) > 0.35) return;  // another row: not this one
  ++s.detected;
  s.lat05.push_back(std::abs(r.line.y_at(0.5) - l.y_at(0.5)));
  s.lat15.push_back(std::abs(r.line.y_at(1.5) - l.y_at(1.5)));
  s.heading.push_back(std::abs(r.heading - std::atan2(l.direction.y(), l.direction.x())));
}

/// Runs `detect` (observation from a DetectorInput) over every labelled frame.
template <class Detect>
CornStats evaluate_corn(Detect&& detect, const char* name) {
  CornStats s;
  const auto clouds = io::read_points_csv(corn_dir() / "scans.csv");
  const auto labels = io::read_row_labels(corn_dir() / "labels.csv");
  preprocess::PreprocessConfig pc;
  pc.crop.x_min = 0.0;  // the one row-crop crop box
  pc.voxel.voxel_size = 0.0;  // 2D scans are already sparse
  pc.crop.x_max = 2.5;
  preprocess::Preprocessor pre(pc);
  std::vector<Eigen::Vector2f> pts;
  for (const auto& cloud : clouds) {
    const auto it = labels.find(static_cast<std::int64_t>(cloud.stamp));
    if (it == labels.end()) continue;
    ++s.frames;
    pts.clear();
    for (const auto& p : cloud.points) pts.emplace_back(p.x, p.y);
    pre.run(pts);
    const auto obs = detect(pre.input(cloud.stamp));
    add_line(s, obs, obs.left, it->second.left);
    add_line(s, obs, obs.right, it->second.right);
    if (!obs.corridor) continue;
    ++s.corridors;
    const core::Line2 l = it->second.left.line(), r = it->second.right.line();
    s.centre.push_back(std::abs(obs.corridor->offset - 0.5 * (l.y_at(0.0) + r.y_at(0.0))));
    const double h = 0.5 * (l.heading() + r.heading());
    s.centre_heading.push_back(std::abs(obs.corridor->heading - h));
  }
  std::printf("%s on corn_rows_2d: %d frames, lines detected %d / %d (%.1f %%), lateral median / "
              "p90 at 0.5 m %.3f / %.3f m, at 1.5 m %.3f / %.3f m, heading median / p90 %.2f / "
              "%.2f deg; corridor in %d frames, centre median / p90 %.3f / %.3f m, heading %.2f / "
              "%.2f deg\n",
              name, s.frames, s.detected, s.lines, 100.0 * s.detected / std::max(1, s.lines),
              median(s.lat05), quantile(s.lat05, 0.9), median(s.lat15), quantile(s.lat15, 0.9),
              median(s.heading) * 180 / M_PI, quantile(s.heading, 0.9) * 180 / M_PI, s.corridors,
              median(s.centre), quantile(s.centre, 0.9), median(s.centre_heading) * 180 / M_PI,
              quantile(s.centre_heading, 0.9) * 180 / M_PI);
  return s;
}

}  // namespace rownav::test
