#pragma once
/// @file plot.hpp Line plots (error over time / distance) as PNG, SVG or PDF: nice ticks, grid,
/// axis labels, legend, shaded x intervals; NaN breaks a line.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rownav/io/canvas.hpp"

namespace rownav::io {

/// One line of a plot. x and y have the same length; a NaN / Inf y (or x) breaks the line.
struct Series {
  std::string label;
  std::vector<double> x, y;
  Color color = Color::hex("#1f77b4");
  bool dashed = false;
  bool markers = false;  ///< a dot at every point
};

/// Plot layout.
struct PlotOptions {
  std::string title, x_label, y_label;
  int width_px = 900;
  int height_px = 350;
  std::optional<std::pair<double, double>> y_range;  ///< default: the data range, padded
  std::vector<std::pair<double, double>> bands;      ///< shaded x intervals, e.g. headland turns
  std::string band_label = "headland";               ///< legend label of the bands
};

/// Draws the plot on `canvas` (sets its view to width_px x height_px).
void draw_plot(Canvas& canvas, const std::vector<Series>& series, const PlotOptions& options);

/// Draws and saves a plot; the format follows the extension (.png / .svg / .pdf, else
/// io::InputError).
void write_plot(const std::filesystem::path& out, const std::vector<Series>& series,
                const PlotOptions& options);

/// Round tick values (1 / 2 / 5 x 10^k steps) inside [lo, hi], about `target_count` of them.
/// Values are the closest doubles to the decimal ticks (0.15, not 0.15000000000000002).
std::vector<double> nice_ticks(double lo, double hi, int target_count = 5);

/// Tick label with as many decimals as the tick step needs.
std::string tick_label(double value, double step);

}  // namespace rownav::io
