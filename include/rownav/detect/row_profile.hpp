#pragma once
/// @file row_profile.hpp Each detected row as a centre line plus a canopy half width (issue 10).
///
/// A detector fits a row's line to the points it sees, and a LiDAR inside a corridor sees the
/// corridor-side face of each canopy: for a thin, see-through VSP wall the fit (or its trunk
/// line, trunk_offset.hpp) is close to the centre, for an opaque canopy (a solid hedge, a real
/// photogrammetric vineyard) it sits a canopy half width in front of it. Centre-to-centre
/// spacing from such lines is the face-to-face corridor width (1.2 m instead of 1.7 m measured).
///
/// The crown of a canopy stands over its row line (a trellised vine, a hedge mound, a tree): the
/// highest points the LiDAR sees of a row mark its centre line whatever the crop, and the
/// lowest quantile of the points across the row towards the robot marks its inner face. Both
/// are measured per row in a window bounded by the neighbouring rows (so the window scales with
/// the measured spacing, no crop constant). A flat-topped box hedge shows only the top edge of
/// its inner face from below: there the crown is the face and nothing changes (unobservable
/// from inside the corridor). 2D scans carry no heights: nothing changes either.
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::detect {

/// Parameters of the row profile (rownav, issue 10).
struct RowProfileConfig {
  bool enabled = true;  ///< estimate centre_shift / half_width of every row from the 3D cloud
  /// [-] a row's crown: its points at or above this quantile of their heights. From inside a
  /// corridor the LiDAR sees an opaque crown only at grazing angles, by ~1-2 % of the row's points
  /// (the face below takes the rest; measured on the solid-hedge fields of bench/fields/); the
  /// top percent, not a single highest point (a shoot tip or noise)
  double crown_quantile = 0.99;
  /// [-] a row's inner face: this quantile of its points' distances across the row, counted
  /// from the robot (robust to the odd weed or shoot in front of the wall)
  double face_quantile = 0.05;
  /// [-] window towards the robot: this fraction of the gap to the neighbouring row on that side
  /// (the corridor half width for the followed rows would reach the weeds in its middle)
  double inner_ratio = 0.25;
  /// [-] window away from the robot: this fraction of the gap to the next row out (0.5: midway,
  /// the rest is that row's)
  double outer_ratio = 0.5;
  /// [-] window away from the robot when no row is detected beyond (an opaque canopy hides the
  /// next row, or it is out of range): this fraction of the gap on the robot's side. Midway, as
  /// outer_ratio: a see-through canopy is fitted at its centre, so that gap is the spacing and
  /// the next row's crown stands one gap out (1.0 took it for this row's: zoo:1:41, 2.74 m
  /// clumps, measured 4.9 m instead of 2.7 m, issue 10); an opaque canopy fitted at its face
  /// keeps its crown in the window while it is thinner than its corridor is wide (the real
  /// vineyard mesh: 0.5 m thick, 1.2 m face to face); a thicker one reads a spacing short by at
  /// most the excess
  double outer_ratio_last = 0.5;
  double max_range = 8.0;  ///< [m] points farther from the robot are ignored (sparse, noisy)
  int min_points = 8;      ///< [-] fewer points in a row's window: no profile (line = centre)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("crown_quantile", s.crown_quantile);
    v("face_quantile", s.face_quantile);
    v("inner_ratio", s.inner_ratio);
    v("outer_ratio", s.outer_ratio);
    v("outer_ratio_last", s.outer_ratio_last);
    v("max_range", s.max_range);
    v("min_points", s.min_points);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Per-row centre and half width from a 3D cloud. Holds buffers: one per pipeline.
class RowProfile {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit RowProfile(const RowProfileConfig& config = {});
  /// Sets centre_shift and half_width of every row of `obs` (rows sorted by offset) from the
  /// cloud (base frame, z up from the ground). Rows with too few points keep 0. Never throws.
  void apply(const core::PointCloud& cloud, core::RowObservation& obs);
  const RowProfileConfig& config() const { return config_; }

 private:
  struct Sample {
    float s, z;  // across the row (outwards from the robot, from the line), height
  };
  /// Window [lo, hi] across row k (outwards) from its neighbours.
  void window(const core::RowObservation& obs, std::size_t k, double& lo, double& hi) const;
  /// Median across-row position of the top crown_quantile of samples_ (NaN: none).
  float crown_offset();
  void profile(const core::PointCloud& cloud, core::RowLine& r, double lo, double hi);

  RowProfileConfig config_;
  std::vector<Sample> samples_;
  std::vector<float> buf_;
};

}  // namespace rownav::detect
