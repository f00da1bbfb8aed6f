#pragma once
/// @file top_view.hpp Top views of a field with ground truth and LiDAR data: soil, canopy bands,
/// plants, posts, weeds, row and corridor centre lines, robot footprints, scans, clouds, paths,
/// with a legend column on the right and a scale bar, axes arrow and colour bar underneath.
///
/// Typical use:
/// @code
///   auto canvas = make_canvas("view.png");
///   TopViewOptions o; o.title = "vineyard"; o.extra_legend = {{"robot", robot_legend_style()}};
///   draw_field(*canvas, field, o);        // sets the view: call it first
///   draw_robot(*canvas, T_world_base, 1.2, 0.7, Color::hex("#d62728"));
///   canvas->save("view.png");
/// @endcode
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/io/canvas.hpp"
#include "rownav/sim/field.hpp"

namespace rownav::io {

/// A legend entry: label and the style its swatch is drawn with (filled: a square, else a line).
using LegendEntry = std::pair<std::string, Style>;

/// What draw_field shows and how.
struct TopViewOptions {
  double pixels_per_metre = 20;  ///< [px/m]
  /// World box shown; default: the rows' bounds grown by the headland width.
  std::optional<Eigen::AlignedBox2d> window;
  bool plants = true;            ///< vines / trees / crops as footprint circles
  bool posts = true;             ///< posts (grey squares) and end posts (dark squares)
  bool weeds = true;             ///< weeds (light green dots)
  bool row_lines = true;         ///< row centre lines (thin dark green)
  bool corridor_centres = true;  ///< corridor centre lines (dashed blue)
  bool legend = true;            ///< legend column on the right
  bool scale_bar = true;         ///< scale bar and axes arrow underneath
  std::string title;             ///< drawn above the field when not empty
  /// Entries for what the caller draws after draw_field (robot, scan, path), added to the legend.
  std::vector<LegendEntry> extra_legend;
};

/// Draws the field and sets the canvas view (call before the other draw_* functions).
void draw_field(Canvas& canvas, const sim::Field& field, const TopViewOptions& options);

/// Robot footprint (length x width centred on the base origin) and a heading arrow.
void draw_robot(Canvas& canvas, const core::Pose2& T_world_base, double length, double width,
                Color color);

/// Cloud points as dots coloured by world height (viridis) over [z_min, z_max], drawn low to high;
/// with `colour_bar`, a height colour bar goes under the picture. NaN / Inf points are skipped.
void draw_cloud(Canvas& canvas, const core::PointCloud& cloud_lidar,
                const Eigen::Isometry3d& T_world_lidar, double z_min, double z_max,
                bool colour_bar = true, double dot_radius_px = 1.3);

/// Valid scan returns as dots of one colour.
void draw_scan(Canvas& canvas, const core::Scan2D& scan, const core::Pose2& T_world_lidar,
               Color color, double dot_radius_px = 1.8);

/// A world path (trajectory, plan) as a polyline.
void draw_path(Canvas& canvas, const std::vector<Eigen::Vector2d>& path, const Style& style);

/// Legend box at the top of the right margin column.
void draw_legend(Canvas& canvas, const std::vector<LegendEntry>& entries);
/// Scale bar of a round length under the plot, right of the axes arrow.
void draw_scale_bar(Canvas& canvas);
/// World x / y axes arrow at the bottom-left, under the plot.
void draw_axes_arrow(Canvas& canvas);
/// Title above the plot.
void draw_title(Canvas& canvas, const std::string& title);
/// Horizontal colour bar (viridis over [lo, hi]) at the bottom-right, under the plot.
void draw_colour_bar(Canvas& canvas, double lo, double hi, const std::string& label);

/// Perceptual colour map (viridis, piecewise linear), t clamped to [0, 1].
Color viridis(double t);

/// Midline of two adjacent rows, from sampling both polylines at equal arc-length fractions.
std::vector<Eigen::Vector2d> corridor_centre(const sim::Row& a, const sim::Row& b,
                                             int samples = 64);

/// Legend entries for the field layers `options` enables.
std::vector<LegendEntry> field_legend(const TopViewOptions& options, sim::FieldKind kind);

/// Legend styles matching draw_robot / draw_scan, for TopViewOptions::extra_legend.
Style robot_legend_style(Color color);
Style scan_legend_style(Color color);

}  // namespace rownav::io
