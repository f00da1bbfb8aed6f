// Ground-truth point labels with configurable detector errors (for the map stage).
#include "rownav/sim/truth_labeller.hpp"

#include <gtest/gtest.h>

namespace rownav::sim {
namespace {

using map::PointLabel;

std::vector<Eigen::Vector3f> points(int n, float x = 1.0f) {
  return std::vector<Eigen::Vector3f>(static_cast<std::size_t>(n), Eigen::Vector3f(x, 0, 0));
}

TEST(TruthLabeller, WithoutErrorsLabelsFollowTheSurfaceHit) {
  TruthLabeller l({}, 1);
  l.set_frame(core::Pose2(), {SurfaceClass::crop, SurfaceClass::ground, SurfaceClass::weed,
                              SurfaceClass::obstacle, SurfaceClass::trunk});
  std::vector<PointLabel> labels;
  l.label(points(6), labels);
  const std::vector<PointLabel> want{PointLabel::crop,     PointLabel::ground, PointLabel::weed,
                                     PointLabel::obstacle, PointLabel::crop,
                                     PointLabel::obstacle};  // the 6th point has no class
  EXPECT_EQ(labels, want);
}

TEST(TruthLabeller, CropOutsideTheTargetRegionIsAnotherCrop) {
  TruthLabellerConfig c;
  c.use_target_region = true;
  c.target_min = {0.0, 0.0};
  c.target_max = {10.0, 5.0};
  TruthLabeller l(c, 1);
  l.set_frame(core::Pose2(0.0, 4.5, 0.0), {SurfaceClass::crop, SurfaceClass::crop});
  std::vector<PointLabel> labels;
  l.label({{1.0f, 0.2f, 0.0f}, {1.0f, 1.0f, 0.0f}}, labels);  // world y 4.7 and 5.5
  EXPECT_EQ(labels[0], PointLabel::crop);
  EXPECT_EQ(labels[1], PointLabel::other_crop);
}

TEST(TruthLabeller, ErrorRatesMatchTheConfigAndTheSeedRepeats) {
  TruthLabellerConfig c;
  c.false_positive_rate = 0.05;
  c.false_negative_rate = 0.2;
  const int n = 20000;
  std::vector<SurfaceClass> cls(n, SurfaceClass::crop);
  for (int i = 0; i < n / 2; ++i) cls[static_cast<std::size_t>(i)] = SurfaceClass::ground;
  TruthLabeller a(c, 7), b(c, 7);
  a.set_frame(core::Pose2(), cls);
  b.set_frame(core::Pose2(), cls);
  std::vector<PointLabel> la, lb;
  a.label(points(n), la);
  b.label(points(n), lb);
  EXPECT_EQ(la, lb);
  int fp = 0, fn = 0;
  for (int i = 0; i < n; ++i) {
    const bool crop = la[static_cast<std::size_t>(i)] == PointLabel::crop;
    if (i < n / 2) fp += crop ? 1 : 0;
    else fn += crop ? 0 : 1;
  }
  EXPECT_NEAR(fp / (n / 2.0), 0.05, 0.01);
  EXPECT_NEAR(fn / (n / 2.0), 0.2, 0.02);
}

TEST(TruthLabeller, RatesOutsideZeroOneAreRejected) {
  TruthLabellerConfig c;
  c.false_negative_rate = 1.5;
  EXPECT_THROW(TruthLabeller(c, 1), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::sim
