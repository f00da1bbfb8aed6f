#pragma once
/// @file trunk_offset.hpp Row offsets from trunk evidence: the true row line of a trellised crop
/// is its trunk / post line, but a LiDAR mounted below the canopy top sees only the corridor-side
/// face of each canopy wall, so a line fitted to canopy points sits up to a canopy half width too
/// close to the robot (the denser the canopy, the larger the bias). Under the canopy, in a low
/// height band between the ground and the cordon, only trunks, posts and the cordon stand, all on
/// the row line (Lan 2022, 001_b5f4b55a1b95775a.txt Fig. 1 finds the trunks in such a band).
///
/// Once the common row direction and the canopy rows are known, each row's offset is
/// re-estimated as the median perpendicular offset of the band points near it (robust to the
/// odd weed or shoot tip; a minimum count), else the canopy fit is kept. Needs the 3D cloud:
/// with 2D points only (scans, the corn data) nothing changes. Ground assumed flat around the
/// robot (base z = height above the ground under the robot), as Lan 2022 does.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::detect {

/// Parameters of the trunk re-estimation of row offsets. Defaults: vineyards (VSP trellis, cordon
/// 0.3 m and up, canopy from ~5 cm above the cordon; the preprocessing keeps z >= 0.2 m).
struct TrunkOffsetConfig {
  bool enabled = true;  ///< re-estimate row offsets from the trunk band of the 3D cloud
  double z_min = 0.15;  ///< [m] base z, bottom of the trunk band: above ground and grass
  /// [m] base z, top of the trunk band: about the lowest canopy (vineyard cordon 0.3-0.6 m, on
  /// the row line; canopy from 0.05 m above it); mostly trunks, posts, cordons and the lowest
  /// wire below. Measured on the simulated vineyards: 0.3 keeps too few points, 0.4 is best.
  double z_max = 0.4;
  /// [m] search window from the canopy line towards the robot (the trunk line lies behind the
  /// visible canopy face, never much in front of it)
  double inner = 0.1;
  /// [m] search window from the canopy line away from the robot: a canopy half width plus
  /// margin (0.5 m walls: 0.25 m)
  double outer = 0.4;
  /// [m] second pass: half width of the window around the first median (drops weeds and shoot
  /// tips caught at the window's edges)
  double half_width = 0.1;
  int min_points = 6;        ///< [-] fewer band points in the window: keep the canopy fit
  double max_range = 8.0;    ///< [m] band points farther from the robot are ignored
  double max_shift = 0.35;   ///< [m] larger moves from the canopy line are rejected

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("z_min", s.z_min);
    v("z_max", s.z_max);
    v("inner", s.inner);
    v("outer", s.outer);
    v("half_width", s.half_width);
    v("min_points", s.min_points);
    v("max_range", s.max_range);
    v("max_shift", s.max_shift);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Trunk-band re-estimation of row offsets. Holds buffers: one instance per detector.
class TrunkOffset {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit TrunkOffset(const TrunkOffsetConfig& config = {});

  /// Collects the trunk band of `cloud` (finite points, z in [z_min, z_max], within max_range)
  /// as offsets along the row normal n = (-d.y, d.x) of unit row direction `d`. Returns the
  /// number of band points; 0 when disabled.
  std::size_t collect(const core::PointCloud& cloud, const Eigen::Vector2d& d);
  /// The trunk line offset (along n) of the row whose canopy line lies at `canopy` along n;
  /// `canopy` itself when the band has too few points near it. Call after collect().
  double offset(double canopy);
  /// Moves row `r` (direction d, as given to collect()) onto its trunk line; its support,
  /// extent and rms stay those of the canopy fit. Returns the shift [m] along n.
  double apply(core::RowLine& r);

  const TrunkOffsetConfig& config() const { return config_; }

 private:
  TrunkOffsetConfig config_;
  Eigen::Vector2d n_ = Eigen::Vector2d::UnitY();
  std::vector<float> band_, window_;
};

}  // namespace rownav::detect
