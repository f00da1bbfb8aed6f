#include "rownav/io/canvas.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "rownav/io/bitmap_font.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/png_canvas.hpp"
#include "rownav/io/svg_canvas.hpp"

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
  SvgCanvas c;
  c.set_view(kWorld, 20.0, 40);
  EXPECT_EQ(c.width(), 10 * 20 + 80);
  EXPECT_EQ(c.height(), 5 * 20 + 80);
  EXPECT_TRUE(c.to_pixel({0, 0}).isApprox(Eigen::Vector2d(40, 140)));   // bottom-left
  EXPECT_TRUE(c.to_pixel({10, 5}).isApprox(Eigen::Vector2d(240, 40)));  // top-right
  EXPECT_LT(c.to_pixel({0, 1}).y(), c.to_pixel({0, 0}).y());            // y up = pixel up
  EXPECT_TRUE(c.to_world(c.to_pixel({3.3, 1.7})).isApprox(Eigen::Vector2d(3.3, 1.7)));
}

TEST(Canvas, FitKeepsAspect) {
  SvgCanvas c;
  c.set_view_fit(kWorld, 400, 400, 0);
  EXPECT_NEAR(c.pixels_per_metre(), 40.0, 1e-9);
  EXPECT_TRUE(c.to_pixel({5, 2.5}).isApprox(Eigen::Vector2d(200, 200)));
}

TEST(Canvas, UnknownExtensionIsInputError) {
  EXPECT_THROW(make_canvas("picture.bmp"), InputError);
  EXPECT_THROW(make_canvas("picture"), InputError);
  EXPECT_NE(dynamic_cast<SvgCanvas*>(make_canvas("a.SVG").get()), nullptr);
  EXPECT_NE(dynamic_cast<PngCanvas*>(make_canvas("a.png").get()), nullptr);
}

TEST(PngCanvas, RedLineAcrossIsRedAlongAndWhiteAway) {
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

TEST(PngCanvas, FilledCircleAreaIsPiRSquared) {
  PngCanvas c;
  c.set_view(kWorld, 20.0, 0);
  const double r_m = 1.5, r_px = r_m * 20.0;
  c.circle({5, 2.5}, r_m, {{}, Color::hex("#000000"), 0.0, true});
  double covered = 0.0;  // darkness summed = anti-aliased area
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) covered += (255 - c.image().at(x, y).r) / 255.0;
  EXPECT_NEAR(covered, std::numbers::pi * r_px * r_px, 0.05 * std::numbers::pi * r_px * r_px);
}

TEST(PngCanvas, PolygonEvenOddAndAlphaBlend) {
  PngCanvas c;
  c.set_view(kWorld, 20.0, 0);
  // Outer square with an inner square: even-odd leaves a hole.
  std::vector<Eigen::Vector2d> ring{{1, 1}, {4, 1}, {4, 4}, {1, 4}, {1, 1},
                                    {2, 2}, {3, 2}, {3, 3}, {2, 3}, {2, 2}};
  c.polygon(ring, {{}, Color::hex("#0000ff"), 0.0, true});
  const Eigen::Vector2i inside = c.to_pixel({1.5, 1.5}).cast<int>();
  const Eigen::Vector2i hole = c.to_pixel({2.5, 2.5}).cast<int>();
  EXPECT_EQ(c.image().at(inside.x(), inside.y()), (Color{0, 0, 255, 255}));
  EXPECT_EQ(c.image().at(hole.x(), hole.y()), (Color{255, 255, 255, 255}));
  // 50 % black over white gives mid grey.
  c.rect_px({150, 10}, {180, 40}, {{}, Color{0, 0, 0, 128}, 0.0, true});
  EXPECT_NEAR(c.image().at(165, 25).r, 127, 2);
}

TEST(PngCanvas, DashedLineHasGaps) {
  PngCanvas c;
  c.set_view(kWorld, 20.0, 0);
  c.line({0, 2.5}, {10, 2.5}, {Color::hex("#000000"), {}, 2.0, false, true});
  const int y = static_cast<int>(c.to_pixel({0, 2.5}).y());
  int ink = 0, blank = 0;
  for (int x = 0; x < c.width(); ++x) (c.image().at(x, y).r < 128 ? ink : blank)++;
  EXPECT_GT(ink, c.width() / 3);
  EXPECT_GT(blank, c.width() / 5);
}

TEST(PngCanvas, TextDrawsInkAndClipStopsIt) {
  PngCanvas c;
  c.set_view(kWorld, 20.0, 0);
  c.text_px({10, 20}, "Hi 0.5 m", 12, Color::hex("#000000"));
  int ink = 0;
  for (int y = 10; y < 30; ++y)
    for (int x = 5; x < 70; ++x) ink += c.image().at(x, y).r < 128;
  EXPECT_GT(ink, 30);
  const Eigen::AlignedBox2d clip(Eigen::Vector2d(100, 0), Eigen::Vector2d(200, 100));
  c.begin_group("clipped", &clip);
  c.line_px({0, 60}, {199, 60}, {Color::hex("#ff0000"), {}, 4.0});
  c.end_group();
  EXPECT_FALSE(is_red(c.image().at(50, 60)));
  EXPECT_TRUE(is_red(c.image().at(150, 60)));
  EXPECT_NE(glyph_row('A', 3), 0);
  EXPECT_EQ(glyph_row('\x7f', 0), glyph_row('?', 0));
}

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

/// Every opening tag is closed (self-closing or matched), in order.
bool balanced(const std::string& doc) {
  std::vector<std::string> stack;
  const std::regex tag(R"(<(/?)([a-zA-Z]+)[^>]*?(/?)>)");
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), tag); it != std::sregex_iterator();
       ++it) {
    const auto& m = *it;
    if (m[3] == "/") continue;
    if (m[1] == "/") {
      if (stack.empty() || stack.back() != m[2]) return false;
      stack.pop_back();
    } else {
      stack.push_back(m[2]);
    }
  }
  return stack.empty();
}

TEST(SvgCanvas, WellFormedWithExpectedElements) {
  SvgCanvas c;
  c.set_view(kWorld, 20.0, 40);
  const Eigen::AlignedBox2d clip(Eigen::Vector2d(40, 40), Eigen::Vector2d(240, 140));
  c.begin_group("field", &clip);
  c.line({0, 0}, {1.234567, 1}, {Color::hex("#ff0000"), {}, 2.0, false, true});
  c.polygon({{0, 0}, {1, 0}, {1, 1}}, {Color::hex("#000000"), Color::hex("#40b25580"), 1, true});
  c.circle({5, 2}, 0.5, {{}, Color::hex("#00ff00"), 0, true});
  c.begin_group("inner");  // left open: save() closes it
  c.text_px({10, 10}, "a < b & c", 12, Color::hex("#000000"), true);
  const std::string doc = c.document();
  EXPECT_TRUE(balanced(doc)) << doc;
  EXPECT_EQ(count(doc, "<line "), 1);
  EXPECT_EQ(count(doc, "<polygon "), 1);
  EXPECT_EQ(count(doc, "<circle "), 1);
  EXPECT_EQ(count(doc, "<text "), 1);
  EXPECT_EQ(count(doc, "<clipPath "), 1);
  EXPECT_NE(doc.find("a &lt; b &amp; c"), std::string::npos);
  EXPECT_NE(doc.find("x2=\"64.7\""), std::string::npos);  // 40 + 1.234567 * 20 rounded to 0.1
  EXPECT_NE(doc.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(doc.find("fill-opacity=\"0.502\""), std::string::npos);
  EXPECT_NE(doc.find("width=\"280\" height=\"180\""), std::string::npos);
  c.save(temp("canvas.svg"));
  std::ifstream f(temp("canvas.svg"));
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), doc);
}

TEST(PngCanvas, ReadPngRejectsNonPng) {
  const auto p = temp("not_a.png");
  std::ofstream(p) << "hello";
  EXPECT_THROW(read_png(p), InputError);
}

}  // namespace
}  // namespace rownav::io
