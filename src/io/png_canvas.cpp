#include "rownav/io/png_canvas.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rownav/io/bitmap_font.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace {

using Box = Eigen::AlignedBox2i;  // [min, max) in pixels

/// Coverage in [0, 1] over the pixel window [x0, x1) x [y0, y1).
struct Mask {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  std::vector<float> a;
  float& at(int x, int y) { return a[static_cast<std::size_t>(y - y0) * (x1 - x0) + (x - x0)]; }
};

/// Mask over the pixels touched by the box [lo, hi] (plus 1 px), inside the clip.
Mask make_mask(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Box& clip) {
  Mask m;
  const auto fl = [](double v) { return static_cast<int>(std::clamp(std::floor(v), -1e6, 1e6)); };
  m.x0 = std::max(clip.min().x(), fl(lo.x()) - 1);
  m.y0 = std::max(clip.min().y(), fl(lo.y()) - 1);
  m.x1 = std::max(m.x0, std::min(clip.max().x(), fl(hi.x()) + 2));
  m.y1 = std::max(m.y0, std::min(clip.max().y(), fl(hi.y()) + 2));
  m.a.assign(static_cast<std::size_t>(m.x1 - m.x0) * (m.y1 - m.y0), 0.0f);
  return m;
}

double segment_distance(double px, double py, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double dx = b.x() - a.x(), dy = b.y() - a.y();
  const double l2 = dx * dx + dy * dy;
  const double s =
      l2 > 0.0 ? std::clamp(((px - a.x()) * dx + (py - a.y()) * dy) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(px - (a.x() + s * dx), py - (a.y() + s * dy));
}

/// Max-combines a round-capped segment of half width hw. Lines thinner than a pixel are drawn
/// one pixel wide with proportionally less coverage.
void stamp_segment(Mask& m, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double hw) {
  const double gain = std::min(1.0, 2.0 * hw);
  hw = std::max(hw, 0.5);
  const int xa = std::max(m.x0, static_cast<int>(std::floor(std::min(a.x(), b.x()) - hw - 1)));
  const int xb = std::min(m.x1, static_cast<int>(std::ceil(std::max(a.x(), b.x()) + hw + 1)));
  const int ya = std::max(m.y0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - hw - 1)));
  const int yb = std::min(m.y1, static_cast<int>(std::ceil(std::max(a.y(), b.y()) + hw + 1)));
  for (int y = ya; y < yb; ++y)
    for (int x = xa; x < xb; ++x) {
      const double d = segment_distance(x + 0.5, y + 0.5, a, b);
      const double c = std::clamp(hw + 0.5 - d, 0.0, 1.0) * gain;
      float& v = m.at(x, y);
      v = std::max(v, static_cast<float>(c));
    }
}

/// Max-combines an annulus |d - r| <= hw (hw < 0: the full disc of radius r).
void stamp_circle(Mask& m, const Eigen::Vector2d& c, double r, double hw) {
  for (int y = m.y0; y < m.y1; ++y)
    for (int x = m.x0; x < m.x1; ++x) {
      const double d = std::hypot(x + 0.5 - c.x(), y + 0.5 - c.y());
      const double cov = hw < 0.0 ? std::clamp(r + 0.5 - d, 0.0, 1.0)
                                  : std::clamp(hw + 0.5 - std::abs(d - r), 0.0, 1.0);
      float& v = m.at(x, y);
      v = std::max(v, static_cast<float>(cov));
    }
}

/// Even-odd fill with 4 sub-scanlines a pixel row and exact horizontal span coverage.
void fill_polygon(Mask& m, const std::vector<Eigen::Vector2d>& pts) {
  constexpr int kSub = 4;
  std::vector<double> xs;
  for (int y = m.y0; y < m.y1; ++y)
    for (int k = 0; k < kSub; ++k) {
      const double sy = y + (k + 0.5) / kSub;
      xs.clear();
      for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++) {
        const auto &p = pts[i], &q = pts[j];
        if ((p.y() > sy) != (q.y() > sy))
          xs.push_back(p.x() + (sy - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
      }
      std::sort(xs.begin(), xs.end());
      for (std::size_t i = 0; i + 1 < xs.size(); i += 2) {
        const double a = std::max(xs[i], double(m.x0)), b = std::min(xs[i + 1], double(m.x1));
        for (int x = static_cast<int>(std::floor(a)); x < b; ++x) {
          const double overlap = std::min(b, x + 1.0) - std::max(a, double(x));
          if (overlap > 0.0) m.at(x, y) += static_cast<float>(overlap / kSub);
        }
      }
    }
}

/// Cuts a polyline into dashes (round caps come from stamp_segment).
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> dashes(
    const std::vector<Eigen::Vector2d>& pts, double width) {
  const double on = std::max(5.0, 4.0 * width), off = std::max(4.0, 3.0 * width);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> out;
  double phase = 0.0;  // distance into the current on + off period
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const Eigen::Vector2d d = pts[i] - pts[i - 1];
    const double len = d.norm();
    double s = 0.0;
    while (s < len && len > 0.0) {
      const bool drawing = phase < on;
      const double step = std::min(len - s, (drawing ? on : on + off) - phase);
      if (drawing)
        out.emplace_back(pts[i - 1] + d * (s / len), pts[i - 1] + d * ((s + step) / len));
      s += step;
      phase = std::fmod(phase + step, on + off);
    }
  }
  return out;
}

void blend(RgbaImage& img, int x, int y, Color c, double coverage) {
  const double a = c.a / 255.0 * std::clamp(coverage, 0.0, 1.0);
  if (a <= 0.0) return;
  std::uint8_t* p = &img.rgba[(static_cast<std::size_t>(y) * img.width + x) * 4];
  const double da = p[3] / 255.0, oa = a + da * (1.0 - a);
  const std::uint8_t src[3] = {c.r, c.g, c.b};
  for (int k = 0; k < 3; ++k)
    p[k] = static_cast<std::uint8_t>(std::lround((src[k] * a + p[k] * da * (1.0 - a)) / oa));
  p[3] = static_cast<std::uint8_t>(std::lround(oa * 255.0));
}

void composite(RgbaImage& img, const Mask& m, Color c) {
  for (int y = m.y0; y < m.y1; ++y)
    for (int x = m.x0; x < m.x1; ++x) {
      const float v = m.a[static_cast<std::size_t>(y - m.y0) * (m.x1 - m.x0) + (x - m.x0)];
      if (v > 0.0f) blend(img, x, y, c, v);
    }
}

std::pair<Eigen::Vector2d, Eigen::Vector2d> bounds(const std::vector<Eigen::Vector2d>& pts,
                                                   double pad) {
  Eigen::Vector2d lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {lo.array() - pad, hi.array() + pad};
}

int font_scale(double size_px) {
  return std::max(1, static_cast<int>(std::lround(size_px / 11.0)));
}

}  // namespace

void PngCanvas::resize(int width_px, int height_px) {
  image_.width = width_px;
  image_.height = height_px;
  image_.rgba.assign(static_cast<std::size_t>(width_px) * height_px * 4, 255);
  clips_.assign(1, Box(Eigen::Vector2i(0, 0), Eigen::Vector2i(width_px, height_px)));
}

void PngCanvas::stroke_path(const std::vector<Eigen::Vector2d>& pts, const Style& s, bool closed) {
  if (pts.size() < 2 || s.stroke_width_px <= 0.0 || s.stroke.a == 0 || clips_.empty()) return;
  std::vector<Eigen::Vector2d> path = pts;
  if (closed) path.push_back(pts.front());
  const double hw = s.stroke_width_px / 2.0;
  const auto [lo, hi] = bounds(path, hw + 1.0);
  Mask m = make_mask(lo, hi, clips_.back());
  if (s.dashed) {
    for (const auto& [a, b] : dashes(path, s.stroke_width_px)) stamp_segment(m, a, b, hw);
  } else {
    for (std::size_t i = 1; i < path.size(); ++i) stamp_segment(m, path[i - 1], path[i], hw);
  }
  composite(image_, m, s.stroke);
}

void PngCanvas::line_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s) {
  stroke_path({a, b}, s, false);
}

void PngCanvas::polyline_px(const std::vector<Eigen::Vector2d>& pts, const Style& s, bool closed) {
  stroke_path(pts, s, closed);
}

void PngCanvas::polygon_px(const std::vector<Eigen::Vector2d>& pts, const Style& s) {
  if (pts.size() < 3 || clips_.empty()) return;
  if (s.filled && s.fill.a > 0) {
    const auto [lo, hi] = bounds(pts, 0.0);
    Mask m = make_mask(lo, hi, clips_.back());
    fill_polygon(m, pts);
    composite(image_, m, s.fill);
  }
  stroke_path(pts, s, true);
}

void PngCanvas::circle_px(const Eigen::Vector2d& c, double r, const Style& s) {
  if (clips_.empty() || !(r >= 0.0)) return;
  const double pad = r + s.stroke_width_px / 2.0 + 1.0;
  if (s.filled && s.fill.a > 0) {
    Mask m = make_mask(c.array() - pad, c.array() + pad, clips_.back());
    stamp_circle(m, c, r, -1.0);
    composite(image_, m, s.fill);
  }
  if (s.stroke_width_px > 0.0 && s.stroke.a > 0) {
    Mask m = make_mask(c.array() - pad, c.array() + pad, clips_.back());
    stamp_circle(m, c, r, s.stroke_width_px / 2.0);
    composite(image_, m, s.stroke);
  }
}

void PngCanvas::dot_px(const Eigen::Vector2d& c, double r, Color color) {
  if (clips_.empty() || !c.allFinite()) return;
  Mask m = make_mask(c.array() - r - 1.0, c.array() + r + 1.0, clips_.back());
  stamp_circle(m, c, r, -1.0);
  composite(image_, m, color);
}

void PngCanvas::text_px(const Eigen::Vector2d& p, const std::string& text, double size_px,
                        Color color, Align align, bool vertical) {
  if (clips_.empty()) return;
  const int s = font_scale(size_px);
  const double w = text_width(text, size_px);
  const double u0 = align == Align::left ? 0.0 : align == Align::centre ? -w / 2.0 : -w;
  const double v0 = -kGlyphAscent * s / 2.0;  // cap height centred on the anchor
  const Box& clip = clips_.back();
  for (std::size_t i = 0; i < text.size(); ++i)
    for (int row = 0; row < kGlyphRows; ++row) {
      const std::uint8_t bits = glyph_row(text[i], row);
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (!(bits & (1u << (kGlyphWidth - 1 - col)))) continue;
        const double u = std::round(u0) + (static_cast<double>(i) * kGlyphAdvance + col) * s;
        const double v = std::round(v0) + row * s;
        for (int dy = 0; dy < s; ++dy)
          for (int dx = 0; dx < s; ++dx) {
            const int x = static_cast<int>(std::lround(vertical ? p.x() + v + dy : p.x() + u + dx));
            const int y =
                static_cast<int>(std::lround(vertical ? p.y() - u - dx - 1 : p.y() + v + dy));
            if (x >= clip.min().x() && x < clip.max().x() && y >= clip.min().y() &&
                y < clip.max().y())
              blend(image_, x, y, color, 1.0);
          }
      }
    }
}

double PngCanvas::text_width(const std::string& text, double size_px) const {
  if (text.empty()) return 0.0;
  const int s = font_scale(size_px);
  return static_cast<double>(text.size() * kGlyphAdvance - 1) * s;
}

void PngCanvas::begin_group(const std::string&, const Eigen::AlignedBox2d* clip) {
  Box active = clips_.empty() ? Box(Eigen::Vector2i(0, 0), Eigen::Vector2i(0, 0)) : clips_.back();
  if (clip) {
    const Box c(Eigen::Vector2i(static_cast<int>(std::floor(clip->min().x())),
                                static_cast<int>(std::floor(clip->min().y()))),
                Eigen::Vector2i(static_cast<int>(std::ceil(clip->max().x())),
                                static_cast<int>(std::ceil(clip->max().y()))));
    active = active.intersection(c);  // may be empty: then nothing draws
  }
  clips_.push_back(active);
}

void PngCanvas::end_group() {
  if (clips_.size() > 1) clips_.pop_back();
}

void PngCanvas::save(const std::filesystem::path& out) const {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  img.width = static_cast<png_uint_32>(image_.width);
  img.height = static_cast<png_uint_32>(image_.height);
  img.format = PNG_FORMAT_RGBA;
  if (!png_image_write_to_file(&img, out.c_str(), 0, image_.rgba.data(), 0, nullptr))
    throw std::runtime_error(out.string() + ": cannot write PNG (" + img.message + ")");
}

RgbaImage read_png(const std::filesystem::path& file) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, file.c_str()))
    throw InputError(file.string(), "", std::string("not a readable PNG (") + img.message + ")");
  img.format = PNG_FORMAT_RGBA;
  RgbaImage out;
  out.width = static_cast<int>(img.width);
  out.height = static_cast<int>(img.height);
  out.rgba.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, out.rgba.data(), 0, nullptr))
    throw InputError(file.string(), "", std::string("corrupt PNG (") + img.message + ")");
  return out;
}

}  // namespace rownav::io
