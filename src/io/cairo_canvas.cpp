// Canvas drawing on a cairo recording surface; the outputs (PNG / SVG / PDF) replay it
// (cairo_output.cpp).
#include "rownav/io/cairo_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "cairo_recording.hpp"

namespace rownav::io {

namespace {

constexpr double kMaxPx = 1e6;  // cairo's 24.8 fixed point overflows near 8e6 px

Eigen::Vector2d clamp_px(const Eigen::Vector2d& p) {
  return p.cwiseMax(Eigen::Vector2d(-kMaxPx, -kMaxPx)).cwiseMin(Eigen::Vector2d(kMaxPx, kMaxPx));
}

bool finite(const std::vector<Eigen::Vector2d>& pts) {
  return std::all_of(pts.begin(), pts.end(), [](const auto& p) { return p.allFinite(); });
}

void set_colour(cairo_t* cr, Color c) {
  cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0);
}

/// Path through `pts`; false (no path) when a vertex is NaN / Inf.
bool path(cairo_t* cr, const std::vector<Eigen::Vector2d>& pts, bool closed) {
  cairo_new_path(cr);
  if (pts.empty() || !finite(pts)) return false;
  for (const auto& p : pts) {
    const Eigen::Vector2d q = clamp_px(p);
    cairo_line_to(cr, q.x(), q.y());  // line_to on an empty path is a move_to
  }
  if (closed) cairo_close_path(cr);
  return true;
}

/// Stroke settings of `s`; false when it draws no outline. Dashes as the old SVG writer drew
/// them (on 4 widths, off 3, at least 5 / 4 px), so pictures keep their look.
bool set_stroke(cairo_t* cr, const Style& s) {
  if (!(s.stroke_width_px > 0.0) || s.stroke.a == 0) return false;
  const double w = s.stroke_width_px;
  set_colour(cr, s.stroke);
  cairo_set_line_width(cr, w);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  if (s.dashed) {
    const double dash[2] = {std::max(5.0, 4.0 * w), std::max(4.0, 3.0 * w)};
    cairo_set_dash(cr, dash, 2, 0.0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  } else {
    cairo_set_dash(cr, nullptr, 0, 0.0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  }
  return true;
}

/// Fills (even-odd) and / or strokes the current path, then clears it.
void paint_path(cairo_t* cr, const Style& s) {
  if (s.filled && s.fill.a > 0) {
    set_colour(cr, s.fill);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
    cairo_fill_preserve(cr);
  }
  if (set_stroke(cr, s)) cairo_stroke_preserve(cr);
  cairo_new_path(cr);
}

/// Length of the well-formed UTF-8 sequence at text[i] (no overlong forms, surrogates or code
/// points past U+10FFFF), 0 when there is none.
std::size_t utf8_length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
  const unsigned c = byte(0);
  const std::size_t n = c < 0x80   ? 1
                        : c < 0xc2 ? 0
                        : c < 0xe0 ? 2
                        : c < 0xf0 ? 3
                        : c < 0xf5 ? 4
                                   : 0;
  if (n == 0 || i + n > text.size()) return 0;
  std::uint32_t cp = n == 1 ? c : c & (0x7f >> n);
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(k) >> 6) != 0x2) return 0;
    cp = (cp << 6) | (byte(k) & 0x3f);
  }
  const std::uint32_t least[5] = {0, 0, 0x80, 0x800, 0x10000};
  const bool ok = cp >= least[n] && cp <= 0x10ffff && (cp < 0xd800 || cp > 0xdfff);
  return ok ? n : 0;
}

/// Cairo fails a whole context on invalid UTF-8: then keep ASCII and replace the rest by '?'.
std::string utf8_or_ascii(const std::string& text) {
  for (std::size_t i = 0, n = 0; i < text.size(); i += n)
    if ((n = utf8_length(text, i)) == 0) {
      std::string out = text;
      for (char& ch : out)
        if (static_cast<unsigned char>(ch) >= 0x80) ch = '?';
      return out;
    }
  return text;
}

void set_font(cairo_t* cr, double size_px) {
  // The toy text API with fontconfig is enough for labels; DejaVu Sans is fonts-dejavu-core.
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, std::clamp(size_px, 1.0, 1000.0));
}

}  // namespace

CairoCanvas::CairoCanvas() : rec_(std::make_unique<Recording>(1, 1)) {}
CairoCanvas::~CairoCanvas() = default;

void CairoCanvas::resize(int width_px, int height_px) {
  rec_ = std::make_unique<Recording>(width_px, height_px);
  cairo_t* cr = rec_->cr;
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);
}

void CairoCanvas::line_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s) {
  polyline_px({a, b}, s, false);
}

void CairoCanvas::polyline_px(const std::vector<Eigen::Vector2d>& pts, const Style& s,
                              bool closed) {
  cairo_t* cr = rec_->cr;
  if (pts.size() < 2 || !path(cr, pts, closed)) return;
  if (set_stroke(cr, s)) cairo_stroke(cr);
  cairo_new_path(cr);
}

void CairoCanvas::polygon_px(const std::vector<Eigen::Vector2d>& pts, const Style& s) {
  cairo_t* cr = rec_->cr;
  if (pts.size() < 3 || !path(cr, pts, true)) return;
  paint_path(cr, s);
}

void CairoCanvas::circle_px(const Eigen::Vector2d& c, double r, const Style& s) {
  cairo_t* cr = rec_->cr;
  if (!c.allFinite() || !(r >= 0.0) || !std::isfinite(r)) return;
  const Eigen::Vector2d q = clamp_px(c);
  cairo_new_path(cr);
  cairo_arc(cr, q.x(), q.y(), std::min(r, kMaxPx), 0.0, 2.0 * std::numbers::pi);
  cairo_close_path(cr);
  paint_path(cr, s);
}

void CairoCanvas::dot_px(const Eigen::Vector2d& c, double r, Color color) {
  circle_px(c, r, Style{{}, color, 0.0, true, false});
}

void CairoCanvas::text_px(const Eigen::Vector2d& p, const std::string& text, double size_px,
                          Color color, Align align, bool vertical) {
  cairo_t* cr = rec_->cr;
  if (text.empty() || !p.allFinite()) return;
  const std::string t = utf8_or_ascii(text);
  set_font(cr, size_px);
  cairo_text_extents_t te;
  cairo_text_extents(cr, t.c_str(), &te);
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  const double u = align == Align::left     ? 0.0
                   : align == Align::centre ? -te.x_advance / 2.0
                                            : -te.x_advance;
  const double v = (fe.ascent - fe.descent) / 2.0;  // baseline below the anchor: centred em box
  const Eigen::Vector2d q = clamp_px(p);
  cairo_save(cr);
  cairo_translate(cr, q.x(), q.y());
  if (vertical) cairo_rotate(cr, -std::numbers::pi / 2.0);
  set_colour(cr, color);
  cairo_move_to(cr, u, v);
  cairo_show_text(cr, t.c_str());
  cairo_new_path(cr);
  cairo_restore(cr);
}

double CairoCanvas::text_width(const std::string& text, double size_px) const {
  if (text.empty()) return 0.0;
  cairo_t* cr = rec_->cr;
  const std::string t = utf8_or_ascii(text);
  set_font(cr, size_px);
  cairo_text_extents_t te;
  cairo_text_extents(cr, t.c_str(), &te);
  return te.x_advance;
}

void CairoCanvas::begin_group(const std::string&, const Eigen::AlignedBox2d* clip) {
  cairo_t* cr = rec_->cr;
  cairo_save(cr);
  if (clip) {
    const Eigen::AlignedBox2d box(clamp_px(clip->min()), clamp_px(clip->max()));
    cairo_new_path(cr);
    if (box.isEmpty())
      cairo_rectangle(cr, 0, 0, 0, 0);  // nothing draws
    else
      cairo_rectangle(cr, box.min().x(), box.min().y(), box.sizes().x(), box.sizes().y());
    cairo_clip(cr);
  }
  ++rec_->depth;
}

void CairoCanvas::end_group() {
  if (rec_->depth == 0) return;
  cairo_restore(rec_->cr);
  --rec_->depth;
}

}  // namespace rownav::io
