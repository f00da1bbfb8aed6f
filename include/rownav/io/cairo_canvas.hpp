#pragma once
/// @file cairo_canvas.hpp The Canvas on cairo: one drawing, recorded once, written as PNG
/// (anti-aliased raster), SVG or PDF (vectors) by the file's extension, text set in DejaVu Sans
/// through fontconfig. Cairo stays out of this header (it is linked privately).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rownav/io/canvas.hpp"

namespace rownav::io {

/// An 8-bit RGBA picture (straight alpha), rows top to bottom.
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

/// Canvas backend on cairo. Calls are recorded (a cairo recording surface); each output replays
/// the recording, so one drawing gives the PNG, the SVG and the PDF. The picture starts opaque
/// white. Groups are cairo save / restore (with a clip); cairo's SVG keeps no group names.
class CairoCanvas : public Canvas {
 public:
  CairoCanvas();
  ~CairoCanvas() override;
  CairoCanvas(const CairoCanvas&) = delete;
  CairoCanvas& operator=(const CairoCanvas&) = delete;

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
  /// Writes `out` as PNG, SVG or PDF by its extension (io::InputError for any other); throws
  /// std::runtime_error naming the file when it cannot be written.
  void save(const std::filesystem::path& out) const override;

  /// The picture rasterised (what the PNG holds).
  RgbaImage raster() const;
  /// PNG file bytes.
  std::string png() const;
  /// SVG document (text is drawn as glyph outlines, as cairo does).
  std::string svg() const;
  /// The SVG for inlining into HTML beside other SVGs: no XML declaration, and every id (glyphs,
  /// clips, surfaces) prefixed with `id_prefix`, since inline SVGs share the page's id space.
  std::string svg_inline(const std::string& id_prefix) const;
  /// PDF file bytes (one page; 1 px = 0.75 pt, i.e. 96 px per inch as in SVG / CSS).
  std::string pdf() const;

 protected:
  void resize(int width_px, int height_px) override;

 private:
  struct Recording;
  std::unique_ptr<Recording> rec_;
};

}  // namespace rownav::io
