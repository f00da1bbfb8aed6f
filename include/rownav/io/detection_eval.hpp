#pragma once
/// @file detection_eval.hpp Accuracy of row detectors against ground truth: simulated frames
/// (sim::FieldTruth) and the real corn data set (hand-labelled lines), with markdown / JSON
/// reports. Used by bench/detect_accuracy_bench.cpp and reusable by other benchmarks.
///
/// Definitions (all errors are absolute values; statistics over the frames where the quantity
/// exists, `n` says how many):
/// - simulated frames. Truth: the corridor's left / right rows (GroundTruth::left_row /
///   right_row, their base-frame tangent lines in GroundTruth::rows) and every row within reach.
///   * heading error [deg]: detected corridor heading (RowObservation::corridor, else the common
///     heading) minus the true corridor heading (mean direction of the two true rows);
///   * lateral error [m]: detected left (right) row minus true left (right) row, y at x = 0,
///     pooled over both sides; for a corridor-only detector (rows empty, corridor set) the
///     corridor centre offset minus the true centre (mean of the two rows at x = 0);
///   * corridor rows output: lateral errors scored / (2 x frames) (frames for corridor-only);
///   * detection rate: frames whose detected left and right rows are both within
///     kMatchLateral at x = 0 and kMatchHeadingDeg of the true ones (corridor-only: the centre
///     and heading within those), over all frames;
///   * false rows per frame: detected rows whose support centre point lies farther than
///     kMatchLateral from every true row within reach, summed over frames / frames.
/// - corn set (labels in the sensor frame = base frame):
///   * lateral error [m] at x = 0.5 m and 1.5 m: detected left (right) row y(x) minus the
///     labelled left (right) line y(x), pooled over both lines;
///   * heading error [deg]: mean direction of the detected left and right rows minus the mean
///     direction of the labelled lines (one row only: that row against its label);
///   * row heading error [deg]: each detected left (right) row's direction minus its labelled
///     line's, pooled over both lines (the "heading error" of the baseline: the two
///     baseline lines often splay symmetrically, so their mean direction is better than either);
///   * detection rate: labelled lines with some detected row within kCornMatch of it at x = 1 m,
///     over all labelled lines; output rate: labelled lines for which the detector gave a row on
///     that side (RowObservation::left / right), whatever its accuracy.
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/row_observation.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/detect/pipeline.hpp"
#include "rownav/io/row_labels.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/ground_truth.hpp"

namespace rownav::io {

inline constexpr double kMatchLateral = 0.3;     ///< [m] simulated rows: match distance
inline constexpr double kMatchHeadingDeg = 5.0;  ///< [deg] simulated rows: match angle
inline constexpr double kCornMatch = 0.2;        ///< [m] corn lines: match distance at x = 1 m

/// One simulated test case: a field, a sensor and robot poses in its corridors.
struct EvalScenario {
  std::string name;
  sim::FieldConfig field;
  std::string lidar_preset = "os1_16";       ///< sim::lidar_preset name
  int frames = 20;                           ///< [-] robot poses (one LiDAR frame each)
  std::uint64_t seed = 1;                    ///< poses and sensor noise
  double max_lateral = 0.3;                  ///< [m] uniform offset from the corridor centre, +-
  double max_heading_deg = 8.0;              ///< [deg] uniform heading offset from the corridor, +-
  std::string crop = "vineyard";             ///< detection config to use: config/detect/<crop>.yaml
  std::optional<Eigen::Vector3d> mount_xyz;  ///< [m] overrides the preset's LiDAR mount
};

/// The standard set: narrow (1.8 m) / wide (2.8 m) vineyards at low / medium / high canopy with
/// no / some / many weeds, missing vines, an orchard and maize; OS1-16, OS1-64 and LMS-1081.
/// `quick`: fewer frames (for CI and tests).
std::vector<EvalScenario> standard_scenarios(bool quick);

/// One LiDAR frame (cloud for a spinning sensor, scan for a planar one) and its truth.
struct EvalFrame {
  bool planar = false;
  core::PointCloud cloud;  ///< LiDAR frame
  core::Scan2D scan;       ///< LiDAR frame
  sim::GroundTruth truth;
};

/// The frames of a scenario and the mount they were taken with.
struct SimulatedFrames {
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
  std::vector<EvalFrame> frames;
};

/// Generates the field, places the robot (seeded) and takes one LiDAR frame per pose.
/// Throws std::invalid_argument on a bad scenario.
SimulatedFrames simulate_frames(const EvalScenario& scenario);

/// Median and 95th percentile (linear interpolation) of n values; NaN when n = 0.
struct Stat {
  int n = 0;
  double median = std::numeric_limits<double>::quiet_NaN();
  double p95 = std::numeric_limits<double>::quiet_NaN();
};
Stat make_stat(std::vector<double> values);

/// Scores of one simulated frame (see the file comment).
struct FrameScore {
  bool valid = false;          ///< the truth has both corridor rows
  bool corridor_only = false;  ///< scored on the corridor (rows empty, corridor set)
  std::optional<double> heading_error_deg;
  std::vector<double> lateral_errors;  ///< [m] left and right rows present (or the centre)
  bool detected = false;
  int false_rows = 0;
};
FrameScore score_frame(const core::RowObservation& obs, const sim::GroundTruth& truth);

/// Accuracy of one detector on one scenario.
struct ScenarioEval {
  std::string detector, scenario, lidar;
  int frames = 0;              ///< frames scored (truth with both corridor rows)
  bool corridor_only = false;  ///< lateral is the corridor centre's
  Stat heading_deg, lateral_m;
  double detection_rate = 0.0;  ///< [0, 1]
  double false_rows_per_frame = 0.0;
  double ms_per_frame = 0.0;  ///< [ms] pipeline time (preprocessing + detection), wall clock
};
ScenarioEval evaluate_frames(detect::DetectionPipeline& pipeline, const SimulatedFrames& frames,
                             const EvalScenario& scenario);

/// Scores of one labelled corn frame.
struct CornFrameScore {
  std::vector<double> lateral_05, lateral_15;  ///< [m] per detected labelled side
  std::optional<double> heading_error_deg;
  std::vector<double> row_heading_deg;  ///< [deg] per detected labelled side
  int lines_detected = 0;               ///< of the 2 labelled lines
  int lines_output = 0;                 ///< labelled sides with a detected left / right row
};
CornFrameScore score_corn_frame(const core::RowObservation& obs, const RowLabel& label);

/// Accuracy of one detector on the real corn set.
struct CornEval {
  std::string detector;
  int frames = 0, lines = 0;
  Stat lateral_05_m, lateral_15_m, heading_deg, row_heading_deg;
  double detection_rate = 0.0;  ///< [0, 1] labelled lines detected (within kCornMatch)
  double output_rate = 0.0;     ///< [0, 1] labelled lines with a detected row on their side
  double ms_per_frame = 0.0;
};
/// Runs `pipeline` (process_points, the data are in the sensor frame = base frame) on every
/// `stride`-th labelled frame of `data_dir` (scans.csv + labels.csv). InputError on bad files.
CornEval evaluate_corn(detect::DetectionPipeline& pipeline, const std::filesystem::path& data_dir,
                       int stride = 1);

/// Markdown tables (one row per detector x scenario; one per detector on the corn set).
std::string scenario_table_markdown(const std::vector<ScenarioEval>& results);
std::string corn_table_markdown(const std::vector<CornEval>& results);
/// Both result sets as one JSON document {"simulated": [...], "corn": [...]}, NaN as null.
std::string eval_json(const std::vector<ScenarioEval>& simulated,
                      const std::vector<CornEval>& corn);
/// Writes eval_json to `file`; std::runtime_error when it cannot be written.
void write_eval_json(const std::filesystem::path& file, const std::vector<ScenarioEval>& simulated,
                     const std::vector<CornEval>& corn);

}  // namespace rownav::io
