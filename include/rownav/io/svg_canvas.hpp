#pragma once
/// @file svg_canvas.hpp Canvas that writes clean SVG: one element a primitive, named groups,
/// coordinates rounded to 0.1 px, a white background.
#include <string>

#include "rownav/io/canvas.hpp"

namespace rownav::io {

/// SVG backend of Canvas.
class SvgCanvas : public Canvas {
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

  /// The complete document as it would be saved.
  std::string document() const;

 protected:
  void resize(int width_px, int height_px) override;

 private:
  std::string body_;
  int open_groups_ = 0;
  int clip_count_ = 0;
};

}  // namespace rownav::io
