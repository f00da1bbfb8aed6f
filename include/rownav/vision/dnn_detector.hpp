#pragma once
/// @file dnn_detector.hpp A user's own YOLO-style crop detector (Darknet cfg + weights, or ONNX)
/// run by OpenCV's DNN module (Debian's libopencv-dnn-dev): Emmi 2021
/// (002_806e72d300173f73.txt, sec. "Perception", Table 3) used YOLOv3 at 288 x 416. OpenCV
/// stays in the .cpp (pimpl).
#include <memory>
#include <string>

#include "rownav/core/config_fields.hpp"
#include "rownav/vision/detection.hpp"

namespace rownav::vision {

/// Configuration of the DNN detector. Output rows are YOLO's: centre u, centre v, width,
/// height, objectness, one score per class.
struct DnnDetectorConfig {
  std::string model_path;    ///< Darknet `.cfg` or `.onnx` file (required)
  std::string weights_path;  ///< Darknet `.weights` file (required with a `.cfg`; unused for ONNX)
  int input_width = 416;     ///< [px] network input (Emmi 2021 Table 3: YOLOv3 288 x 416)
  int input_height = 288;    ///< [px]
  double pixel_scale = 1.0 / 255.0;  ///< [-] input = byte x pixel_scale (Darknet's convention)
  bool swap_rb = false;  ///< swap R and B: images are RGB; true for a network trained on BGR
  /// [-] boxes whose best class score is lower are dropped (YOLOv3's usual 0.5)
  double confidence_threshold = 0.5;
  double nms_threshold = 0.4;  ///< [-] IoU above which the weaker box is suppressed (YOLOv3)
  /// box coordinates in [0, 1] of the input (Darknet's region / yolo layers); false: input
  /// pixels (ONNX exports of YOLOv5 and later)
  bool normalised_boxes = true;
  /// class score = objectness x class probability (ONNX YOLOv5 exports); false: the class
  /// scores already include it (OpenCV's Darknet yolo layer)
  bool multiply_objectness = false;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("model_path", s.model_path);
    v("weights_path", s.weights_path);
    v("input_width", s.input_width);
    v("input_height", s.input_height);
    v("pixel_scale", s.pixel_scale);
    v("swap_rb", s.swap_rb);
    v("confidence_threshold", s.confidence_threshold);
    v("nms_threshold", s.nms_threshold);
    v("normalised_boxes", s.normalised_boxes);
    v("multiply_objectness", s.multiply_objectness);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Runs a Darknet / ONNX YOLO detector. Not thread-safe.
class DnnDetector : public ImageDetector {
 public:
  /// Loads the model and runs it once on a blank image. Throws std::invalid_argument for a bad
  /// config, std::runtime_error (one line naming the file) when a file cannot be read, is not a
  /// model of its kind, or its network cannot run.
  explicit DnnDetector(const DnnDetectorConfig& config);
  ~DnnDetector() override;
  DnnDetector(DnnDetector&&) noexcept;
  DnnDetector& operator=(DnnDetector&&) noexcept;
  /// Boxes after confidence threshold and per-class non-maximum suppression. Does not throw.
  void detect(const core::CameraImage& image, std::vector<Detection>& out) override;
  /// [-] number of classes the network outputs (from its first run).
  int class_count() const { return class_count_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  DnnDetectorConfig config_;
  int class_count_ = 0;
  /// Forward pass of one RGB8 image (h x w) and its boxes; throws cv::Exception.
  void run(const core::CameraImage& image, std::vector<Detection>& out);
};

}  // namespace rownav::vision
