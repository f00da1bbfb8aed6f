#include "rownav/io/canvas.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "rownav/io/cairo_canvas.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("rownav_" + name);
}

const Eigen::AlignedBox2d kWorld(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 5));

bool is_red(Color c) {
  return c.r > 200 && c.g < 80 && c.b < 80;
}

TEST(Color, ParsesHex) {
  EXPECT_EQ(Color::hex("#40b255"), (Color{0x40, 0xb2, 0x55, 255}));
  EXPECT_EQ(Color::hex("ff000080").a, 0x80);
  EXPECT_EQ(Color::hex("#40b255").to_hex(), "#40b255");
  EXPECT_THROW(Color::hex("#12"), std::invalid_argument);
  EXPECT_THROW(Color::hex("#zz0000"), std::invalid_argument);
}

TEST(Canvas, WorldToPixelHasYUp) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 40);
  EXPECT_EQ(c.width(), 10 * 20 + 80);
  EXPECT_EQ(c.height(), 5 * 20 + 80);
  EXPECT_TRUE(c.to_pixel({0, 0}).isApprox(Eigen::Vector2d(40, 140)));   // bottom-left
  EXPECT_TRUE(c.to_pixel({10, 5}).isApprox(Eigen::Vector2d(240, 40)));  // top-right
  EXPECT_LT(c.to_pixel({0, 1}).y(), c.to_pixel({0, 0}).y());            // y up = pixel up
  EXPECT_TRUE(c.to_world(c.to_pixel({3.3, 1.7})).isApprox(Eigen::Vector2d(3.3, 1.7)));
}

TEST(Canvas, FitKeepsAspect) {
  CairoCanvas c;
  c.set_view_fit(kWorld, 400, 400, 0);
  EXPECT_NEAR(c.pixels_per_metre(), 40.0, 1e-9);
  EXPECT_TRUE(c.to_pixel({5, 2.5}).isApprox(Eigen::Vector2d(200, 200)));
}

TEST(Canvas, FormatFollowsTheExtension) {
  EXPECT_EQ(picture_format("a.png"), PictureFormat::png);
  EXPECT_EQ(picture_format("a.SVG"), PictureFormat::svg);
  EXPECT_EQ(picture_format("dir.x/a.Pdf"), PictureFormat::pdf);
  EXPECT_THROW(make_canvas("picture.bmp"), InputError);
  EXPECT_THROW(make_canvas("picture"), InputError);
  for (const char* name : {"a.png", "a.svg", "a.pdf"})
    EXPECT_NE(dynamic_cast<CairoCanvas*>(make_canvas(name).get()), nullptr) << name;
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 40);
  EXPECT_THROW(c.save(temp("picture.jpg")), InputError);
}

TEST(CairoCanvas, RedLineAcrossIsRedAlongAndWhiteAway) {
  auto canvas = make_canvas(temp("line.png"));
  canvas->set_view(kWorld, 20.0, 40);
  canvas->line({0, 2.5}, {10, 2.5}, {Color::hex("#ff0000"), {}, 3.0});
  canvas->save(temp("line.png"));
  const RgbaImage img = read_png(temp("line.png"));
  ASSERT_EQ(img.width, 280);
  ASSERT_EQ(img.height, 180);
  const int y = static_cast<int>(canvas->to_pixel({0, 2.5}).y());  // 90
  for (int x = 45; x < 235; x += 10) {
    EXPECT_TRUE(is_red(img.at(x, y)) || is_red(img.at(x, y - 1))) << x;
    EXPECT_EQ(img.at(x, y - 6), (Color{255, 255, 255, 255})) << x;
    EXPECT_EQ(img.at(x, y + 6), (Color{255, 255, 255, 255})) << x;
  }
  EXPECT_EQ(img.at(10, y), (Color{255, 255, 255, 255}));  // the line stops at its end
}

TEST(CairoCanvas, PngHasSignatureAndSize) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 40);
  c.circle({5, 2.5}, 1.0, {Color::hex("#000000"), Color::hex("#40b255"), 1.0, true});
  const std::string png = c.png();
  ASSERT_GT(png.size(), 33u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  const auto be32 = [&](std::size_t i) {
    return (std::uint32_t(std::uint8_t(png[i])) << 24) |
           (std::uint32_t(std::uint8_t(png[i + 1])) << 16) |
           (std::uint32_t(std::uint8_t(png[i + 2])) << 8) | std::uint32_t(std::uint8_t(png[i + 3]));
  };
  EXPECT_EQ(be32(16), 280u);  // IHDR width, height
  EXPECT_EQ(be32(20), 180u);
}

TEST(CairoCanvas, FilledCircleAreaIsPiRSquared) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 0);
  const double r_m = 1.5, r_px = r_m * 20.0;
  c.circle({5, 2.5}, r_m, {{}, Color::hex("#000000"), 0.0, true});
  const RgbaImage img = c.raster();
  double covered = 0.0;  // darkness summed = anti-aliased area
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) covered += (255 - img.at(x, y).r) / 255.0;
  EXPECT_NEAR(covered, std::numbers::pi * r_px * r_px, 0.01 * std::numbers::pi * r_px * r_px);
  int grey = 0;  // anti-aliased: the rim has partial coverage
  for (int x = 0; x < img.width; ++x) grey += img.at(x, img.height / 2 + 20).r % 255 != 0;
  EXPECT_GT(grey, 0);
}

TEST(CairoCanvas, PolygonEvenOddAndAlphaBlend) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 0);
  // Outer square with an inner square: even-odd leaves a hole.
  std::vector<Eigen::Vector2d> ring{{1, 1}, {4, 1}, {4, 4}, {1, 4}, {1, 1},
                                    {2, 2}, {3, 2}, {3, 3}, {2, 3}, {2, 2}};
  c.polygon(ring, {{}, Color::hex("#0000ff"), 0.0, true});
  // 50 % black over white gives mid grey.
  c.rect_px({150, 10}, {180, 40}, {{}, Color{0, 0, 0, 128}, 0.0, true});
  const RgbaImage img = c.raster();
  const Eigen::Vector2i inside = c.to_pixel({1.5, 1.5}).cast<int>();
  const Eigen::Vector2i hole = c.to_pixel({2.5, 2.5}).cast<int>();
  EXPECT_EQ(img.at(inside.x(), inside.y()), (Color{0, 0, 255, 255}));
  EXPECT_EQ(img.at(hole.x(), hole.y()), (Color{255, 255, 255, 255}));
  EXPECT_NEAR(img.at(165, 25).r, 127, 2);
}

TEST(CairoCanvas, DashedLineHasGaps) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 0);
  c.line({0, 2.5}, {10, 2.5}, {Color::hex("#000000"), {}, 2.0, false, true});
  const RgbaImage img = c.raster();
  const int y = static_cast<int>(c.to_pixel({0, 2.5}).y());
  int ink = 0, blank = 0;
  for (int x = 0; x < img.width; ++x) (img.at(x, y).r < 128 ? ink : blank)++;
  EXPECT_GT(ink, img.width / 3);
  EXPECT_GT(blank, img.width / 5);
}

TEST(CairoCanvas, TextDrawsInkAndClipStopsIt) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 0);
  c.text_px({10, 20}, "Hi 0.5 m", 12, Color::hex("#000000"));
  c.text_px({10, 80}, "bad \xff utf-8", 12, Color::hex("#000000"));  // drawn with '?'
  c.text_px({10, 95}, "\xed\xa0\x80 surrogate", 12, Color::hex("#000000"));
  c.text_px({100, 95}, "\xc3\xa9t\xc3\xa9 \xc2\xb0", 12, Color::hex("#000000"));  // UTF-8 kept
  const Eigen::AlignedBox2d clip(Eigen::Vector2d(100, 0), Eigen::Vector2d(200, 100));
  c.begin_group("clipped", &clip);
  c.line_px({0, 60}, {199, 60}, {Color::hex("#ff0000"), {}, 4.0});
  c.end_group();
  const RgbaImage img = c.raster();
  const auto ink_in = [&](int y0, int y1) {
    int ink = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 5; x < 90; ++x) ink += img.at(x, y).r < 128;
    return ink;
  };
  EXPECT_GT(ink_in(10, 30), 30);
  EXPECT_GT(ink_in(70, 90), 30);  // an invalid byte does not poison the drawing
  EXPECT_FALSE(is_red(img.at(50, 60)));
  EXPECT_TRUE(is_red(img.at(150, 60)));
  // Real font metrics: proportional, and growing with the size.
  EXPECT_LT(c.text_width("iiii", 12), c.text_width("WWWW", 12));
  EXPECT_NEAR(c.text_width("label", 24), 2.0 * c.text_width("label", 12), 0.5);
  EXPECT_EQ(c.text_width("", 12), 0.0);
}

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

/// XML well-formedness as far as these documents need it: one root element, every opening tag
/// closed (self-closing or matched) in order, every attribute value quoted.
bool well_formed(const std::string& doc, const std::string& root) {
  std::vector<std::string> stack;
  int roots = 0;
  const std::regex tag(R"(<(/?)([a-zA-Z][\w:-]*)((?:\s+[\w:-]+="[^"]*")*)\s*(/?)>)");
  std::size_t tags = 0;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), tag); it != std::sregex_iterator();
       ++it, ++tags) {
    const auto& m = *it;
    if (stack.empty() && m[1] != "/") roots += m[2] == root ? 1 : 100;
    if (m[4] == "/") continue;
    if (m[1] == "/") {
      if (stack.empty() || stack.back() != m[2]) return false;
      stack.pop_back();
    } else {
      stack.push_back(m[2]);
    }
  }
  // Every '<' that is not the XML declaration opened or closed a matched tag.
  return stack.empty() && roots == 1 &&
         tags == static_cast<std::size_t>(count(doc, "<") - count(doc, "<?xml"));
}

TEST(CairoCanvas, SvgIsWellFormedWithTheDrawing) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 40);
  const Eigen::AlignedBox2d clip(Eigen::Vector2d(40, 40), Eigen::Vector2d(240, 140));
  c.begin_group("field", &clip);
  c.line({0, 0}, {1.234567, 1}, {Color::hex("#ff0000"), {}, 2.0, false, true});
  c.polygon({{0, 0}, {1, 0}, {1, 1}}, {Color::hex("#000000"), Color::hex("#40b25580"), 1, true});
  c.circle({5, 2}, 0.5, {{}, Color::hex("#00ff00"), 0, true});
  c.begin_group("inner");  // left open: the outputs do not depend on it
  c.text_px({120, 80}, "a < b & c", 12, Color::hex("#000000"), true);
  const std::string doc = c.svg();
  EXPECT_EQ(c.svg(), doc);  // reproducible
  EXPECT_EQ(doc.rfind("<?xml", 0), 0u);
  EXPECT_TRUE(well_formed(doc, "svg")) << doc;
  EXPECT_NE(doc.find("width=\"280px\" height=\"180px\" viewBox=\"0 0 280 180\""),
            std::string::npos);
  EXPECT_NE(doc.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(doc.find("fill-opacity:0.5"), std::string::npos);  // 0x80 / 255
  EXPECT_GE(count(doc, "<clipPath"), 1);
  // Text as glyph outlines: one glyph use per character of "a < b & c" (spaces included).
  EXPECT_EQ(count(doc, "<use xlink:href=\"#glyph"), 9);
  c.save(temp("canvas.svg"));
  std::ifstream f(temp("canvas.svg"));
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), doc);
}

TEST(CairoCanvas, InlineSvgHasItsOwnIds) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 40);
  const Eigen::AlignedBox2d clip(Eigen::Vector2d(40, 40), Eigen::Vector2d(240, 140));
  c.begin_group("field", &clip);
  c.text_px({50, 50}, "top view", 12, Color::hex("#000000"));
  c.end_group();
  const std::string doc = c.svg_inline("top-");
  EXPECT_EQ(doc.rfind("<svg", 0), 0u);  // no XML declaration inside HTML
  EXPECT_TRUE(well_formed(doc, "svg"));
  EXPECT_GT(count(doc, "id=\""), 0);
  EXPECT_EQ(count(doc, "id=\""), count(doc, "id=\"top-"));
  EXPECT_EQ(count(doc, "href=\"#"), count(doc, "href=\"#top-"));
  EXPECT_EQ(count(doc, "url(#"), count(doc, "url(#top-"));
  EXPECT_GT(count(doc, "url(#top-clip"), 0);
}

TEST(CairoCanvas, PdfHasHeaderPageSizeAndTrailer) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 40);
  c.line({0, 0}, {10, 5}, {Color::hex("#1f77b4"), {}, 2.0});
  c.text_px({10, 10}, "pdf", 12, Color::hex("#000000"));
  c.save(temp("canvas.pdf"));
  std::ifstream f(temp("canvas.pdf"), std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string pdf = ss.str();
  EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
  EXPECT_NE(pdf.find("/MediaBox [ 0 0 210 135 ]"), std::string::npos);  // 280 x 180 px at 0.75
  EXPECT_NE(pdf.find("%%EOF"), std::string::npos);
  EXPECT_NE(pdf.find("DejaVuSans"), std::string::npos);  // a real font, embedded
}

TEST(CairoCanvas, UnwritablePathIsOneLineNamingTheFile) {
  CairoCanvas c;
  c.set_view(kWorld, 20.0, 40);
  for (const char* name : {"x.png", "x.svg", "x.pdf"}) {
    const fs::path out = temp("no_such_dir") / name;
    try {
      c.save(out);
      ADD_FAILURE() << out << " was written";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(out.string() + ": cannot write", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(CairoCanvas, ReadPngRejectsNonPng) {
  const auto p = temp("not_a.png");
  std::ofstream(p) << "hello";
  EXPECT_THROW(read_png(p), InputError);
  EXPECT_THROW(read_png(temp("no_such.png")), InputError);
}

}  // namespace
}  // namespace rownav::io
