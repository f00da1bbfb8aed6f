// A user's own Darknet detector through cv::dnn, tested with a tiny network the test writes.
#include "rownav/vision/dnn_detector.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "vision/tiny_onnx.hpp"
#include "vision/tiny_yolo.hpp"

namespace rownav::vision {
namespace {

namespace fs = std::filesystem;

class DnnDetectorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rownav_dnn_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    cfg_ = dir_ / "tiny.cfg";
    weights_ = dir_ / "tiny.weights";
    test::write_tiny_yolo(cfg_, weights_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  DnnDetectorConfig config() const {
    DnnDetectorConfig c;
    c.model_path = cfg_.string();
    c.weights_path = weights_.string();
    c.input_width = c.input_height = 32;
    return c;
  }
  fs::path dir_, cfg_, weights_;
};

/// Black image of side 128 px (a 4 x 4 grid of 32 px cells) with blocks filling some cells.
core::CameraImage grid_image(const std::vector<std::array<int, 5>>& cells) {  // cu, cv, r, g, b
  core::CameraImage img;
  img.intrinsics.width = img.intrinsics.height = 128;
  img.rgb.assign(128 * 128 * 3, 0);
  for (const auto& c : cells)
    for (int v = c[1] * 32; v < c[1] * 32 + 32; ++v)
      for (int u = c[0] * 32; u < c[0] * 32 + 32; ++u)
        for (int k = 0; k < 3; ++k)
          img.rgb[(std::size_t(v) * 128 + u) * 3 + k] = std::uint8_t(c[2 + k]);
  return img;
}

TEST_F(DnnDetectorTest, TheTinyNetworkFindsColouredBlocksInTheirGridCells) {
  DnnDetector det(config());
  EXPECT_EQ(det.class_count(), 2);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> cell(0, 3);
  for (int trial = 0; trial < 6; ++trial) {
    const int gu = cell(rng), gv = cell(rng);
    int bu = cell(rng), bv = cell(rng);
    if (bu == gu && bv == gv) bu = (bu + 2) % 4;  // two different cells
    std::vector<Detection> out;
    det.detect(grid_image({{gu, gv, 0, 255, 0}, {bu, bv, 0, 0, 255}}), out);
    ASSERT_EQ(out.size(), 2u) << "trial " << trial;
    for (const Detection& d : out) {
      const int cu = d.class_id == 0 ? gu : bu, cv = d.class_id == 0 ? gv : bv;
      EXPECT_NEAR(0.5 * (d.u_min + d.u_max), cu * 32 + 16, 2.0) << "class " << d.class_id;
      EXPECT_NEAR(0.5 * (d.v_min + d.v_max), cv * 32 + 16, 2.0) << "class " << d.class_id;
      EXPECT_NEAR(d.u_max - d.u_min, 32.0, 2.0);  // the 8 x 8 anchor of a 32 px input
      EXPECT_GT(d.score, 0.9f);
    }
    EXPECT_NE(out[0].class_id, out[1].class_id);
  }
}

/// Uniform image of side 128 px.
core::CameraImage uniform_image(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  core::CameraImage img;
  img.intrinsics.width = img.intrinsics.height = 128;
  img.rgb.resize(128 * 128 * 3);
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    img.rgb[i] = r, img.rgb[i + 1] = g, img.rgb[i + 2] = b;
  return img;
}

TEST_F(DnnDetectorTest, AnOnnxYoloModelWithPixelBoxesLoadsAndDetects) {
  const fs::path onnx = dir_ / "tiny.onnx";
  test::write_tiny_onnx(onnx);
  DnnDetectorConfig c;
  c.model_path = onnx.string();
  c.input_width = c.input_height = 32;
  c.normalised_boxes = false;    // the box is in input pixels (YOLOv5-style export)
  c.multiply_objectness = true;  // score = objectness x class
  DnnDetector det(c);
  EXPECT_EQ(det.class_count(), 2);
  std::vector<Detection> out;
  det.detect(uniform_image(0, 255, 0), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].class_id, 0);
  EXPECT_NEAR(out[0].score, 1.0f, 0.01f);
  // The 8 px box at the 32 px input's centre, scaled to the 128 px image: [48, 80).
  EXPECT_NEAR(out[0].u_min, 48.0f, 0.5f);
  EXPECT_NEAR(out[0].u_max, 80.0f, 0.5f);
  EXPECT_NEAR(out[0].v_min, 48.0f, 0.5f);
  det.detect(uniform_image(0, 0, 255), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].class_id, 1);
  det.detect(uniform_image(0, 90, 0), out);  // score 0.35^2 < 0.5
  EXPECT_TRUE(out.empty());
}

TEST_F(DnnDetectorTest, ABlackImageHasNoDetectionsAndABadImageNoneEither) {
  DnnDetector det(config());
  std::vector<Detection> out{Detection{}};
  det.detect(grid_image({}), out);
  EXPECT_TRUE(out.empty());
  core::CameraImage bad = grid_image({{0, 0, 0, 255, 0}});
  bad.rgb.resize(10);  // byte count does not match the size
  out.push_back({});
  det.detect(bad, out);
  EXPECT_TRUE(out.empty());
}

/// The message of the std::runtime_error `make` throws ("" when it does not throw).
template <class F>
std::string runtime_error_of(F&& make) {
  try {
    make();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST_F(DnnDetectorTest, AMissingFileIsAOneLineErrorNamingIt) {
  auto c = config();
  c.weights_path = (dir_ / "absent.weights").string();
  const std::string msg = runtime_error_of([&] { DnnDetector d(c); });
  EXPECT_NE(msg.find("absent.weights"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST_F(DnnDetectorTest, AGarbageCfgIsAOneLineErrorNamingIt) {
  std::ofstream(cfg_) << "this is not a darknet network\n[convolutional\nfilters=banana\n";
  const std::string msg = runtime_error_of([&] { DnnDetector d(config()); });
  EXPECT_NE(msg.find("tiny.cfg"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST_F(DnnDetectorTest, AGarbageOnnxFileIsAOneLineErrorNamingIt) {
  const fs::path onnx = dir_ / "model.onnx";
  std::ofstream(onnx) << "not a protobuf at all";
  DnnDetectorConfig c;
  c.model_path = onnx.string();
  const std::string msg = runtime_error_of([&] { DnnDetector d(c); });
  EXPECT_NE(msg.find("model.onnx"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST_F(DnnDetectorTest, WeightsCutInsideAValueOrTheHeaderAreAnErrorNamingTheFile) {
  for (const std::size_t bytes : {std::size_t(10), std::size_t(20 + 4 * 13 + 2)}) {
    test::write_tiny_yolo(cfg_, weights_, bytes);
    const std::string msg = runtime_error_of([&] { DnnDetector d(config()); });
    EXPECT_NE(msg.find("tiny.weights"), std::string::npos) << bytes << " bytes: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(DnnDetectorConfig, ACfgWithoutWeightsIsRejectedNamingTheField) {
  DnnDetectorConfig c;
  c.model_path = "net.cfg";
  try {
    c.validate();
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("weights_path"), std::string::npos);
  }
}

}  // namespace
}  // namespace rownav::vision
