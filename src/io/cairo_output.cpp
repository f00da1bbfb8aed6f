// CairoCanvas outputs: the recording replayed onto an image (PNG), SVG or PDF surface that
// writes to memory, so every format fails or succeeds the same way when the file is written.
#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

#include "cairo_recording.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace {

constexpr double kPtPerPx = 0.75;  // 96 px per inch, as SVG and CSS count

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void check(cairo_status_t status, const char* what) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string(what) + ": cairo: " + cairo_status_to_string(status));
}

/// Paints `source` (the recording, or a decoded PNG) onto `target` at `scale`.
void replay(cairo_surface_t* target, cairo_surface_t* source, double scale) {
  cairo_t* cr = cairo_create(target);
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, source, 0.0, 0.0);
  cairo_paint(cr);
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  check(status, "picture");
}

/// Owns a cairo surface (destroyed on every path out, throws included).
struct Surface {
  cairo_surface_t* s;
  explicit Surface(cairo_surface_t* surface) : s(surface) {}
  ~Surface() { cairo_surface_destroy(s); }
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;
};

/// Premultiplied native-endian ARGB32 to straight RGBA bytes.
RgbaImage to_rgba(cairo_surface_t* image) {
  cairo_surface_flush(image);
  RgbaImage out;
  out.width = cairo_image_surface_get_width(image);
  out.height = cairo_image_surface_get_height(image);
  out.rgba.resize(static_cast<std::size_t>(out.width) * out.height * 4);
  const unsigned char* data = cairo_image_surface_get_data(image);
  const int stride = cairo_image_surface_get_stride(image);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      std::uint32_t argb;
      std::memcpy(&argb, data + static_cast<std::size_t>(y) * stride + 4 * x, 4);
      const std::uint32_t a = argb >> 24;
      const auto un = [a](std::uint32_t c) {
        return static_cast<std::uint8_t>(a == 0 ? 0 : (c * 255 + a / 2) / a);
      };
      std::uint8_t* p = &out.rgba[(static_cast<std::size_t>(y) * out.width + x) * 4];
      p[0] = un((argb >> 16) & 0xff), p[1] = un((argb >> 8) & 0xff), p[2] = un(argb & 0xff);
      p[3] = static_cast<std::uint8_t>(a);
    }
  return out;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (auto p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

/// Cairo names SVG groups after its surfaces' process-wide serial numbers ("surface53"):
/// renumber them in order of appearance, so the same drawing gives the same document.
std::string renumber_surfaces(const std::string& doc) {
  static const std::string kWord = "surface";
  std::map<std::string, std::string> renamed;
  std::string out;
  out.reserve(doc.size());
  std::size_t i = 0;
  for (auto p = doc.find(kWord); p != std::string::npos; p = doc.find(kWord, p + 1)) {
    std::size_t e = p + kWord.size();
    while (e < doc.size() && std::isdigit(static_cast<unsigned char>(doc[e]))) ++e;
    if (e == p + kWord.size() || p == 0 || (doc[p - 1] != '"' && doc[p - 1] != '#')) continue;
    const auto [it, added] = renamed.try_emplace(doc.substr(p, e - p), "");
    if (added) it->second = kWord + std::to_string(renamed.size());
    out.append(doc, i, p - i).append(it->second);
    i = e;
    p = e - 1;
  }
  return out.append(doc, i, std::string::npos);
}

void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  errno = 0;
  std::ofstream f(file, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  f.close();
  if (!f)
    throw std::runtime_error(file.string() + ": cannot write" +
                             (errno ? std::string(" (") + std::strerror(errno) + ")" : ""));
}

}  // namespace

RgbaImage CairoCanvas::raster() const {
  Surface image(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width(), height()));
  check(cairo_surface_status(image.s), "picture");
  replay(image.s, rec_->surface, 1.0);
  return to_rgba(image.s);
}

std::string CairoCanvas::png() const {
  Surface image(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width(), height()));
  check(cairo_surface_status(image.s), "picture");
  replay(image.s, rec_->surface, 1.0);
  std::string bytes;
  check(cairo_surface_write_to_png_stream(image.s, append, &bytes), "PNG");
  return bytes;
}

std::string CairoCanvas::svg() const {
  std::string bytes;
  {
    Surface svg(cairo_svg_surface_create_for_stream(append, &bytes, width(), height()));
    check(cairo_surface_status(svg.s), "SVG");
    // Sizes in px, as the pictures were laid out (cairo's default unit is pt).
    cairo_svg_surface_set_document_unit(svg.s, CAIRO_SVG_UNIT_PX);
    replay(svg.s, rec_->surface, 1.0);
    cairo_surface_finish(svg.s);
    check(cairo_surface_status(svg.s), "SVG");
  }
  return renumber_surfaces(bytes);
}

std::string CairoCanvas::svg_inline(const std::string& id_prefix) const {
  std::string doc = svg();
  if (doc.rfind("<?xml", 0) == 0) doc.erase(0, doc.find("?>") + 2);
  doc.erase(0, doc.find('<'));
  // Cairo numbers glyphs, clips and surfaces from 1 in every document: the ids of two inline
  // SVGs collide, and a browser draws one picture's text with the other's glyphs.
  doc = replace_all(std::move(doc), "id=\"", "id=\"" + id_prefix);
  doc = replace_all(std::move(doc), "href=\"#", "href=\"#" + id_prefix);
  return replace_all(std::move(doc), "url(#", "url(#" + id_prefix);
}

std::string CairoCanvas::pdf() const {
  std::string bytes;
  {
    Surface pdf(cairo_pdf_surface_create_for_stream(append, &bytes, width() * kPtPerPx,
                                                    height() * kPtPerPx));
    check(cairo_surface_status(pdf.s), "PDF");
    replay(pdf.s, rec_->surface, kPtPerPx);
    cairo_surface_finish(pdf.s);
    check(cairo_surface_status(pdf.s), "PDF");
  }
  return bytes;
}

void CairoCanvas::save(const std::filesystem::path& out) const {
  const PictureFormat format = picture_format(out);
  std::string bytes;
  try {
    bytes = format == PictureFormat::png ? png() : format == PictureFormat::svg ? svg() : pdf();
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(out.string() + ": cannot draw (" + e.what() + ")");
  }
  write_bytes(out, bytes);
}

RgbaImage read_png(const std::filesystem::path& file) {
  Surface png(cairo_image_surface_create_from_png(file.c_str()));
  if (cairo_surface_status(png.s) != CAIRO_STATUS_SUCCESS)
    throw InputError(file.string(), "",
                     std::string("not a readable PNG (") +
                         cairo_status_to_string(cairo_surface_status(png.s)) + ")");
  // Grey, RGB or palette PNGs come in other cairo formats: paint them onto ARGB32.
  Surface argb(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, cairo_image_surface_get_width(png.s),
                                          cairo_image_surface_get_height(png.s)));
  replay(argb.s, png.s, 1.0);
  return to_rgba(argb.s);
}

}  // namespace rownav::io
