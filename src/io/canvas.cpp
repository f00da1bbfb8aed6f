#include "rownav/io/canvas.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "rownav/io/cairo_canvas.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::uint8_t hex_byte(std::string_view s, std::size_t i, std::string_view whole) {
  const int hi = hex_digit(s[i]), lo = hex_digit(s[i + 1]);
  if (hi < 0 || lo < 0) throw std::invalid_argument("bad colour '" + std::string(whole) + "'");
  return static_cast<std::uint8_t>(hi * 16 + lo);
}

}  // namespace

Color Color::hex(std::string_view s) {
  const std::string_view whole = s;
  if (!s.empty() && s.front() == '#') s.remove_prefix(1);
  if (s.size() != 6 && s.size() != 8)
    throw std::invalid_argument("bad colour '" + std::string(whole) + "' (want #rrggbb[aa])");
  Color c{hex_byte(s, 0, whole), hex_byte(s, 2, whole), hex_byte(s, 4, whole), 255};
  if (s.size() == 8) c.a = hex_byte(s, 6, whole);
  return c;
}

Color Color::with_alpha(double alpha) const {
  Color c = *this;
  c.a = static_cast<std::uint8_t>(std::lround(std::clamp(alpha, 0.0, 1.0) * 255.0));
  return c;
}

std::string Color::to_hex() const {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", r, g, b);
  return buf;
}

Canvas::~Canvas() = default;

void Canvas::set_view(const Eigen::AlignedBox2d& world, double pixels_per_metre, int margin_px) {
  set_view(world, pixels_per_metre, Margins{margin_px, margin_px, margin_px, margin_px});
}

void Canvas::set_view(const Eigen::AlignedBox2d& world, double ppm, const Margins& m) {
  if (world.isEmpty() || !(ppm > 0.0)) throw std::invalid_argument("set_view: empty view");
  const double w = std::ceil(world.sizes().x() * ppm), h = std::ceil(world.sizes().y() * ppm);
  const Eigen::AlignedBox2d plot(Eigen::Vector2d(m.left, m.top),
                                 Eigen::Vector2d(m.left + w, m.top + h));
  // Keep the scale exact: the world box grows to fill the rounded-up pixel box.
  const Eigen::AlignedBox2d grown(
      world.min(), Eigen::Vector2d(world.min().x() + w / ppm, world.min().y() + h / ppm));
  set_view_rect(grown, plot, m.left + static_cast<int>(w) + m.right,
                m.top + static_cast<int>(h) + m.bottom);
}

void Canvas::set_view_fit(const Eigen::AlignedBox2d& world, int width_px, int height_px,
                          int margin_px) {
  if (world.isEmpty()) throw std::invalid_argument("set_view_fit: empty view");
  const double aw = width_px - 2.0 * margin_px, ah = height_px - 2.0 * margin_px;
  const double ppm = std::min(aw / world.sizes().x(), ah / world.sizes().y());
  const Eigen::Vector2d half(aw / ppm / 2.0, ah / ppm / 2.0);
  const Eigen::AlignedBox2d fitted(world.center() - half, world.center() + half);
  const Eigen::AlignedBox2d plot(Eigen::Vector2d(margin_px, margin_px),
                                 Eigen::Vector2d(width_px - margin_px, height_px - margin_px));
  set_view_rect(fitted, plot, width_px, height_px);
}

void Canvas::set_view_rect(const Eigen::AlignedBox2d& world, const Eigen::AlignedBox2d& plot_px,
                           int width_px, int height_px) {
  if (world.isEmpty() || plot_px.isEmpty() || width_px <= 0 || height_px <= 0)
    throw std::invalid_argument("set_view_rect: empty view");
  world_ = world;
  plot_px_ = plot_px;
  sx_ = plot_px.sizes().x() / std::max(world.sizes().x(), 1e-12);
  sy_ = plot_px.sizes().y() / std::max(world.sizes().y(), 1e-12);
  width_ = width_px;
  height_ = height_px;
  resize(width_px, height_px);
}

Eigen::Vector2d Canvas::to_pixel(const Eigen::Vector2d& p) const {
  return {plot_px_.min().x() + (p.x() - world_.min().x()) * sx_,
          plot_px_.max().y() - (p.y() - world_.min().y()) * sy_};
}

Eigen::Vector2d Canvas::to_world(const Eigen::Vector2d& q) const {
  return {world_.min().x() + (q.x() - plot_px_.min().x()) / sx_,
          world_.min().y() + (plot_px_.max().y() - q.y()) / sy_};
}

std::vector<Eigen::Vector2d> Canvas::to_pixels(const std::vector<Eigen::Vector2d>& pts) const {
  std::vector<Eigen::Vector2d> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.push_back(to_pixel(p));
  return out;
}

void Canvas::line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s) {
  line_px(to_pixel(a), to_pixel(b), s);
}

void Canvas::polyline(const std::vector<Eigen::Vector2d>& pts, const Style& s, bool closed) {
  polyline_px(to_pixels(pts), s, closed);
}

void Canvas::polygon(const std::vector<Eigen::Vector2d>& pts, const Style& s) {
  polygon_px(to_pixels(pts), s);
}

void Canvas::circle(const Eigen::Vector2d& c, double radius_m, const Style& s) {
  circle_px(to_pixel(c), radius_m * sx_, s);
}

void Canvas::dot(const Eigen::Vector2d& c, double radius_px, Color color) {
  dot_px(to_pixel(c), radius_px, color);
}

void Canvas::rect_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s) {
  polygon_px({a, {b.x(), a.y()}, b, {a.x(), b.y()}}, s);
}

void Canvas::begin_group(const std::string&, const Eigen::AlignedBox2d*) {}
void Canvas::end_group() {}

PictureFormat picture_format(const std::filesystem::path& out) {
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".png") return PictureFormat::png;
  if (ext == ".svg") return PictureFormat::svg;
  if (ext == ".pdf") return PictureFormat::pdf;
  throw InputError(out.string(), "",
                   "unknown picture format '" + ext + "' (want .png, .svg or .pdf)");
}

std::unique_ptr<Canvas> make_canvas(const std::filesystem::path& out) {
  picture_format(out);  // reject an unknown extension before anything is drawn
  return std::make_unique<CairoCanvas>();
}

}  // namespace rownav::io
