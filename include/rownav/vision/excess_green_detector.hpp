#pragma once
/// @file excess_green_detector.hpp The default image crop detector, with nothing but Debian's
/// OpenCV: excess green ExG = 2g - r - b on chromaticity-normalised rgb (Woebbecke 1995, the
/// classical vegetation index of crop-row vision, Hamuda 2016's survey cited by Emmi 2021,
/// 002_806e72d300173f73.txt), an Otsu (or fixed) threshold, each vegetation pixel given the
/// nearest crop colour signature (mean chromaticity prototypes: two crops side by side are told
/// apart by their colour, Emmi 2021's reason for the camera), morphology per class and connected
/// components as boxes. Stands in for the paper's YOLOv3 boxes.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/vision/detection.hpp"

namespace rownav::vision {

/// One plant class the detector knows by its colour signature.
struct ExgClassConfig {
  /// [-] mean chromaticity (r, g) = (R, G) / (R + G + B) of the class's plants (b = 1 - r - g)
  Eigen::Vector2d chromaticity{0.362, 0.534};

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("chromaticity", s.chromaticity);
  }
  void validate() const;
};

/// Configuration of the excess-green detector.
struct ExcessGreenDetectorConfig {
  /// Plant classes, in class_id order. Defaults: the simulated camera's target crop
  /// (yellow-green), the neighbouring field's crop (blue-green) and weeds (rownav:
  /// sim::PinholeCameraConfig's crop_colour, other_crop_colour, weed_colour)
  std::vector<ExgClassConfig> classes{{{0.362, 0.534}}, {{0.196, 0.429}}, {{0.309, 0.464}}};
  /// [-] a pixel farther than this in (r, g) from every class is not a plant (rownav)
  double max_class_distance = 0.08;
  /// threshold ExG by Otsu's method per image (Otsu 1979; at least exg_threshold). Off by
  /// default: chromaticity already removes the brightness, and with two crops of different
  /// greenness in view Otsu's two-mode split can fall between the crops (rownav, measured)
  bool otsu = false;
  /// [-] ExG threshold; with Otsu, the lowest threshold accepted (an image without plants must
  /// not split its soil noise in two). Soil ~0, the bluest default crop ~0.29 (rownav)
  double exg_threshold = 0.15;
  /// [-] darker pixels (R + G + B below this x 765) have no reliable chromaticity: not plants
  double min_brightness = 0.04;
  int open_kernel_px = 3;   ///< [px] morphological opening per class: drops speckle (rownav)
  int close_kernel_px = 5;  ///< [px] closing: joins the leaves of one plant (rownav)
  int min_area_px = 12;     ///< [px] smaller components are noise (rownav, 320 x 240 images)
  int box_margin_px = 1;    ///< [px] each box grows by this much (laser points on leaf edges)
  /// [px] a component wider or taller than this (plants of a row touching in the image) gives
  /// one box per tile x tile cell, hugging its pixels in the cell, so that a row seen in
  /// perspective is not one box over the soil and weeds between the rows; 0: one box each (rownav)
  int tile_px = 24;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("classes", s.classes);
    v("max_class_distance", s.max_class_distance);
    v("otsu", s.otsu);
    v("exg_threshold", s.exg_threshold);
    v("min_brightness", s.min_brightness);
    v("open_kernel_px", s.open_kernel_px);
    v("close_kernel_px", s.close_kernel_px);
    v("min_area_px", s.min_area_px);
    v("box_margin_px", s.box_margin_px);
    v("tile_px", s.tile_px);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Excess-green segmentation + connected components. Box score: the share of the box's pixels
/// that belong to the component. Not thread-safe (keeps its buffers).
class ExcessGreenDetector : public ImageDetector {
 public:
  explicit ExcessGreenDetector(const ExcessGreenDetectorConfig& config = {});
  void detect(const core::CameraImage& image, std::vector<Detection>& out) override;
  /// [-] the ExG threshold the last detect() used (Otsu's, or the configured one).
  double last_threshold() const { return last_threshold_; }
  const ExcessGreenDetectorConfig& config() const { return config_; }

 private:
  /// ExG, its byte for Otsu and the nearest class of every pixel.
  void chromaticity(const core::CameraImage& image);

  ExcessGreenDetectorConfig config_;
  double last_threshold_ = 0.0;
  std::vector<float> exg_;                 // per pixel, NaN for dark pixels
  std::vector<std::uint8_t> exg8_;         // ExG mapped to 0..255 for Otsu
  std::vector<std::uint8_t> nearest_;      // nearest class per pixel, 255: none
  std::vector<std::uint8_t> pixel_class_;  // 0: not a plant, k + 1: class k
};

}  // namespace rownav::vision
