#pragma once
/// @file ground_cover.hpp How tall the vegetation is that the robot drives through, measured on
/// the ground it has just driven over, so that the obstacle stop can tell ground cover from an
/// obstacle (issue 10: "inter-row weeds below the crop height slow the robot but do not stop
/// it; a real obstacle (a person, a box, a post in the corridor) still stops it"). A fixed
/// height threshold cannot hold for every field: grass and weeds in a corridor are 0.1-0.6 m
/// tall, and a threshold above the tallest would hide a low box in a clean corridor. The
/// estimate comes from beside and behind the robot (what it has driven through), never from the
/// stop box ahead, so an object ahead cannot raise its own threshold.
#include <Eigen/Core>
#include <deque>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/ground.hpp"

namespace rownav::navigate {

/// Ground-cover estimate parameters.
struct GroundCoverConfig {
  bool enabled = true;  ///< false: the obstacle band's min_height alone decides
  /// [m] tallest ground cover: points higher than this are always obstacles (a standing person's
  /// trunk, a post, a machine), whatever the cover
  double cap = 0.8;
  double margin = 0.1;  ///< [m] an obstacle rises this far above the measured cover
  /// [m] lowest cover point: above the ground's roughness and its estimate's noise (rownav's
  /// fields: roughness up to 0.05 m)
  double floor = 0.15;
  double quantile = 0.98;  ///< [-] of the cover points' heights in a frame: the tallest tops
  /// [m] region from this far behind the base origin to the front (a LiDAR on a mast does not
  /// see low cover within ~1.5 m of itself: an OS1-16 at 0.75 m sees 0.3 m high from 1.5 m on)
  double behind = 4.0;
  double side = 0.15;   ///< [m] region reaches this far beside the footprint
  int min_points = 10;  ///< [-] fewer cover points in a frame: that frame saw no cover
  int frames = 30;      ///< [-] the cover is the median over this many frames (3 s at 10 Hz)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("cap", s.cap);
    v("margin", s.margin);
    v("floor", s.floor);
    v("quantile", s.quantile);
    v("behind", s.behind);
    v("side", s.side);
    v("min_points", s.min_points);
    v("frames", s.frames);
  }
  void validate() const {
    core::check_positive(cap, "cap");
    core::check_non_negative(margin, "margin");
    core::check(floor >= 0.0 && floor < cap, "floor", "must be >= 0 and < cap");
    core::check_range(quantile, 0.0, 1.0, "quantile");
    core::check_non_negative(behind, "behind");
    core::check_non_negative(side, "side");
    core::check_positive(min_points, "min_points");
    core::check_positive(frames, "frames");
  }
};

/// The footprint the region is drawn around (base frame).
struct CoverRegion {
  double base_to_front = 0.45;  ///< [m]
  double half_width = 0.3;      ///< [m]
};

/// Median over recent frames of the tops of the vegetation beside and behind the robot.
class GroundCoverEstimator {
 public:
  explicit GroundCoverEstimator(const GroundCoverConfig& config = {});
  /// One 3D sweep (base frame) and its ground: heights in [floor, cap] inside the region are
  /// cover. Never throws; non-finite points are skipped.
  void update(const core::PointCloud& cloud_base, const preprocess::GroundEstimator& ground,
              const CoverRegion& region);
  /// [m] measured cover height (0: none seen).
  double cover() const { return cover_; }
  /// [m] lowest obstacle height: cover + margin, within [min_height, cap]; min_height when
  /// disabled or without cover.
  double obstacle_min_height(double min_height) const;
  /// Forgets the history. NavStack keeps the cover across corridors and turns and forgets it
  /// only on a new mission (NavStack::restart_mission: perhaps another field).
  void reset();

 private:
  GroundCoverConfig config_;
  std::vector<float> heights_;  // reused per frame
  std::deque<double> history_;
  double cover_ = 0.0;
};

}  // namespace rownav::navigate
