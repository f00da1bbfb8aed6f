#pragma once
/// @file canvas.hpp An abstract drawing surface in world metres (x right, y up on screen); its
/// backend is cairo (cairo_canvas.hpp: PNG, SVG and PDF from one drawing). World-space calls go through one view transform; pixel-space calls
/// (titles, legends, colour bars) bypass it. Pixel origin: top-left, y down.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rownav::io {

/// 8-bit RGBA colour (straight, not premultiplied alpha).
struct Color {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;

  /// Parses "#rrggbb" or "#rrggbbaa" (the '#' is optional); throws std::invalid_argument.
  static Color hex(std::string_view s);
  /// Same colour with alpha a in [0, 1].
  Color with_alpha(double a) const;
  /// "#rrggbb" (alpha dropped).
  std::string to_hex() const;
  bool operator==(const Color&) const = default;
};

/// How a shape is drawn.
struct Style {
  Color stroke;
  Color fill;
  double stroke_width_px = 1.0;  ///< [px] 0: no stroke
  bool filled = false;
  bool dashed = false;
};

/// Horizontal text alignment about the anchor point.
enum class Align : std::uint8_t { left, centre, right };

/// Blank space around the plot area, in pixels.
struct Margins {
  int left = 40, top = 40, right = 40, bottom = 40;
};

/// A drawing surface. Call one of the `set_view` functions first: it fixes the picture size.
class Canvas {
 public:
  virtual ~Canvas();

  /// World box `world` drawn at `pixels_per_metre`, plus a margin on every side.
  void set_view(const Eigen::AlignedBox2d& world, double pixels_per_metre, int margin_px = 40);
  /// Same with a margin per side (room for a title, a legend column, a scale bar).
  void set_view(const Eigen::AlignedBox2d& world, double pixels_per_metre, const Margins& m);
  /// Fixed picture size: `world` fitted inside the margins with equal x / y scales, centred.
  void set_view_fit(const Eigen::AlignedBox2d& world, int width_px, int height_px,
                    int margin_px = 40);
  /// General form: `world` maps exactly onto the pixel rectangle `plot_px` (x / y scales may
  /// differ, as in line plots) on a width_px x height_px picture.
  void set_view_rect(const Eigen::AlignedBox2d& world, const Eigen::AlignedBox2d& plot_px,
                     int width_px, int height_px);

  // ---- world space [m] ----
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s);
  void polyline(const std::vector<Eigen::Vector2d>& pts, const Style& s, bool closed = false);
  /// Filled (even-odd) and / or stroked polygon.
  void polygon(const std::vector<Eigen::Vector2d>& pts, const Style& s);
  /// Circle of world radius (x scale).
  void circle(const Eigen::Vector2d& c, double radius_m, const Style& s);
  /// Filled dot of fixed pixel radius at a world point (point clouds).
  void dot(const Eigen::Vector2d& c, double radius_px, Color color);

  // ---- pixel space ----
  virtual void line_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s) = 0;
  virtual void polyline_px(const std::vector<Eigen::Vector2d>& pts, const Style& s,
                           bool closed = false) = 0;
  virtual void polygon_px(const std::vector<Eigen::Vector2d>& pts, const Style& s) = 0;
  virtual void circle_px(const Eigen::Vector2d& c, double radius_px, const Style& s) = 0;
  virtual void dot_px(const Eigen::Vector2d& c, double radius_px, Color color) = 0;
  /// Axis-aligned rectangle between two pixel corners.
  void rect_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s);
  /// Text whose vertical centre is at `pixel`; `vertical` turns it 90 deg counter-clockwise
  /// (reads bottom to top; the anchor is then along the text's vertical axis).
  virtual void text_px(const Eigen::Vector2d& pixel, const std::string& text, double size_px,
                       Color color, Align align = Align::left, bool vertical = false) = 0;
  /// Left-aligned or centred text (shorthand).
  void text_px(const Eigen::Vector2d& pixel, const std::string& text, double size_px, Color color,
               bool centred) {
    text_px(pixel, text, size_px, color, centred ? Align::centre : Align::left);
  }
  /// [px] width the text will take (for layout).
  virtual double text_width(const std::string& text, double size_px) const = 0;

  /// Opens a named group (names document the drawing; cairo's SVG does not keep them); with
  /// `clip`, its content is clipped to that pixel box.
  virtual void begin_group(const std::string& name, const Eigen::AlignedBox2d* clip = nullptr);
  virtual void end_group();

  /// Writes the picture; throws std::runtime_error when the file cannot be written.
  virtual void save(const std::filesystem::path& out) const = 0;

  int width() const { return width_; }
  int height() const { return height_; }
  /// Pixel rectangle the view's world box maps onto.
  const Eigen::AlignedBox2d& plot_rect() const { return plot_px_; }
  /// World box of the view.
  const Eigen::AlignedBox2d& world_box() const { return world_; }
  /// [px/m] horizontal scale.
  double pixels_per_metre() const { return sx_; }
  /// World point to pixel (y flipped: world y up, pixel y down).
  Eigen::Vector2d to_pixel(const Eigen::Vector2d& world) const;
  /// Pixel to world point.
  Eigen::Vector2d to_world(const Eigen::Vector2d& pixel) const;

 protected:
  /// Called when the picture size changes: allocate / clear the surface.
  virtual void resize(int width_px, int height_px) = 0;

 private:
  std::vector<Eigen::Vector2d> to_pixels(const std::vector<Eigen::Vector2d>& pts) const;

  int width_ = 0, height_ = 0;
  Eigen::AlignedBox2d world_{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)};
  Eigen::AlignedBox2d plot_px_{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)};
  double sx_ = 1.0, sy_ = 1.0;
};

/// Picture file formats, chosen by the file's extension.
enum class PictureFormat : std::uint8_t { png, svg, pdf };

/// Format of `out` by its extension (".png", ".svg", ".pdf", any case); else io::InputError.
PictureFormat picture_format(const std::filesystem::path& out);

/// Canvas for `out` (a CairoCanvas); an extension picture_format rejects throws io::InputError.
std::unique_ptr<Canvas> make_canvas(const std::filesystem::path& out);

}  // namespace rownav::io
