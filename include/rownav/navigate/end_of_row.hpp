#pragma once
/// @file end_of_row.hpp End-of-row detection: is the robot leaving the corridor?
///
/// CONTRACT (signatures) shared by navigate/ and the closed-loop runner. Three cues, combined:
///  - the point-count hypothesis test of 001_b5f4b55a1b95775a.txt eq. (24)-(25): points 0.5-1.3 m
///    high in a box 3-5 m ahead, compared with a threshold;
///  - the end-of-row rectangle of 003_25dc0df51a1e5faf.txt (sec. II-C): too few points in a
///    rectangle ahead on each side;
///  - the tracked row models' extent (x_max of the followed rows).
/// After the end is declared the robot exits by a fixed distance measured by odometry; that
/// distance is reported here, the navigator drives it.
#include <Eigen/Core>
#include <optional>
#include <span>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::navigate {

/// Configuration of the end-of-row detector (the implementation owns and may extend the fields).
struct EndOfRowConfig {
  double band_z_min = 0.5;      ///< [m] lowest point height counted (001 eq. 24)
  double band_z_max = 1.3;      ///< [m] highest point height counted (001 eq. 24)
  double box_x_min = 3.0;       ///< [m] near edge of the look-ahead box (001 sec. 2.5)
  double box_x_max = 5.0;       ///< [m] far edge of the look-ahead box
  int point_threshold = 20;     ///< [points] fewer than this in the box: row end ahead (001 eq. 25)
  int confirm_frames = 3;       ///< [frames] consecutive positive frames before declaring the end
  double exit_distance = 1.0;   ///< [m] driven past the last plant (by odometry) before turning

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("band_z_min", s.band_z_min);
    v("band_z_max", s.band_z_max);
    v("box_x_min", s.box_x_min);
    v("box_x_max", s.box_x_max);
    v("point_threshold", s.point_threshold);
    v("confirm_frames", s.confirm_frames);
    v("exit_distance", s.exit_distance);
  }
  void validate() const;
};

/// Per-frame end-of-row decision.
struct EndOfRowResult {
  bool end_detected = false;  ///< confirmed: the rows end ahead (or have ended)
  double confidence = 0.0;    ///< [0, 1]
  /// [m] estimated distance along x from the base to the row end (the last plants), when known;
  /// negative once the base has passed it.
  std::optional<double> distance_to_end;
  int box_points = 0;          ///< points counted in the look-ahead box this frame
};

/// End-of-row detector. Stateful (confirmation counter); update() never throws.
class EndOfRowDetector {
 public:
  explicit EndOfRowDetector(const EndOfRowConfig& config = {});
  /// One frame: the 3D cloud in the base frame (raw heights; may be empty for a planar scan, in
  /// which case `points_base` 2D points are counted instead), and the tracker's output.
  EndOfRowResult update(const core::PointCloud& cloud_base,
                        std::span<const Eigen::Vector2f> points_base,
                        const track::RowTracking& tracking);
  void reset();
  const EndOfRowConfig& config() const { return config_; }

 private:
  EndOfRowConfig config_;
  int positives_ = 0;
};

}  // namespace rownav::navigate
