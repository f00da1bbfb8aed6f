#pragma once
/// @file trunk_centres.hpp Tree / vine trunks as points: the compact clusters of a low height band.
///
/// Lan 2021 (001_b5f4b55a1b95775a.txt Fig. 1) finds the trunks of a grape row in the height band
/// between the ground and the canopy; under an orchard's crowns the same band holds only trunks,
/// posts and the odd weed. Each trunk is a small cluster of band points; its centre lies on the
/// row's centre line whatever the crown does (a crown face can stand 0.5-2 m in front of it).
#include <Eigen/Core>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/detect/dbscan.hpp"

namespace rownav::detect {

/// Parameters of the trunk band clustering. Defaults: orchards (sim/orchard.hpp: trunks 0.1-0.3 m
/// thick, crowns from 0.8 m up; weeds of the `some` level below 0.25 m).
struct TrunkCentresConfig {
  /// [m] height above the ground, bottom of the trunk band: above grass and low weeds
  /// (rownav weeds `some` reach 0.25 m)
  double z_min = 0.3;
  /// [m] height above the ground, top of the trunk band: below the lowest branches (orchard
  /// trunks 0.5-1 m to the crown; a vine's cordon from 0.3 m)
  double z_max = 0.7;
  double max_range = 12.0;  ///< [m] band points farther from the robot are ignored (few rings)
  double cluster_eps = 0.25;  ///< [m] DBSCAN radius: points of one trunk lie closer (Ester 1996)
  int min_points = 2;  ///< [-] fewer points: not a trunk (a 0.15 m trunk at 10 m gives 2-3)
  /// [m] largest distance of a cluster point from its centre: a 0.3 m trunk plus beam spread;
  /// larger clusters are low branches, bushes or walls
  double max_radius = 0.35;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("z_min", s.z_min);
    v("z_max", s.z_max);
    v("max_range", s.max_range);
    v("cluster_eps", s.cluster_eps);
    v("min_points", s.min_points);
    v("max_radius", s.max_radius);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// One trunk candidate in the base frame.
struct TrunkCentre {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< [m] mean of its band points (x, y)
  int points = 0;                                     ///< band points of the cluster
};

/// Finds trunk centres in a 3D cloud (base frame). Reusable buffers: one instance per thread.
class TrunkCentres {
 public:
  explicit TrunkCentres(const TrunkCentresConfig& config = {});
  /// Trunks of `cloud`. `heights`: each point's height above the estimated ground (same order
  /// as cloud.points); empty: the base z is used (ground flat at z = 0, as Lan 2021 assumes).
  /// Non-finite points are skipped. Never throws (bad input gives no trunks).
  const std::vector<TrunkCentre>& find(const core::PointCloud& cloud,
                                       std::span<const float> heights);
  const TrunkCentresConfig& config() const { return config_; }

 private:
  TrunkCentresConfig config_;
  Dbscan dbscan_;
  std::vector<Eigen::Vector2f> band_;
  std::vector<TrunkCentre> trunks_;
  std::vector<Eigen::Vector2d> sum_;
  std::vector<int> count_;
};

}  // namespace rownav::detect
