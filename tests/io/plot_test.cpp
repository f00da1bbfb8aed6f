#include "rownav/io/plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "rownav/io/cairo_canvas.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

TEST(NiceTicks, OneTwoFiveSteps) {
  EXPECT_EQ(nice_ticks(0, 0.173), (std::vector<double>{0, 0.05, 0.1, 0.15}));
  EXPECT_EQ(nice_ticks(0, 100), (std::vector<double>{0, 20, 40, 60, 80, 100}));
  EXPECT_EQ(nice_ticks(-1.3, 1.3), (std::vector<double>{-1, -0.5, 0, 0.5, 1}));
  EXPECT_EQ(nice_ticks(3, 3), (std::vector<double>{3}));
  EXPECT_TRUE(nice_ticks(0, std::nan("")).empty());
  EXPECT_EQ(nice_ticks(1e6, 1e6 + 7, 7).size(), 8u);
  EXPECT_EQ(tick_label(0.1, 0.05), "0.10");
  EXPECT_EQ(tick_label(40, 20), "40");
  EXPECT_EQ(tick_label(-1e-17, 0.5), "0.0");
}

Series wave(const std::string& label, Color c, double phase) {
  Series s{label, {}, {}, c};
  for (int i = 0; i <= 200; ++i) {
    s.x.push_back(i * 0.5);
    s.y.push_back(0.1 * std::sin(i * 0.05 + phase));
  }
  return s;
}

bool is_red(Color c) {
  return c.r > 180 && c.g < 120 && c.b < 120;
}

TEST(Plot, NanBreaksTheLine) {
  Series s = wave("lateral error", Color::hex("#d62728"), 0.0);
  s.y[50] = std::nan("");
  s.y[120] = std::nan("");
  CairoCanvas c;
  draw_plot(c, {s}, PlotOptions{});
  const RgbaImage img = c.raster();
  const Eigen::AlignedBox2d plot = c.plot_rect();
  const auto red_in_column = [&](double x) {
    const int px = static_cast<int>(c.to_pixel({x, 0}).x());
    int red = 0;
    for (int y = static_cast<int>(plot.min().y()); y < static_cast<int>(plot.max().y()); ++y)
      red += is_red(img.at(px, y));
    return red;
  };
  EXPECT_EQ(red_in_column(25.0), 0);  // between points 49 and 51
  EXPECT_EQ(red_in_column(60.0), 0);  // between 119 and 121
  EXPECT_GT(red_in_column(24.0), 0);  // the line runs on either side
  EXPECT_GT(red_in_column(26.0), 0);
  EXPECT_GT(red_in_column(61.0), 0);
}

TEST(Plot, WritesPngAndSvgOfTheRequestedSize) {
  Series a = wave("lateral error [m]", Color::hex("#d62728"), 0.0);
  Series b = wave("heading error [rad]", Color::hex("#1f77b4"), 1.0);
  b.dashed = true;
  for (int i = 60; i < 70; ++i) b.y[i] = std::nan("");
  PlotOptions o;
  o.title = "tracking error";
  o.x_label = "time [s]";
  o.y_label = "error";
  o.bands = {{30, 45}, {80, 90}};
  for (const char* name : {"rownav_plot.png", "rownav_plot.svg", "rownav_plot.pdf"})
    write_plot(fs::temp_directory_path() / name, {a, b}, o);
  const RgbaImage img = read_png(fs::temp_directory_path() / "rownav_plot.png");
  EXPECT_EQ(img.width, 900);
  EXPECT_EQ(img.height, 350);
  // The zero crossing of series a at x = 0 sits at the vertical middle of the data range.
  CairoCanvas c;
  draw_plot(c, {a, b}, o);
  const Eigen::Vector2d p = c.to_pixel({20.0, 0.1 * std::sin(40 * 0.05)});
  int red = 0;
  for (int dy = -2; dy <= 2; ++dy) {
    const Color px = img.at(static_cast<int>(p.x()), static_cast<int>(p.y()) + dy);
    red += px.r > 180 && px.g < 120;
  }
  EXPECT_GT(red, 0);
  EXPECT_GT(fs::file_size(fs::temp_directory_path() / "rownav_plot.svg"), 2000u);
  EXPECT_GT(fs::file_size(fs::temp_directory_path() / "rownav_plot.pdf"), 2000u);
  EXPECT_THROW(write_plot(fs::temp_directory_path() / "p.jpg", {a}, o), InputError);
}

TEST(Plot, YRangeIsHonouredAndEmptyPlotDraws) {
  PlotOptions o;
  o.y_range = std::make_pair(-0.5, 0.5);
  CairoCanvas c;
  draw_plot(c, {wave("a", Color::hex("#000000"), 0.0)}, o);
  EXPECT_NEAR(c.world_box().min().y(), -0.5, 1e-12);
  EXPECT_NEAR(c.world_box().max().y(), 0.5, 1e-12);
  CairoCanvas empty;
  EXPECT_NO_THROW(draw_plot(empty, {}, PlotOptions{}));
  EXPECT_EQ(empty.width(), 900);
}

}  // namespace
}  // namespace rownav::io
