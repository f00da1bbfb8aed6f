#pragma once
/// @file scan_scale_match.hpp The odometry's distance scale between two LiDAR frames: the
/// frame at the end of a straight stretch is moved back along the odometry's own translation,
/// scaled by s, and s is the one that lays its points best on the first frame's (a truncated
/// distance field, searched coarse to fine). Bertoglio 2023 (003_25dc0df51a1e5faf.txt sec. II-A)
/// calibrates its skid-steer correction factor alpha off-line; issue 11 asks for it online
/// "or from the LiDAR": this is the LiDAR's measurement of it. Only the scale along the
/// odometry's translation is searched: heading comes from the gyro, and one free parameter
/// cannot slide into the side-to-side freedom of a corridor.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"

namespace rownav::localize {

/// How the two frames are compared.
struct ScanScaleMatchConfig {
  /// [m] cell of the distance field of the first frame's points; the coarse search moves the
  /// second frame by about one cell per step (rownav)
  double resolution = 0.04;
  /// [m] a point further than this from every point of the other frame counts as this far:
  /// what one frame sees and the other does not (occlusion, range) weighs the same whatever s
  double truncation = 0.3;
  /// [-] s is searched in [1 - e, 1 + e]: the odometry's distance error a drive train can have
  /// (Bertoglio 2023's robot: 10 %; tyre pressure, belt tension, slip)
  double max_scale_error = 0.25;
  /// [-] the cost must rise by this share of its minimum one coarse step either side of it; a
  /// flatter minimum is a stretch that repeats along the motion (a solid hedge) and says
  /// nothing about the distance
  double min_contrast = 0.01;
  /// [-] share of the second frame's points within truncation / 2 of the first frame's at the
  /// best s: less is two views that do not overlap
  double min_overlap = 0.5;
  int min_points = 30;  ///< [-] fewer points in either frame: no match
  /// [m] points farther from the robot are not used: the distance field's size (and memory)
  /// stays bounded whatever the sensor's reach (24 m square at most: 1.4 MB), and far returns
  /// are too sparse to place (rownav)
  double max_range = 12.0;
  /// [-] a second valley of the coarse cost within this share of the cost's range of the best
  /// one, behind a ridge higher than that share, makes the match ambiguous: plants or trunks
  /// repeating along the row closer than the odometry's error over the baseline (rownav)
  double ambiguity = 0.25;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("resolution", s.resolution);
    v("truncation", s.truncation);
    v("max_scale_error", s.max_scale_error);
    v("min_contrast", s.min_contrast);
    v("min_overlap", s.min_overlap);
    v("min_points", s.min_points);
    v("ambiguity", s.ambiguity);
    v("max_range", s.max_range);
  }
  void validate() const;
};

/// Why a match gave no scale.
enum class ScaleMatchStatus : std::uint8_t {
  ok,
  too_few_points,  ///< fewer than min_points in a frame
  no_motion,       ///< the odometry moved less than a few field cells
  flat,            ///< the cost hardly rises away from its minimum (contrast)
  no_overlap,      ///< the frames do not show the same things
  at_bound,        ///< the minimum is at the edge of the searched scales
  ambiguous        ///< two valleys (repeating plants)
};

/// The outcome of one comparison.
struct ScanScaleMatch {
  ScaleMatchStatus status = ScaleMatchStatus::too_few_points;
  double scale = 1.0;     ///< [-] true translation / odometry translation (ok only)
  double contrast = 0.0;  ///< [-] relative rise of the cost one coarse step from the minimum
  double overlap = 0.0;   ///< [-] share of points within truncation / 2 at the best scale
};

/// Scale s such that T(s) = (s t, theta) of `T_first_second` = (t, theta) maps the second
/// frame's points best onto the first's. Points are in each frame's base frame. Never throws;
/// non-finite points are skipped.
ScanScaleMatch match_scan_scale(const std::vector<Eigen::Vector2f>& first,
                                const std::vector<Eigen::Vector2f>& second,
                                const core::Pose2& T_first_second,
                                const ScanScaleMatchConfig& config);

}  // namespace rownav::localize
