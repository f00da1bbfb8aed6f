/// @file excess_green_detector.cpp ExG segmentation, nearest colour signature, components.
#include "rownav/vision/excess_green_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace rownav::vision {
namespace {

constexpr double kExgMin = -1.0;  // ExG = 2g - r - b of chromaticities lies in [-1, 2]
constexpr double kExgSpan = 3.0;
constexpr double kByteMax = 255.0;
constexpr double kMaxRgbSum = 3.0 * kByteMax;
constexpr std::uint8_t kNoClass = std::numeric_limits<std::uint8_t>::max();
constexpr int kMaxClasses = 254;  // class k is stored as k + 1 in a byte, 0 = background

std::uint8_t exg_to_byte(double exg) {
  return static_cast<std::uint8_t>(
      std::lround(std::clamp((exg - kExgMin) / kExgSpan, 0.0, 1.0) * kByteMax));
}

/// Index of the class whose chromaticity is nearest (r, g), kNoClass beyond max_distance.
std::uint8_t nearest_class(const std::vector<ExgClassConfig>& classes, double r, double g,
                           double max_distance) {
  std::uint8_t best = kNoClass;
  double best_d2 = max_distance * max_distance;
  for (std::size_t k = 0; k < classes.size(); ++k) {
    const double dr = r - classes[k].chromaticity.x(), dg = g - classes[k].chromaticity.y();
    const double d2 = dr * dr + dg * dg;
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = static_cast<std::uint8_t>(k);
    }
  }
  return best;
}

/// A box around pixel rectangle [u0, u1) x [v0, v1) grown by the margin, clamped to the image.
Detection make_box(int u0, int v0, int u1, int v1, int pixels, int k, const cv::Mat& mask,
                   int margin) {
  Detection d;
  d.u_min = static_cast<float>(std::max(0, u0 - margin));
  d.v_min = static_cast<float>(std::max(0, v0 - margin));
  d.u_max = static_cast<float>(std::min(mask.cols, u1 + margin));
  d.v_max = static_cast<float>(std::min(mask.rows, v1 + margin));
  d.class_id = k;
  d.score = static_cast<float>(pixels) / static_cast<float>((u1 - u0) * (v1 - v0));
  return d;
}

/// Per tile x tile cell of component `id`'s bounding rect, the box of its pixels in the cell.
void tile_boxes(const cv::Mat& labels, int id, const cv::Rect& r, int k,
                const ExcessGreenDetectorConfig& c, std::vector<Detection>& out) {
  const int nu = (r.width + c.tile_px - 1) / c.tile_px, nv = (r.height + c.tile_px - 1) / c.tile_px;
  struct Cell {
    int u0 = std::numeric_limits<int>::max(), v0 = std::numeric_limits<int>::max(), u1 = 0, v1 = 0,
        n = 0;
  };
  std::vector<Cell> cells(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv));
  for (int v = r.y; v < r.y + r.height; ++v) {
    const int* row = labels.ptr<int>(v);
    for (int u = r.x; u < r.x + r.width; ++u) {
      if (row[u] != id) continue;
      Cell& cell =
          cells[static_cast<std::size_t>((v - r.y) / c.tile_px * nu + (u - r.x) / c.tile_px)];
      cell.u0 = std::min(cell.u0, u);
      cell.v0 = std::min(cell.v0, v);
      cell.u1 = std::max(cell.u1, u + 1);
      cell.v1 = std::max(cell.v1, v + 1);
      ++cell.n;
    }
  }
  for (const Cell& cell : cells)
    if (cell.n > 0)
      out.push_back(
          make_box(cell.u0, cell.v0, cell.u1, cell.v1, cell.n, k, labels, c.box_margin_px));
}

/// Boxes of the connected components of `mask` (8-connected) into out, with class `k`.
void components_to_boxes(const cv::Mat& mask, int k, const ExcessGreenDetectorConfig& c,
                         std::vector<Detection>& out) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  for (int i = 1; i < n; ++i) {  // 0 is the background
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    if (area < c.min_area_px) continue;
    const cv::Rect r(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                     stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    if (c.tile_px > 0 && (r.width > c.tile_px || r.height > c.tile_px))
      tile_boxes(labels, i, r, k, c, out);
    else
      out.push_back(
          make_box(r.x, r.y, r.x + r.width, r.y + r.height, area, k, mask, c.box_margin_px));
  }
}

}  // namespace

void ExgClassConfig::validate() const {
  core::check(
      chromaticity.allFinite() && (chromaticity.array() >= 0.0).all() && chromaticity.sum() <= 1.0,
      "chromaticity", "r, g must be >= 0 with r + g <= 1");
}

void ExcessGreenDetectorConfig::validate() const {
  core::check(!classes.empty() && classes.size() <= static_cast<std::size_t>(kMaxClasses),
              "classes", "must list 1 to 254 classes");
  for (const auto& k : classes) core::validate_nested(k, "classes");
  core::check_positive(max_class_distance, "max_class_distance");
  core::check_range(exg_threshold, kExgMin, kExgMin + kExgSpan, "exg_threshold");
  core::check_range(min_brightness, 0.0, 1.0, "min_brightness");
  core::check_positive(open_kernel_px, "open_kernel_px");
  core::check_positive(close_kernel_px, "close_kernel_px");
  core::check_positive(min_area_px, "min_area_px");
  core::check_non_negative(box_margin_px, "box_margin_px");
  core::check_non_negative(tile_px, "tile_px");
}

ExcessGreenDetector::ExcessGreenDetector(const ExcessGreenDetectorConfig& config)
    : config_(config) {
  config_.validate();
}

void ExcessGreenDetector::chromaticity(const core::CameraImage& image) {
  const std::size_t n = image.rgb.size() / 3;
  exg_.resize(n);
  exg8_.resize(n);
  pixel_class_.resize(n);
  nearest_.resize(n);
  const double dark = config_.min_brightness * kMaxRgbSum;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = image.rgb.data() + 3 * i;
    const double sum = double(p[0]) + double(p[1]) + double(p[2]);
    if (sum < dark || sum <= 0.0) {  // no reliable chromaticity
      exg_[i] = std::numeric_limits<float>::quiet_NaN();
      exg8_[i] = 0;
      nearest_[i] = kNoClass;
      continue;
    }
    const double r = p[0] / sum, g = p[1] / sum, b = p[2] / sum;
    exg_[i] = static_cast<float>(2.0 * g - r - b);  // Woebbecke 1995 excess green
    exg8_[i] = exg_to_byte(exg_[i]);
    nearest_[i] = nearest_class(config_.classes, r, g, config_.max_class_distance);
  }
}

void ExcessGreenDetector::detect(const core::CameraImage& image, std::vector<Detection>& out) {
  out.clear();
  if (!image.valid()) return;
  const std::size_t n = image.rgb.size() / 3;
  chromaticity(image);
  try {
    double t = config_.exg_threshold;
    if (config_.otsu) {
      cv::Mat src(image.height(), image.width(), CV_8UC1, exg8_.data()), dst;
      const double t8 = cv::threshold(src, dst, 0.0, kByteMax, cv::THRESH_BINARY | cv::THRESH_OTSU);
      t = std::max(t, kExgMin + kExgSpan * t8 / kByteMax);
    }
    last_threshold_ = t;
    for (std::size_t i = 0; i < n; ++i)
      pixel_class_[i] = (exg_[i] > t && nearest_[i] != kNoClass) ? nearest_[i] + 1 : 0;
    const cv::Mat classes(image.height(), image.width(), CV_8UC1, pixel_class_.data());
    const cv::Mat open = cv::getStructuringElement(
        cv::MORPH_ELLIPSE, cv::Size(config_.open_kernel_px, config_.open_kernel_px));
    const cv::Mat close = cv::getStructuringElement(
        cv::MORPH_ELLIPSE, cv::Size(config_.close_kernel_px, config_.close_kernel_px));
    cv::Mat mask;
    for (std::size_t k = 0; k < config_.classes.size(); ++k) {
      cv::compare(classes, cv::Scalar(static_cast<double>(k + 1)), mask, cv::CMP_EQ);
      cv::morphologyEx(mask, mask, cv::MORPH_OPEN, open);
      cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, close);
      components_to_boxes(mask, static_cast<int>(k), config_, out);
    }
  } catch (...) {  // cv::Exception, bad_alloc: per-frame code does not throw
    out.clear();   // no boxes this frame
  }
}

}  // namespace rownav::vision
