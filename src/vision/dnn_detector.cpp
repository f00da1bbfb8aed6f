/// @file dnn_detector.cpp YOLO-style detector through cv::dnn: load, forward, decode, NMS.
#include "rownav/vision/dnn_detector.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <stdexcept>
#include <string_view>

namespace rownav::vision {
namespace {

constexpr int kBoxColumns = 5;  // centre u, centre v, width, height, objectness
constexpr int kBlankSide = 64;  // [px] the blank image of the load-time check

/// Throws a one-line std::runtime_error naming `path` unless it is a readable regular file.
void require_file(const std::string& path, std::string_view what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path, std::ios::binary))
    throw std::runtime_error("dnn_detector: " + path + ": cannot read the " + std::string(what));
}

/// Darknet weights: a header (3 int32 + a 64-bit count) and whole float32 values. OpenCV 4.6
/// reads a truncated file without a word, so its length is checked here (a file cut at a float
/// boundary still passes: OpenCV does not tell how many floats the cfg needs).
void require_weights_layout(const std::string& path) {
  constexpr std::uintmax_t kHeaderBytes = 3 * 4 + 8;
  constexpr std::uintmax_t kFloatBytes = 4;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size <= kHeaderBytes || (size - kHeaderBytes) % kFloatBytes != 0)
    throw std::runtime_error("dnn_detector: " + path +
                             ": not Darknet weights (a 20-byte header, then float32 values)");
}

/// cv::Exception's short message on one line.
std::string one_line(const cv::Exception& e) {
  std::string s = e.err.empty() ? std::string(e.what()) : e.err;
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() &&
         std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         });
}

/// Decodes the rows of one YOLO output into boxes of an image of size (w, h).
void decode(const cv::Mat& out, const DnnDetectorConfig& c, int w, int h,
            std::vector<cv::Rect2d>& boxes, std::vector<float>& scores, std::vector<int>& ids) {
  const int cols = out.size[out.dims - 1];
  const cv::Mat rows = out.reshape(1, static_cast<int>(out.total() / cols));
  const double su = c.normalised_boxes ? w : double(w) / c.input_width;
  const double sv = c.normalised_boxes ? h : double(h) / c.input_height;
  for (int r = 0; r < rows.rows; ++r) {
    const float* p = rows.ptr<float>(r);
    const float* best = std::max_element(p + kBoxColumns, p + cols);
    float score = *best * (c.multiply_objectness ? p[4] : 1.0f);
    if (!(score >= c.confidence_threshold)) continue;
    const double bw = p[2] * su, bh = p[3] * sv;
    boxes.emplace_back(p[0] * su - 0.5 * bw, p[1] * sv - 0.5 * bh, bw, bh);
    scores.push_back(score);
    ids.push_back(static_cast<int>(best - (p + kBoxColumns)));
  }
}

/// Indices kept by non-maximum suppression within each class (boxes of different crops may
/// overlap; OpenCV 4.6 has no batched NMS).
std::vector<int> nms_per_class(const std::vector<cv::Rect2d>& boxes,
                               const std::vector<float>& scores, const std::vector<int>& ids,
                               const DnnDetectorConfig& c) {
  std::vector<int> keep;
  std::vector<int> classes = ids;
  std::sort(classes.begin(), classes.end());
  classes.erase(std::unique(classes.begin(), classes.end()), classes.end());
  for (const int k : classes) {
    std::vector<int> index;
    std::vector<cv::Rect2d> b;
    std::vector<float> s;
    for (std::size_t i = 0; i < ids.size(); ++i)
      if (ids[i] == k) {
        index.push_back(static_cast<int>(i));
        b.push_back(boxes[i]);
        s.push_back(scores[i]);
      }
    std::vector<int> kept;
    cv::dnn::NMSBoxes(b, s, static_cast<float>(c.confidence_threshold),
                      static_cast<float>(c.nms_threshold), kept);
    for (const int j : kept) keep.push_back(index[static_cast<std::size_t>(j)]);
  }
  return keep;
}

}  // namespace

struct DnnDetector::Impl {
  cv::dnn::Net net;
  std::vector<std::string> outputs;
};

void DnnDetectorConfig::validate() const {
  core::check(!model_path.empty(), "model_path", "must name a .cfg or .onnx file");
  core::check(ends_with(model_path, ".onnx") || !weights_path.empty(), "weights_path",
              "a Darknet .cfg needs its .weights file");
  core::check_positive(input_width, "input_width");
  core::check_positive(input_height, "input_height");
  core::check_positive(pixel_scale, "pixel_scale");
  core::check_range(confidence_threshold, 0.0, 1.0, "confidence_threshold");
  core::check_range(nms_threshold, 0.0, 1.0, "nms_threshold");
}

DnnDetector::DnnDetector(const DnnDetectorConfig& config)
    : impl_(std::make_unique<Impl>()), config_(config) {
  config_.validate();
  const bool onnx = ends_with(config_.model_path, ".onnx");
  require_file(config_.model_path, onnx ? "ONNX model" : "Darknet cfg");
  if (!onnx) {
    require_file(config_.weights_path, "Darknet weights");
    require_weights_layout(config_.weights_path);
  }
  const std::string& named = onnx ? config_.model_path : config_.weights_path;
  try {
    impl_->net = onnx ? cv::dnn::readNetFromONNX(config_.model_path)
                      : cv::dnn::readNetFromDarknet(config_.model_path, config_.weights_path);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("dnn_detector: " + config_.model_path + ": not a valid " +
                             (onnx ? "ONNX model" : "Darknet model") + " (" + one_line(e) + ")");
  }
  if (impl_->net.empty())
    throw std::runtime_error("dnn_detector: " + config_.model_path + ": the model has no layers");
  impl_->outputs = impl_->net.getUnconnectedOutLayersNames();
  core::CameraImage blank;  // a first run checks that the network runs and counts its classes
  blank.intrinsics.width = blank.intrinsics.height = kBlankSide;
  blank.rgb.assign(std::size_t(kBlankSide) * kBlankSide * 3, 0);
  std::vector<Detection> ignored;
  try {
    run(blank, ignored);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("dnn_detector: " + named + ": the network does not run (" +
                             one_line(e) + ")");
  }
  if (class_count_ <= 0)
    throw std::runtime_error("dnn_detector: " + config_.model_path +
                             ": output is not YOLO rows (centre, size, objectness, classes)");
}

DnnDetector::~DnnDetector() = default;
DnnDetector::DnnDetector(DnnDetector&&) noexcept = default;
DnnDetector& DnnDetector::operator=(DnnDetector&&) noexcept = default;

void DnnDetector::run(const core::CameraImage& image, std::vector<Detection>& out) {
  out.clear();
  const cv::Mat rgb(image.height(), image.width(), CV_8UC3,
                    const_cast<std::uint8_t*>(image.rgb.data()));
  const cv::Mat blob = cv::dnn::blobFromImage(rgb, config_.pixel_scale,
                                              cv::Size(config_.input_width, config_.input_height),
                                              cv::Scalar(), config_.swap_rb, false);
  impl_->net.setInput(blob);
  std::vector<cv::Mat> outs;
  impl_->net.forward(outs, impl_->outputs);
  std::vector<cv::Rect2d> boxes;
  std::vector<float> scores;
  std::vector<int> ids;
  class_count_ = 0;
  for (const cv::Mat& o : outs) {
    if (o.dims < 2 || o.type() != CV_32F || o.size[o.dims - 1] <= kBoxColumns) continue;
    class_count_ = std::max(class_count_, o.size[o.dims - 1] - kBoxColumns);
    decode(o, config_, image.width(), image.height(), boxes, scores, ids);
  }
  const std::vector<int> keep = nms_per_class(boxes, scores, ids, config_);
  for (const int k : keep) {
    const cv::Rect2d& b = boxes[static_cast<std::size_t>(k)];
    Detection d;
    d.u_min = static_cast<float>(std::max(0.0, b.x));
    d.v_min = static_cast<float>(std::max(0.0, b.y));
    d.u_max = static_cast<float>(std::min<double>(image.width(), b.x + b.width));
    d.v_max = static_cast<float>(std::min<double>(image.height(), b.y + b.height));
    d.class_id = ids[static_cast<std::size_t>(k)];
    d.score = scores[static_cast<std::size_t>(k)];
    out.push_back(d);
  }
}

void DnnDetector::detect(const core::CameraImage& image, std::vector<Detection>& out) {
  out.clear();
  if (!image.valid()) return;
  try {
    run(image, out);
  } catch (...) {  // per-frame code does not throw: no boxes this frame
    out.clear();
  }
}

}  // namespace rownav::vision
