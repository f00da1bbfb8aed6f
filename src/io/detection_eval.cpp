// Scoring of detections against simulated truth and the corn labels (definitions in the header).
#include "rownav/io/detection_eval.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rownav/core/angle.hpp"
#include "rownav/io/cloud_io.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace {

const sim::RowTruth* find_row(const sim::GroundTruth& gt, int row) {
  if (row < 0) return nullptr;
  for (const auto& r : gt.rows)
    if (r.row == row) return &r;
  return nullptr;
}

// [deg] absolute angle between two directions taken as lines (no +-180 deg ambiguity: rows
// are oriented forward, so a plain wrapped difference is right).
double angle_error_deg(double a, double b) {
  return std::abs(core::rad2deg(core::wrap_angle(a - b)));
}

double mean_heading(const core::Line2& a, const core::Line2& b) {
  const Eigen::Vector2d d = a.direction + b.direction;
  return std::atan2(d.y(), d.x());
}

double y_at(const core::Line2& l, double x) {
  return std::abs(l.direction.x()) > 1e-9 ? l.y_at(x) : l.point.y();
}

// Rows of `obs` that lie farther than kMatchLateral from every true row, measured from the
// point of the detected row at the centre of its support.
int count_false_rows(const core::RowObservation& obs, const sim::GroundTruth& gt) {
  int n = 0;
  for (const auto& r : obs.rows) {
    const double xm = 0.5 * (r.x_min + r.x_max);
    const Eigen::Vector2d p(xm, y_at(r.line, xm));
    bool matched = false;
    for (const auto& t : gt.rows)
      matched |= std::abs(t.line_base.signed_distance(p)) <= kMatchLateral;
    n += matched ? 0 : 1;
  }
  return n;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Stat make_stat(std::vector<double> v) {
  Stat s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const auto q = [&](double f) {
    const double pos = f * static_cast<double>(v.size() - 1);
    const auto i = static_cast<std::size_t>(pos);
    const double w = pos - static_cast<double>(i);
    return i + 1 < v.size() ? v[i] * (1.0 - w) + v[i + 1] * w : v[i];
  };
  s.median = q(0.5);
  s.p95 = q(0.95);
  return s;
}

FrameScore score_frame(const core::RowObservation& obs, const sim::GroundTruth& gt) {
  FrameScore s;
  const auto* L = find_row(gt, gt.left_row);
  const auto* R = find_row(gt, gt.right_row);
  if (!L || !R) return s;
  s.valid = true;
  const double true_heading = mean_heading(L->line_base, R->line_base);
  if (obs.corridor)
    s.heading_error_deg = angle_error_deg(obs.corridor->heading, true_heading);
  else if (obs.status != core::DetectionStatus::no_rows)
    s.heading_error_deg = angle_error_deg(obs.heading, true_heading);
  s.corridor_only = obs.rows.empty() && obs.corridor.has_value();
  if (s.corridor_only) {
    const double centre = 0.5 * (y_at(L->line_base, 0.0) + y_at(R->line_base, 0.0));
    const double e = std::abs(obs.corridor->offset - centre);
    s.lateral_errors.push_back(e);
    s.detected = e <= kMatchLateral && *s.heading_error_deg <= kMatchHeadingDeg;
    return s;
  }
  bool both = true;
  for (const auto& [index, truth] : {std::pair{obs.left, L}, std::pair{obs.right, R}}) {
    if (index < 0 || index >= static_cast<int>(obs.rows.size())) {
      both = false;
      continue;
    }
    const auto& row = obs.rows[static_cast<std::size_t>(index)];
    const double e = std::abs(y_at(row.line, 0.0) - y_at(truth->line_base, 0.0));
    s.lateral_errors.push_back(e);
    both &= e <= kMatchLateral &&
            angle_error_deg(row.line.heading(), truth->line_base.heading()) <= kMatchHeadingDeg;
  }
  s.detected = both;
  s.false_rows = count_false_rows(obs, gt);
  return s;
}

ScenarioEval evaluate_frames(detect::DetectionPipeline& pipeline, const SimulatedFrames& frames,
                             const EvalScenario& scenario) {
  ScenarioEval e;
  e.detector = std::string(pipeline.detector().name());
  e.scenario = scenario.name;
  e.lidar = scenario.lidar_preset;
  std::vector<double> heading, lateral;
  int detected = 0, false_rows = 0;
  double ms = 0.0;
  for (const auto& f : frames.frames) {
    const auto t0 = std::chrono::steady_clock::now();
    const core::RowObservation obs =
        f.planar ? pipeline.process(f.scan) : pipeline.process(f.cloud);
    ms += ms_since(t0);
    const FrameScore s = score_frame(obs, f.truth);
    if (!s.valid) continue;
    ++e.frames;
    e.corridor_only |= s.corridor_only;
    if (s.heading_error_deg) heading.push_back(*s.heading_error_deg);
    lateral.insert(lateral.end(), s.lateral_errors.begin(), s.lateral_errors.end());
    detected += s.detected ? 1 : 0;
    false_rows += s.false_rows;
  }
  e.heading_deg = make_stat(std::move(heading));
  e.lateral_m = make_stat(std::move(lateral));
  if (e.frames > 0) {
    e.detection_rate = static_cast<double>(detected) / e.frames;
    e.false_rows_per_frame = static_cast<double>(false_rows) / e.frames;
  }
  if (!frames.frames.empty()) ms /= static_cast<double>(frames.frames.size());
  e.ms_per_frame = ms;
  return e;
}

CornFrameScore score_corn_frame(const core::RowObservation& obs, const RowLabel& label) {
  CornFrameScore s;
  Eigen::Vector2d det_dir = Eigen::Vector2d::Zero(), lab_dir = Eigen::Vector2d::Zero();
  for (const auto& [index, seg] :
       {std::pair{obs.left, &label.left}, std::pair{obs.right, &label.right}}) {
    core::Line2 truth = seg->line();
    if (truth.direction.x() < 0.0) truth.direction = -truth.direction;  // forward, as the rows
    for (const auto& r : obs.rows)
      if (std::abs(y_at(r.line, 1.0) - y_at(truth, 1.0)) <= kCornMatch) {
        ++s.lines_detected;
        break;
      }
    if (index < 0 || index >= static_cast<int>(obs.rows.size())) continue;
    const auto& row = obs.rows[static_cast<std::size_t>(index)].line;
    ++s.lines_output;
    s.row_heading_deg.push_back(angle_error_deg(row.heading(), truth.heading()));
    s.lateral_05.push_back(std::abs(y_at(row, 0.5) - y_at(truth, 0.5)));
    s.lateral_15.push_back(std::abs(y_at(row, 1.5) - y_at(truth, 1.5)));
    det_dir += row.direction;
    lab_dir += truth.direction;
  }
  if (det_dir.squaredNorm() > 0.0)
    s.heading_error_deg =
        angle_error_deg(std::atan2(det_dir.y(), det_dir.x()), std::atan2(lab_dir.y(), lab_dir.x()));
  return s;
}

CornEval evaluate_corn(detect::DetectionPipeline& pipeline, const std::filesystem::path& data_dir,
                       int stride) {
  const auto labels = read_row_labels(data_dir / "labels.csv");
  const auto clouds = read_points_csv(data_dir / "scans.csv");
  CornEval e;
  e.detector = std::string(pipeline.detector().name());
  std::vector<double> l05, l15, heading, row_heading;
  int detected = 0, output = 0, n = 0;
  double ms = 0.0;
  std::vector<Eigen::Vector2f> pts;
  for (const auto& cloud : clouds) {
    const auto frame = static_cast<std::int64_t>(std::llround(cloud.stamp));
    const auto it = labels.find(frame);
    if (it == labels.end() || n++ % std::max(stride, 1) != 0) continue;
    pts.clear();
    for (const auto& p : cloud.points) pts.emplace_back(p.x, p.y);
    const auto t0 = std::chrono::steady_clock::now();
    const core::RowObservation obs = pipeline.process_points(pts, cloud.stamp);
    ms += ms_since(t0);
    const CornFrameScore s = score_corn_frame(obs, it->second);
    ++e.frames;
    e.lines += 2;
    detected += s.lines_detected;
    output += s.lines_output;
    row_heading.insert(row_heading.end(), s.row_heading_deg.begin(), s.row_heading_deg.end());
    l05.insert(l05.end(), s.lateral_05.begin(), s.lateral_05.end());
    l15.insert(l15.end(), s.lateral_15.begin(), s.lateral_15.end());
    if (s.heading_error_deg) heading.push_back(*s.heading_error_deg);
  }
  if (e.frames == 0) throw InputError(data_dir.string(), "", "no labelled frame with points");
  e.lateral_05_m = make_stat(std::move(l05));
  e.lateral_15_m = make_stat(std::move(l15));
  e.heading_deg = make_stat(std::move(heading));
  e.row_heading_deg = make_stat(std::move(row_heading));
  e.detection_rate = static_cast<double>(detected) / e.lines;
  e.output_rate = static_cast<double>(output) / e.lines;
  e.ms_per_frame = ms / e.frames;
  return e;
}

}  // namespace rownav::io
