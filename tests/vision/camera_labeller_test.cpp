// Laser points labelled by the camera's boxes (Emmi 2021 Fig. 2b), against the simulator's truth.
#include "rownav/vision/camera_labeller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/vision/excess_green_detector.hpp"
#include "vision/field_scene.hpp"

namespace rownav::vision {
namespace {

using map::PointLabel;

/// A 100 x 100 px camera at the base origin looking along base x (optical z = base x).
core::CameraImage straight_camera() {
  core::CameraImage img;
  img.intrinsics = {100, 100, 50.0, 50.0, 50.0, 50.0};
  Eigen::Matrix3d R;
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  img.T_base_camera.linear() = R;
  img.T_base_camera.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);
  return img;
}

TEST(CameraLabeller, PointsTakeTheClassOfTheBoxTheyProjectInto) {
  CameraLabeller l;
  // (2, 0, 1) projects to the centre (50, 50); (2, 1, 1) to u = 25.
  l.set_detections(straight_camera(), {{40, 40, 60, 60, 0, 0.9f}, {20, 40, 30, 60, 1, 0.8f}});
  std::vector<PointLabel> labels;
  l.label({{2, 0, 1}, {2, 1, 1}, {2, -1, 1}, {2, 0, 0.01f}, {-2, 0, 1}}, labels);
  const std::vector<PointLabel> want{PointLabel::crop, PointLabel::other_crop,
                                     PointLabel::obstacle,   // outside every box
                                     PointLabel::ground,     // at the ground
                                     PointLabel::obstacle};  // behind the camera
  EXPECT_EQ(labels, want);
}

TEST(CameraLabeller, OverlappingBoxesGiveTheHighestScoresClass) {
  CameraLabeller l;
  l.set_detections(straight_camera(), {{0, 0, 100, 100, 1, 0.3f}, {45, 45, 55, 55, 0, 0.7f}});
  EXPECT_EQ(l.label_point({2, 0, 1}), PointLabel::crop);
  EXPECT_EQ(l.label_point({2, 1, 1}), PointLabel::other_crop);
}

TEST(CameraLabeller, NonFinitePointsUnknownClassesAndNoImageNeverThrow) {
  CameraLabeller l;
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  std::vector<PointLabel> labels;
  l.label({{2, 0, 1}, {nan, 0, 1}}, labels);  // no image yet
  EXPECT_EQ(labels, (std::vector<PointLabel>{PointLabel::obstacle, PointLabel::obstacle}));
  l.set_detections(straight_camera(), {{0, 0, 100, 100, 7, 0.9f}});  // class 7 has no label
  l.label({{2, 0, 1}, {inf, 0, 1}, {2, nan, 1}}, labels);
  EXPECT_EQ(labels, (std::vector<PointLabel>(3, PointLabel::obstacle)));
  core::CameraImage broken = straight_camera();
  broken.T_base_camera.translation().x() = nan;
  l.set_detections(broken, {{0, 0, 100, 100, 0, 0.9f}});
  EXPECT_EQ(l.label_point({2, 0, 1}), PointLabel::obstacle);
}

TEST(CameraLabellerConfig, InvalidFieldsAreNamed) {
  CameraLabellerConfig c;
  c.min_depth = 0.0;
  try {
    CameraLabeller l(c);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("min_depth"), std::string::npos);
  }
}

/// Agreement of the camera labeller with the truth labeller over the LiDAR points the camera
/// sees (in the image, 0.5-10 m ahead), per truth label.
struct Agreement {
  int points = 0, agree = 0;
  int crop = 0, crop_agree = 0, other = 0, other_agree = 0;
  void add(PointLabel truth, PointLabel seen) {
    ++points;
    agree += truth == seen;
    if (truth == PointLabel::crop) ++crop, crop_agree += seen == PointLabel::crop;
    if (truth == PointLabel::other_crop) ++other, other_agree += seen == PointLabel::other_crop;
  }
};

/// One frame: a LiDAR sweep and a camera image at T, both labellers, accumulated into `a`.
void label_frame(const test::FieldScene& s, const Eigen::Isometry3d& T, std::uint64_t seed,
                 Agreement& a) {
  sim::LidarConfig lc = sim::lidar_preset("os1_64");
  lc.motion_during_sweep = false;
  sim::Lidar lidar(lc, seed);
  std::vector<sim::SurfaceClass> classes;
  const auto cloud = lidar.sweep(
      *s.world, [&](double) { return T; }, 0.0, &classes);
  std::vector<Eigen::Vector3f> pts;
  const Eigen::Isometry3f T_base_lidar = lc.T_base_lidar().cast<float>();
  for (const auto& p : cloud.points) pts.push_back(T_base_lidar * Eigen::Vector3f(p.x, p.y, p.z));
  sim::TruthLabeller truth(s.truth(), seed);
  truth.set_frame(
      core::Pose2(T.translation().x(), T.translation().y(), std::atan2(T(1, 0), T(0, 0))), classes);
  sim::PinholeCamera cam(s.camera(), seed);
  const auto img = cam.render(*s.world, T, 0.0);
  ExcessGreenDetector det;
  CameraLabeller camera;
  camera.set_image(img, det);
  std::vector<PointLabel> want, got;
  truth.label(pts, want);
  camera.label(pts, got);
  const Eigen::Isometry3d T_camera_base = img.T_base_camera.inverse();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3d p = pts[i].cast<double>();
    if (p.x() < 0.5 || p.x() > 10.0 || !img.intrinsics.project(T_camera_base * p, 0.05)) continue;
    a.add(want[i], got[i]);
  }
}

TEST(CameraLabeller, AgreesWithTheTruthInAFieldBesideAnotherCrop) {
  // An OS1-64 and the default camera (107 deg) in the target field's last corridor (the other
  // field to the left; yaw -0.3..0.6 rad turns towards it), 3 seeds x 4 random poses, ~108,000
  // points in the camera's view. Measured (seeds 1-3, and 4-15 in blocks of 3): agreement
  // 0.988-0.989 of all points, 0.981-0.984 of the true crop points, 0.967-0.973 of the other
  // crop's points (BENCHMARK.md, issue 12). Asserted with margin: 0.97, 0.96, 0.94.
  Agreement a;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto s = test::make_field_scene(seed);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> ux(2.0, 20.0), yaw(-0.3, 0.6);
    for (int i = 0; i < 4; ++i) label_frame(s, s.pose(3, ux(rng), yaw(rng)), seed * 10 + i, a);
  }
  const double all = double(a.agree) / a.points, crop = double(a.crop_agree) / a.crop,
               other = double(a.other_agree) / a.other;
  std::printf("camera vs truth: %d points, agree %.3f; crop %d, %.3f; other_crop %d, %.3f\n",
              a.points, all, a.crop, crop, a.other, other);
  ASSERT_GT(a.crop, 1000);
  ASSERT_GT(a.other, 200);
  EXPECT_GE(all, 0.97);
  EXPECT_GE(crop, 0.96);
  EXPECT_GE(other, 0.94);
}

}  // namespace
}  // namespace rownav::vision
