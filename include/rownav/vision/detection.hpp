#pragma once
/// @file detection.hpp Boxes an image crop detector finds (Emmi 2021, 002_806e72d300173f73.txt,
/// sec. "Perception": a YOLOv3 detector's bounding boxes, one class per crop), and the interface
/// the camera labeller takes them from.
#include <vector>

#include "rownav/core/camera_image.hpp"

namespace rownav::vision {

/// One detected object: an axis-aligned box in image pixels (u right, v down), a class and a score.
struct Detection {
  float u_min = 0.0f;  ///< [px] left edge
  float v_min = 0.0f;  ///< [px] top edge
  float u_max = 0.0f;  ///< [px] right edge (exclusive)
  float v_max = 0.0f;  ///< [px] bottom edge (exclusive)
  int class_id = 0;    ///< detector's class index (camera_labeller maps it to a point label)
  float score = 0.0f;  ///< [-] confidence in [0, 1]

  /// True when pixel point (u, v) lies inside the box.
  bool contains(double u, double v) const {
    return u >= u_min && u < u_max && v >= v_min && v < v_max;
  }
  /// [px^2] box area.
  float area() const { return (u_max - u_min) * (v_max - v_min); }
};

/// An image crop detector. detect() never throws: a bad image gives no detections.
class ImageDetector {
 public:
  virtual ~ImageDetector() = default;
  /// Replaces `out` with the boxes found in `image`.
  virtual void detect(const core::CameraImage& image, std::vector<Detection>& out) = 0;
};

}  // namespace rownav::vision
