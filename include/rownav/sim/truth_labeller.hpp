#pragma once
/// @file truth_labeller.hpp Ground-truth point labeller for the map stage (Emmi 2021,
/// 002_806e72d300173f73.txt, Fig. 2b): the class of the surface each simulated ray hit, the
/// target field told from a neighbouring one by a region, with configurable false-positive /
/// false-negative rates (a stand-in for the paper's camera detector).
#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/map/point_labeller.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Configuration of the truth labeller.
struct TruthLabellerConfig {
  /// surfaces that are the crop (vineyard: trunks and posts, as the paper's detector; row crops:
  /// the plants)
  std::vector<SurfaceClass> crop_classes{SurfaceClass::crop, SurfaceClass::canopy,
                                         SurfaceClass::trunk, SurfaceClass::post,
                                         SurfaceClass::crown};
  /// [-] chance a point that is not the target crop is labelled crop (detector false positive)
  double false_positive_rate = 0.0;
  /// [-] chance a target-crop point is not labelled crop (detector false negative; it becomes
  /// `obstacle`)
  double false_negative_rate = 0.0;
  /// only crop points inside [target_min, target_max] (world x, y) are the target crop; the
  /// others are `other_crop` (a neighbouring field)
  bool use_target_region = false;
  Eigen::Vector2d target_min = Eigen::Vector2d::Zero();  ///< [m] world, lower corner
  Eigen::Vector2d target_max = Eigen::Vector2d::Zero();  ///< [m] world, upper corner

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("crop_classes", s.crop_classes);
    v("false_positive_rate", s.false_positive_rate);
    v("false_negative_rate", s.false_negative_rate);
    v("use_target_region", s.use_target_region);
    v("target_min", s.target_min);
    v("target_max", s.target_max);
  }
  void validate() const;
};

/// Labels points from the surface classes of the rays that produced them. Not thread-safe (owns
/// its random generator).
class TruthLabeller : public map::PointLabeller {
 public:
  TruthLabeller(const TruthLabellerConfig& config, std::uint64_t seed);
  /// The truth of the next frame: robot pose and one surface class per point.
  void set_frame(const core::Pose2& T_world_base, std::vector<SurfaceClass> classes);
  /// Labels; points without a class (beyond the classes given) are `obstacle`.
  void label(const std::vector<Eigen::Vector3f>& points_base,
             std::vector<map::PointLabel>& labels) override;
  /// Error-free label of a surface class at a world position.
  map::PointLabel true_label(SurfaceClass c, const Eigen::Vector2d& world) const;

 private:
  TruthLabellerConfig config_;
  std::mt19937_64 rng_;
  core::Pose2 T_world_base_;
  std::vector<SurfaceClass> classes_;
};

}  // namespace rownav::sim
