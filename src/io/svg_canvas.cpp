#include "rownav/io/svg_canvas.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace rownav::io {

namespace {

/// Number rounded to 0.1, without a trailing ".0".
std::string num(double v) {
  if (!std::isfinite(v)) v = 0.0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", std::round(v * 10.0) / 10.0);
  std::string s = buf;
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  if (s == "-0") s = "0";
  return s;
}

std::string opacity(const char* attr, Color c) {
  if (c.a == 255) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, " %s=\"%.3g\"", attr, c.a / 255.0);
  return buf;
}

std::string stroke_attrs(const Style& s) {
  if (s.stroke_width_px <= 0.0 || s.stroke.a == 0) return " stroke=\"none\"";
  std::string out = " stroke=\"" + s.stroke.to_hex() + "\" stroke-width=\"" +
                    num(s.stroke_width_px) + "\"" + opacity("stroke-opacity", s.stroke);
  if (s.dashed) {
    const double w = s.stroke_width_px;
    out += " stroke-dasharray=\"" + num(std::max(5.0, 4.0 * w)) + " " +
           num(std::max(4.0, 3.0 * w)) + "\"";
  } else {
    out += " stroke-linecap=\"round\" stroke-linejoin=\"round\"";
  }
  return out;
}

std::string fill_attrs(const Style& s) {
  if (!s.filled) return " fill=\"none\"";
  return " fill=\"" + s.fill.to_hex() + "\"" + opacity("fill-opacity", s.fill);
}

std::string points_attr(const std::vector<Eigen::Vector2d>& pts) {
  std::string out;
  out.reserve(pts.size() * 12);
  for (const auto& p : pts) {
    if (!out.empty()) out += ' ';
    out += num(p.x()) + "," + num(p.y());
  }
  return out;
}

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

void SvgCanvas::resize(int width_px, int height_px) {
  body_ = "<rect width=\"" + std::to_string(width_px) + "\" height=\"" + std::to_string(height_px) +
          "\" fill=\"#ffffff\"/>\n";
  open_groups_ = 0;
}

void SvgCanvas::line_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Style& s) {
  body_ += "<line x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) +
           "\" y2=\"" + num(b.y()) + "\"" + stroke_attrs(s) + "/>\n";
}

void SvgCanvas::polyline_px(const std::vector<Eigen::Vector2d>& pts, const Style& s, bool closed) {
  if (pts.size() < 2) return;
  body_ += std::string(closed ? "<polygon" : "<polyline") + " points=\"" + points_attr(pts) +
           "\" fill=\"none\"" + stroke_attrs(s) + "/>\n";
}

void SvgCanvas::polygon_px(const std::vector<Eigen::Vector2d>& pts, const Style& s) {
  if (pts.size() < 3) return;
  body_ += "<polygon points=\"" + points_attr(pts) + "\" fill-rule=\"evenodd\"" + fill_attrs(s) +
           stroke_attrs(s) + "/>\n";
}

void SvgCanvas::circle_px(const Eigen::Vector2d& c, double r, const Style& s) {
  body_ += "<circle cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"" + num(r) + "\"" +
           fill_attrs(s) + stroke_attrs(s) + "/>\n";
}

void SvgCanvas::dot_px(const Eigen::Vector2d& c, double r, Color color) {
  body_ += "<circle cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"" + num(r) +
           "\" fill=\"" + color.to_hex() + "\"" + opacity("fill-opacity", color) + "/>\n";
}

void SvgCanvas::text_px(const Eigen::Vector2d& p, const std::string& text, double size_px,
                        Color color, Align align, bool vertical) {
  const char* anchor = align == Align::left ? "start" : align == Align::centre ? "middle" : "end";
  body_ += "<text x=\"" + num(p.x()) + "\" y=\"" + num(p.y()) + "\" font-size=\"" + num(size_px) +
           "\" fill=\"" + color.to_hex() + "\"" + opacity("fill-opacity", color) +
           " text-anchor=\"" + anchor + "\" dominant-baseline=\"central\"";
  if (vertical) body_ += " transform=\"rotate(-90 " + num(p.x()) + " " + num(p.y()) + ")\"";
  body_.append(">").append(escape(text)).append("</text>\n");
}

double SvgCanvas::text_width(const std::string& text, double size_px) const {
  return 0.58 * size_px * static_cast<double>(text.size());  // average sans-serif advance
}

void SvgCanvas::begin_group(const std::string& name, const Eigen::AlignedBox2d* clip) {
  std::string clip_attr;
  if (clip) {
    const std::string id = "clip" + std::to_string(++clip_count_);
    body_ += "<clipPath id=\"" + id + "\"><rect x=\"" + num(clip->min().x()) + "\" y=\"" +
             num(clip->min().y()) + "\" width=\"" + num(clip->sizes().x()) + "\" height=\"" +
             num(clip->sizes().y()) + "\"/></clipPath>\n";
    clip_attr = " clip-path=\"url(#" + id + ")\"";
  }
  body_ += "<g id=\"" + escape(name) + "\"" + clip_attr + ">\n";
  ++open_groups_;
}

void SvgCanvas::end_group() {
  if (open_groups_ == 0) return;
  body_ += "</g>\n";
  --open_groups_;
}

std::string SvgCanvas::document() const {
  std::string doc = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  doc += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width()) +
         "\" height=\"" + std::to_string(height()) + "\" viewBox=\"0 0 " + std::to_string(width()) +
         " " + std::to_string(height()) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  doc += body_;
  for (int i = 0; i < open_groups_; ++i) doc += "</g>\n";
  doc += "</svg>\n";
  return doc;
}

void SvgCanvas::save(const std::filesystem::path& out) const {
  std::ofstream f(out, std::ios::binary);
  f << document();
  if (!f) throw std::runtime_error(out.string() + ": cannot write");
}

}  // namespace rownav::io
