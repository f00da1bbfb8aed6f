#pragma once
/// @file camera_labeller.hpp Laser points labelled by the camera's detection boxes (Emmi 2021,
/// 002_806e72d300173f73.txt, Fig. 2b and sec. "Perception": the laser points are transformed
/// into the image frame and the points inside a bounding box of the target crop are labelled).
///
/// Rule, point by point (base frame, origin on the ground under the robot, z up):
///  1. a non-finite point is `obstacle` (the map stage drops it);
///  2. a point at most `ground_max_z` above the base plane is `ground` (soil seen through a box);
///  3. a point in front of the camera that projects into the image inside a box takes the label
///     of the box's class (`class_labels`); where boxes overlap, the highest score wins;
///  4. every other point (outside every box, behind the camera, outside the image, no image
///     yet) is `obstacle`: standing, but not a plant the camera recognised.
/// As in the paper, several laser frames are labelled from the last image (set_detections),
/// projected as if the robot had not moved since it: no motion compensation (at 0.5 m/s and a
/// new image every 0.5 s a point may be projected up to 0.25 m off).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "rownav/core/camera_image.hpp"
#include "rownav/core/config_fields.hpp"
#include "rownav/map/point_labeller.hpp"
#include "rownav/vision/detection.hpp"

namespace rownav::vision {

/// Configuration of the camera labeller.
struct CameraLabellerConfig {
  /// label of each detector class id (ids beyond the list: `obstacle`). Default: the
  /// excess-green detector's classes target crop, neighbouring crop, weed (rownav)
  std::vector<map::PointLabel> class_labels{map::PointLabel::crop, map::PointLabel::other_crop,
                                            map::PointLabel::weed};
  /// [m] points at most this high above the base plane are ground (rownav: flat ground under
  /// the robot; Emmi 2021 neglects the slope)
  double ground_max_z = 0.04;
  /// [m] points nearer than this along the optical axis are behind the camera (rownav)
  double min_depth = 0.05;
  double min_score = 0.0;  ///< [-] boxes scoring less are ignored (rownav)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("class_labels", s.class_labels);
    v("ground_max_z", s.ground_max_z);
    v("min_depth", s.min_depth);
    v("min_score", s.min_score);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// map::PointLabeller from camera detections. Never throws from label().
class CameraLabeller : public map::PointLabeller {
 public:
  explicit CameraLabeller(const CameraLabellerConfig& config = {});
  /// The boxes found in `image` (its intrinsics and T_base_camera are kept, not its pixels).
  void set_detections(const core::CameraImage& image, std::vector<Detection> detections);
  /// Runs `detector` on `image` and keeps its boxes. Does not throw.
  void set_image(const core::CameraImage& image, ImageDetector& detector);
  void label(const std::vector<Eigen::Vector3f>& points_base,
             std::vector<map::PointLabel>& labels) override;
  /// Label of one base-frame point by the rule above.
  map::PointLabel label_point(const Eigen::Vector3f& p_base) const;
  const std::vector<Detection>& detections() const { return detections_; }

 private:
  CameraLabellerConfig config_;
  bool has_image_ = false;
  core::CameraIntrinsics intrinsics_;
  Eigen::Isometry3d T_camera_base_ = Eigen::Isometry3d::Identity();
  std::vector<Detection> detections_;  // sorted by score, highest first
};

}  // namespace rownav::vision
