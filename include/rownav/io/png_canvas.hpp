#pragma once
/// @file png_canvas.hpp Canvas with its own anti-aliased software rasterizer into an RGBA buffer
/// (coverage from distance to segments / circles, even-odd scanline polygons with 4x vertical
/// supersampling, alpha blending) and the built-in bitmap font; saved with libpng.
#include <cstdint>
#include <vector>

#include "rownav/io/canvas.hpp"

namespace rownav::io {

/// An 8-bit RGBA picture, rows top to bottom.
struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes

  /// Pixel (x, y); (0, 0) is the top-left corner.
  Color at(int x, int y) const {
    const auto i = (static_cast<std::size_t>(y) * width + x) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
  }
};

/// Reads a PNG file as RGBA; throws io::InputError when it is missing or not a PNG.
RgbaImage read_png(const std::filesystem::path& file);

/// PNG backend of Canvas. The picture starts opaque white.
class PngCanvas : public Canvas {
 public:
  void line_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s) override;
  void polyline_px(const std::vector<Eigen::Vector2d>& pts, const Style& s,
                   bool closed = false) override;
  void polygon_px(const std::vector<Eigen::Vector2d>& pts, const Style& s) override;
  void circle_px(const Eigen::Vector2d& c, double radius_px, const Style& s) override;
  void dot_px(const Eigen::Vector2d& c, double radius_px, Color color) override;
  using Canvas::text_px;
  void text_px(const Eigen::Vector2d& pixel, const std::string& text, double size_px, Color color,
               Align align = Align::left, bool vertical = false) override;
  double text_width(const std::string& text, double size_px) const override;
  void begin_group(const std::string& name, const Eigen::AlignedBox2d* clip = nullptr) override;
  void end_group() override;
  void save(const std::filesystem::path& out) const override;

  /// The picture drawn so far.
  const RgbaImage& image() const { return image_; }

 protected:
  void resize(int width_px, int height_px) override;

 private:
  void stroke_path(const std::vector<Eigen::Vector2d>& pts, const Style& s, bool closed);

  RgbaImage image_;
  std::vector<Eigen::AlignedBox2i> clips_;  // stack of [min, max) pixel boxes; back() is active
};

}  // namespace rownav::io
