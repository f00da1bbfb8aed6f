#include "rownav/io/top_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace rownav::io {

namespace {

const Color kInk = Color::hex("#222222");
const Color kSoil = Color::hex("#efe6d2");
const Color kFrame = Color::hex("#8a8170");
const Color kCanopy = Color::hex("#5aa02c").with_alpha(0.35);
const Color kCanopyEdge = Color::hex("#3d7a1c");
const Color kRowLine = Color::hex("#1f5e12");
const Color kCorridor = Color::hex("#1f6fd1");
const Color kWeed = Color::hex("#a9d65c");
const Color kPost = Color::hex("#9a9a9a");
const Color kEndPost = Color::hex("#3a3a3a");
constexpr int kLegendColumn = 200;  // [px] right margin holding the legend
constexpr int kUnderBand = 74;      // [px] bottom margin: axes arrow, scale bar, colour bar
constexpr double kLegendRow = 20;   // [px] legend line height

Color plant_colour(sim::PlantKind k) {
  switch (k) {
    case sim::PlantKind::tree:
      return Color::hex("#2d6a1f");
    case sim::PlantKind::crop:
      return Color::hex("#4caf50");
    default:
      return Color::hex("#2f7d32");  // vine
  }
}

Style filled(Color fill, Color stroke = {}, double width = 0.0) {
  return {stroke, fill, width, true, false};
}
Style stroked(Color stroke, double width, bool dashed = false) {
  return {stroke, {}, width, false, dashed};
}

double legend_height(std::size_t n) {
  return 16.0 + kLegendRow * static_cast<double>(n);
}

/// Largest 1 / 2 / 5 x 10^k not above x.
double round_down_nice(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= x) return m * p;
  return p;
}

std::string format_metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, v >= 1.0 ? "%.0f m" : "%.1f m", v);
  return buf;
}

/// Point at arc-length fraction f of a polyline.
Eigen::Vector2d point_at_fraction(const std::vector<Eigen::Vector2d>& pl, double total, double f) {
  double target = f * total;
  for (std::size_t i = 1; i < pl.size(); ++i) {
    const double l = (pl[i] - pl[i - 1]).norm();
    if (target <= l && l > 0.0) return pl[i - 1] + (pl[i] - pl[i - 1]) * (target / l);
    target -= l;
  }
  return pl.back();
}

void draw_plants(Canvas& c, const sim::Field& f, const TopViewOptions& o) {
  const double ppm = c.pixels_per_metre();
  for (const auto& p : f.plants) {
    const bool post = p.kind == sim::PlantKind::post || p.kind == sim::PlantKind::end_post;
    if (p.kind == sim::PlantKind::weed) {
      if (o.weeds) c.dot(p.position, std::max(1.5, p.radius * ppm), kWeed);
    } else if (post) {
      if (!o.posts) continue;
      const bool end = p.kind == sim::PlantKind::end_post;
      const double h = std::max(end ? 2.5 : 2.0, p.radius * ppm);
      const Eigen::Vector2d q = c.to_pixel(p.position);
      c.rect_px(q.array() - h, q.array() + h, filled(end ? kEndPost : kPost, kEndPost, 0.6));
    } else if (o.plants) {
      c.dot(p.position, std::max(1.6, p.radius * ppm), plant_colour(p.kind));
    }
  }
}

void draw_rows(Canvas& c, const sim::Field& f, const TopViewOptions& o) {
  c.begin_group("canopy");
  for (const auto& r : f.rows)
    c.polyline(r.polyline, stroked(kCanopy, 2.0 * r.half_width * c.pixels_per_metre()));
  c.end_group();
  if (o.row_lines) {
    c.begin_group("row_lines");
    for (const auto& r : f.rows) c.polyline(r.polyline, stroked(kRowLine, 1.0));
    c.end_group();
  }
  if (o.corridor_centres) {
    c.begin_group("corridor_centres");
    for (std::size_t i = 1; i < f.rows.size(); ++i)
      if (f.rows[i].block == f.rows[i - 1].block)
        c.polyline(corridor_centre(f.rows[i - 1], f.rows[i]), stroked(kCorridor, 1.5, true));
    c.end_group();
  }
}

}  // namespace

Color viridis(double t) {
  static const std::array<Color, 9> stops = {
      Color::hex("#440154"), Color::hex("#482878"), Color::hex("#3e4989"),
      Color::hex("#31688e"), Color::hex("#26828e"), Color::hex("#1f9e89"),
      Color::hex("#35b779"), Color::hex("#6ece58"), Color::hex("#fde725")};
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 0.0;
  const double s = t * (stops.size() - 1);
  const std::size_t i = std::min(stops.size() - 2, static_cast<std::size_t>(s));
  const double u = s - static_cast<double>(i);
  const auto mix = [u](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + (b - a) * u));
  };
  const Color &a = stops[i], &b = stops[i + 1];
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b), 255};
}

std::vector<Eigen::Vector2d> corridor_centre(const sim::Row& a, const sim::Row& b, int samples) {
  std::vector<Eigen::Vector2d> out;
  if (a.polyline.size() < 2 || b.polyline.size() < 2 || samples < 2) return out;
  const double la = a.length(), lb = b.length();
  // Rows may be stored in opposite directions: pair the nearer ends.
  const bool flip = (a.start() - b.start()).norm() > (a.start() - b.end()).norm();
  for (int i = 0; i < samples; ++i) {
    const double f = static_cast<double>(i) / (samples - 1);
    out.push_back(0.5 * (point_at_fraction(a.polyline, la, f) +
                         point_at_fraction(b.polyline, lb, flip ? 1.0 - f : f)));
  }
  return out;
}

std::vector<LegendEntry> field_legend(const TopViewOptions& o, sim::FieldKind kind) {
  std::vector<LegendEntry> e{{"canopy", filled(kCanopy, kCanopyEdge, 1.0)}};
  const char* plant = kind == sim::FieldKind::orchard    ? "tree"
                      : kind == sim::FieldKind::row_crop ? "crop"
                                                         : "vine";
  const sim::PlantKind pk = kind == sim::FieldKind::orchard    ? sim::PlantKind::tree
                            : kind == sim::FieldKind::row_crop ? sim::PlantKind::crop
                                                               : sim::PlantKind::vine;
  if (o.plants) e.emplace_back(plant, filled(plant_colour(pk)));
  if (o.posts) {
    e.emplace_back("post", filled(kPost, kEndPost, 0.6));
    e.emplace_back("end post", filled(kEndPost, kEndPost, 0.6));
  }
  if (o.weeds) e.emplace_back("weed", filled(kWeed));
  if (o.row_lines) e.emplace_back("row centre line", stroked(kRowLine, 1.0));
  if (o.corridor_centres) e.emplace_back("corridor centre", stroked(kCorridor, 1.5, true));
  return e;
}

Style robot_legend_style(Color color) {
  return filled(color.with_alpha(0.3), color, 2.0);
}
Style scan_legend_style(Color color) {
  return filled(color);
}

void draw_field(Canvas& c, const sim::Field& field, const TopViewOptions& o) {
  Eigen::AlignedBox2d window;
  if (o.window) {
    window = *o.window;
  } else {
    window = field.row_bounds();
    if (window.isEmpty())
      window = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10));
    window.min().array() -= field.headland_width;
    window.max().array() += field.headland_width;
  }
  std::vector<LegendEntry> legend = field_legend(o, field.kind);
  legend.insert(legend.end(), o.extra_legend.begin(), o.extra_legend.end());
  Margins m{24, o.title.empty() ? 24 : 48, o.legend ? kLegendColumn : 24,
            o.scale_bar ? kUnderBand : 24};
  const double plot_h = std::ceil(window.sizes().y() * o.pixels_per_metre);
  if (o.legend)  // the legend column must fit beside the plot
    m.bottom = std::max(m.bottom, static_cast<int>(legend_height(legend.size()) - plot_h) + 8);
  c.set_view(window, o.pixels_per_metre, m);

  const Eigen::AlignedBox2d plot = c.plot_rect();
  c.begin_group("field", &plot);
  c.rect_px(plot.min(), plot.max(), filled(kSoil));
  draw_rows(c, field, o);
  c.begin_group("plants");
  draw_plants(c, field, o);
  c.end_group();
  c.end_group();
  c.rect_px(plot.min(), plot.max(), stroked(kFrame, 1.0));
  if (!o.title.empty()) draw_title(c, o.title);
  if (o.legend) draw_legend(c, legend);
  if (o.scale_bar) {
    draw_axes_arrow(c);
    draw_scale_bar(c);
  }
}

void draw_robot(Canvas& c, const core::Pose2& T, double length, double width, Color color) {
  const Eigen::AlignedBox2d plot = c.plot_rect();
  c.begin_group("robot", &plot);
  const double hl = length / 2.0, hw = width / 2.0;
  c.polygon({T * Eigen::Vector2d(hl, hw), T * Eigen::Vector2d(-hl, hw),
             T * Eigen::Vector2d(-hl, -hw), T * Eigen::Vector2d(hl, -hw)},
            robot_legend_style(color));
  const double tip = hl + 0.35 * width, head = 0.3 * width;
  c.line(T.translation(), T * Eigen::Vector2d(tip - head, 0.0), stroked(color, 2.5));
  c.polygon({T * Eigen::Vector2d(tip, 0.0), T * Eigen::Vector2d(tip - head, 0.5 * head),
             T * Eigen::Vector2d(tip - head, -0.5 * head)},
            filled(color, color, 1.0));
  c.dot(T.translation(), 2.5, color);
  c.end_group();
}

void draw_cloud(Canvas& c, const core::PointCloud& cloud, const Eigen::Isometry3d& T, double z_min,
                double z_max, bool colour_bar, double r) {
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(cloud.size());
  for (const auto& p : cloud.points)
    if (p.finite()) pts.push_back(T * Eigen::Vector3d(p.x, p.y, p.z));
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return a.z() < b.z(); });
  const double span = std::max(z_max - z_min, 1e-9);
  const Eigen::AlignedBox2d plot = c.plot_rect();
  c.begin_group("cloud", &plot);
  for (const auto& p : pts) c.dot(p.head<2>(), r, viridis((p.z() - z_min) / span));
  c.end_group();
  if (colour_bar) draw_colour_bar(c, z_min, z_max, "height [m]");
}

void draw_scan(Canvas& c, const core::Scan2D& scan, const core::Pose2& T, Color color, double r) {
  const Eigen::AlignedBox2d plot = c.plot_rect();
  c.begin_group("scan", &plot);
  for (const auto& p : scan.to_points()) c.dot(T * p.cast<double>(), r, color);
  c.end_group();
}

void draw_path(Canvas& c, const std::vector<Eigen::Vector2d>& path, const Style& style) {
  const Eigen::AlignedBox2d plot = c.plot_rect();
  c.begin_group("path", &plot);
  c.polyline(path, style);
  c.end_group();
}

void draw_legend(Canvas& c, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) return;
  const Eigen::AlignedBox2d plot = c.plot_rect();
  const Eigen::Vector2d lo(plot.max().x() + 14, plot.min().y());
  const Eigen::Vector2d hi(c.width() - 10.0, lo.y() + legend_height(entries.size()));
  c.begin_group("legend");
  c.rect_px(lo, hi, filled(Color::hex("#ffffff"), Color::hex("#c8c8c8"), 1.0));
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& [label, s] = entries[i];
    const double y = lo.y() + 8.0 + kLegendRow * (i + 0.5);
    const Eigen::Vector2d sw(lo.x() + 20, y);  // swatch centre
    if (s.filled && s.stroke_width_px <= 0.0)
      c.circle_px(sw, 4.0, s);
    else if (s.filled)
      c.rect_px(sw.array() - 6.0, sw.array() + 6.0, s);
    else
      c.line_px({sw.x() - 11, y}, {sw.x() + 11, y},
                {s.stroke, {}, std::min(s.stroke_width_px, 4.0), false, s.dashed});
    c.text_px({lo.x() + 40, y}, label, 12, kInk);
  }
  c.end_group();
}

void draw_scale_bar(Canvas& c) {
  const Eigen::AlignedBox2d plot = c.plot_rect();
  const double len_m = round_down_nice(plot.sizes().x() / c.pixels_per_metre() / 5.0);
  const double len_px = len_m * c.pixels_per_metre();
  const double x0 = plot.min().x() + 70, y = plot.max().y() + 30;
  c.begin_group("scale_bar");
  for (int k = 0; k < 4; ++k) {
    const Color fill = k % 2 ? Color::hex("#ffffff") : kInk;
    c.rect_px({x0 + len_px * k / 4, y - 3}, {x0 + len_px * (k + 1) / 4, y + 3},
              filled(fill, kInk, 1.0));
  }
  c.text_px({x0, y + 16}, "0", 12, kInk, Align::centre);
  c.text_px({x0 + len_px, y + 16}, format_metres(len_m), 12, kInk, Align::centre);
  c.end_group();
}

void draw_axes_arrow(Canvas& c) {
  const Eigen::AlignedBox2d plot = c.plot_rect();
  const Eigen::Vector2d o(plot.min().x() + 12, plot.max().y() + 58);
  const Style s = stroked(kInk, 1.5);
  c.begin_group("axes");
  c.line_px(o, o + Eigen::Vector2d(30, 0), s);
  c.line_px(o, o - Eigen::Vector2d(0, 30), s);
  c.polygon_px(
      {o + Eigen::Vector2d(36, 0), o + Eigen::Vector2d(28, -4), o + Eigen::Vector2d(28, 4)},
      filled(kInk));
  c.polygon_px(
      {o - Eigen::Vector2d(0, 36), o + Eigen::Vector2d(-4, -28), o + Eigen::Vector2d(4, -28)},
      filled(kInk));
  c.text_px(o + Eigen::Vector2d(40, 0), "x", 12, kInk);
  c.text_px(o + Eigen::Vector2d(8, -34), "y", 12, kInk);
  c.end_group();
}

void draw_title(Canvas& c, const std::string& title) {
  c.text_px({c.plot_rect().min().x(), 24}, title, 18, kInk);
}

void draw_colour_bar(Canvas& c, double lo, double hi, const std::string& label) {
  const Eigen::AlignedBox2d plot = c.plot_rect();
  const double w = 160, x1 = plot.max().x(), x0 = x1 - w, y = plot.max().y() + 24;
  c.begin_group("colour_bar");
  constexpr int kSteps = 40;
  for (int k = 0; k < kSteps; ++k)
    c.rect_px({x0 + w * k / kSteps, y}, {x0 + w * (k + 1) / kSteps + 0.5, y + 10},
              filled(viridis((k + 0.5) / kSteps)));
  c.rect_px({x0, y}, {x1, y + 10}, stroked(kInk, 1.0));
  char buf[32];
  for (int k = 0; k <= 2; ++k) {
    std::snprintf(buf, sizeof buf, "%.1f", lo + (hi - lo) * k / 2.0);
    c.text_px({x0 + w * k / 2.0, y + 22}, buf, 12, kInk, Align::centre);
  }
  c.text_px({x0 - 8, y + 5}, label, 12, kInk, Align::right);
  c.end_group();
}

}  // namespace rownav::io
