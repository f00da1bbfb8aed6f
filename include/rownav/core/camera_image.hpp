#pragma once
/// @file camera_image.hpp A stamped RGB camera image with its pinhole intrinsics and mount (the
/// camera of Emmi 2021, 002_806e72d300173f73.txt, Fig. 2b). Plain bytes: no OpenCV in the core.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace rownav::core {

/// Pinhole intrinsics in pixels. Pixel (u, v) covers [u, u + 1) x [v, v + 1): a point (x, y, z)
/// of the optical frame projects to u = fx x / z + cx, v = fy y / z + cy (no distortion).
struct CameraIntrinsics {
  int width = 0;    ///< [px] columns
  int height = 0;   ///< [px] rows
  double fx = 0.0;  ///< [px] focal length along u
  double fy = 0.0;  ///< [px] focal length along v
  double cx = 0.0;  ///< [px] principal point u
  double cy = 0.0;  ///< [px] principal point v

  /// Pixel coordinates of an optical-frame point; nullopt behind the camera (z <= min_depth),
  /// for a non-finite point or outside the image.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p_camera, double min_depth) const {
    if (!p_camera.allFinite() || p_camera.z() <= min_depth) return std::nullopt;
    const Eigen::Vector2d uv(fx * p_camera.x() / p_camera.z() + cx,
                             fy * p_camera.y() / p_camera.z() + cy);
    if (!(uv.x() >= 0.0 && uv.x() < width && uv.y() >= 0.0 && uv.y() < height)) return std::nullopt;
    return uv;
  }
  /// Unit ray direction (optical frame) through image point (u, v) [px].
  Eigen::Vector3d ray(double u, double v) const {
    return Eigen::Vector3d((u - cx) / fx, (v - cy) / fy, 1.0).normalized();
  }
};

/// One RGB8 image, row-major, 3 bytes a pixel (R, G, B), `width * height * 3` bytes.
struct CameraImage {
  double stamp = 0.0;  ///< [s] exposure time
  CameraIntrinsics intrinsics;
  /// Optical frame (z along the view, x right, y down in the image) to base frame.
  Eigen::Isometry3d T_base_camera = Eigen::Isometry3d::Identity();
  std::vector<std::uint8_t> rgb;  ///< R, G, B bytes, row after row

  int width() const { return intrinsics.width; }
  int height() const { return intrinsics.height; }
  bool empty() const { return rgb.empty(); }
  /// True when the byte count matches width x height x 3 and both are positive.
  bool valid() const {
    return width() > 0 && height() > 0 &&
           rgb.size() == static_cast<std::size_t>(width()) * static_cast<std::size_t>(height()) * 3;
  }
  /// Pointer to pixel (u, v)'s R byte (no bounds check).
  const std::uint8_t* pixel(int u, int v) const {
    return rgb.data() + (static_cast<std::size_t>(v) * static_cast<std::size_t>(width()) +
                         static_cast<std::size_t>(u)) *
                            3;
  }
};

}  // namespace rownav::core
