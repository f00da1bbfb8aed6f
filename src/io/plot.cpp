#include "rownav/io/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rownav::io {

namespace {

const Color kInk = Color::hex("#222222");
const Color kGrid = Color::hex("#e3e3e3");
const Color kBand = Color::hex("#f2b134").with_alpha(0.22);

struct Step {
  double mantissa = 1.0;  // 1, 2, 5 or 10
  int exponent = 0;       // step = mantissa * 10^exponent
  double value() const { return mantissa * std::pow(10.0, exponent); }
};

Step nice_step(double raw) {
  Step s;
  s.exponent = static_cast<int>(std::floor(std::log10(raw)));
  const double r = raw / std::pow(10.0, s.exponent);
  s.mantissa = r < 1.5 ? 1.0 : r < 3.0 ? 2.0 : r < 7.0 ? 5.0 : 10.0;
  return s;
}

/// k * step computed as an exact integer scaled by a power of ten (one rounding).
double tick_value(long long k, const Step& s) {
  const double n = static_cast<double>(k) * s.mantissa;
  return s.exponent >= 0 ? n * std::pow(10.0, s.exponent) : n / std::pow(10.0, -s.exponent);
}

/// Finite [lo, hi] of a set of values; nullopt when none.
std::optional<std::pair<double, double>> finite_range(const std::vector<Series>& series, bool x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      const double v = x ? s.x[i] : s.y[i];
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  if (lo > hi) return std::nullopt;
  return std::make_pair(lo, hi);
}

std::pair<double, double> widen_if_flat(std::pair<double, double> r) {
  if (r.second - r.first > 1e-12 * std::max(1.0, std::abs(r.first))) return r;
  const double d = std::max(0.5, 0.1 * std::abs(r.first));
  return {r.first - d, r.second + d};
}

void draw_series(Canvas& c, const Series& s) {
  const Style style{s.color, {}, 2.0, false, s.dashed};
  std::vector<Eigen::Vector2d> run;
  const auto flush = [&] {
    if (run.size() >= 2) c.polyline(run, style);
    run.clear();
  };
  for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
      flush();
      continue;
    }
    run.emplace_back(s.x[i], s.y[i]);
    if (s.markers) c.dot(run.back(), 3.0, s.color);
  }
  flush();
}

void draw_grid(Canvas& c, const std::vector<double>& xt, const std::vector<double>& yt) {
  const Eigen::AlignedBox2d w = c.world_box();
  const double ys = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double x : xt) c.line({x, w.min().y()}, {x, w.max().y()}, {kGrid, {}, 1.0});
  for (double y : yt) {
    const bool zero = std::abs(y) < 1e-9 * ys;
    c.line({w.min().x(), y}, {w.max().x(), y}, {zero ? Color::hex("#9a9a9a") : kGrid, {}, 1.0});
  }
}

void draw_ticks(Canvas& c, const std::vector<double>& xt, const std::vector<double>& yt) {
  const Eigen::AlignedBox2d p = c.plot_rect();
  const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ys = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  c.begin_group("ticks");
  for (double x : xt) {
    const double px = c.to_pixel({x, 0}).x();
    c.line_px({px, p.max().y()}, {px, p.max().y() + 5}, {kInk, {}, 1.0});
    c.text_px({px, p.max().y() + 15}, tick_label(x, xs), 12, kInk, Align::centre);
  }
  for (double y : yt) {
    const double py = c.to_pixel({0, y}).y();
    c.line_px({p.min().x() - 5, py}, {p.min().x(), py}, {kInk, {}, 1.0});
    c.text_px({p.min().x() - 8, py}, tick_label(y, ys), 12, kInk, Align::right);
  }
  c.end_group();
}

/// Top-left of the legend box: the plot corner whose box covers the fewest data points.
Eigen::Vector2d legend_corner(const Canvas& c, const std::vector<Series>& series,
                              const Eigen::Vector2d& size) {
  const Eigen::AlignedBox2d p = c.plot_rect();
  const double l = p.min().x() + 8, r = p.max().x() - 8 - size.x();
  const double t = p.min().y() + 8, b = p.max().y() - 8 - size.y();
  Eigen::Vector2d best(r, t);  // top-right wins ties
  std::size_t best_count = std::numeric_limits<std::size_t>::max();
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(r, t), Eigen::Vector2d(l, t),
                                        Eigen::Vector2d(r, b), Eigen::Vector2d(l, b)}) {
    const Eigen::AlignedBox2d box(corner, corner + size);
    std::size_t n = 0;
    for (const auto& s : series)
      for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        n += std::isfinite(s.x[i]) && std::isfinite(s.y[i]) &&
             box.contains(c.to_pixel({s.x[i], s.y[i]}));
    if (n < best_count) best_count = n, best = corner;
  }
  return best;
}

void draw_plot_legend(Canvas& c, const std::vector<Series>& series, const PlotOptions& o) {
  std::vector<std::pair<std::string, Style>> e;
  for (const auto& s : series)
    if (!s.label.empty()) e.emplace_back(s.label, Style{s.color, {}, 2.0, false, s.dashed});
  if (!o.bands.empty()) e.emplace_back(o.band_label, Style{{}, kBand, 0.0, true});
  if (e.empty()) return;
  double text_w = 0.0;
  for (const auto& [label, s] : e) text_w = std::max(text_w, c.text_width(label, 12));
  const Eigen::Vector2d size(text_w + 50, 18.0 * e.size() + 16);
  const Eigen::Vector2d lo = legend_corner(c, series, size), hi = lo + size;
  c.begin_group("legend");
  c.rect_px(lo, hi, {Color::hex("#c8c8c8"), Color::hex("#ffffff").with_alpha(0.88), 1.0, true});
  for (std::size_t i = 0; i < e.size(); ++i) {
    const double y = lo.y() + 8 + 18.0 * (i + 0.5);
    const auto& s = e[i].second;
    if (s.filled)
      c.rect_px({lo.x() + 8, y - 6}, {lo.x() + 30, y + 6}, s);
    else
      c.line_px({lo.x() + 8, y}, {lo.x() + 30, y}, s);
    c.text_px({lo.x() + 38, y}, e[i].first, 12, kInk);
  }
  c.end_group();
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || target_count < 1) return {};
  if (lo > hi) std::swap(lo, hi);
  if (hi - lo <= 0.0) return {lo};
  const Step s = nice_step((hi - lo) / target_count);
  const double step = s.value(), eps = 1e-9 * step;
  std::vector<double> out;
  for (auto k = static_cast<long long>(std::ceil((lo - eps) / step)); tick_value(k, s) <= hi + eps;
       ++k)
    out.push_back(tick_value(k, s));
  return out;
}

std::string tick_label(double value, double step) {
  const int decimals = std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 9);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(value) < 1e-12 * step ? 0.0 : value);
  return buf;
}

void draw_plot(Canvas& c, const std::vector<Series>& series, const PlotOptions& o) {
  auto xr = widen_if_flat(finite_range(series, true).value_or(std::make_pair(0.0, 1.0)));
  std::pair<double, double> yr;
  if (o.y_range) {
    yr = widen_if_flat(*o.y_range);
  } else {
    yr = widen_if_flat(finite_range(series, false).value_or(std::make_pair(0.0, 1.0)));
    const double pad = 0.06 * (yr.second - yr.first);
    yr = {yr.first - pad, yr.second + pad};
  }
  const Eigen::AlignedBox2d world(Eigen::Vector2d(xr.first, yr.first),
                                  Eigen::Vector2d(xr.second, yr.second));
  const double top = o.title.empty() ? 16 : 40, left = o.y_label.empty() ? 58 : 78;
  const double bottom = o.x_label.empty() ? 34 : 56;
  const Eigen::AlignedBox2d plot(Eigen::Vector2d(left, top),
                                 Eigen::Vector2d(o.width_px - 20.0, o.height_px - bottom));
  c.set_view_rect(world, plot, o.width_px, o.height_px);
  c.begin_group("data", &plot);
  for (const auto& [a, b] : o.bands)
    c.polygon({{a, yr.first}, {b, yr.first}, {b, yr.second}, {a, yr.second}},
              {{}, kBand, 0.0, true});
  const auto xt = nice_ticks(xr.first, xr.second, std::max(2, o.width_px / 110));
  const auto yt = nice_ticks(yr.first, yr.second, std::max(2, o.height_px / 70));
  draw_grid(c, xt, yt);
  for (const auto& s : series) draw_series(c, s);
  c.end_group();
  draw_ticks(c, xt, yt);
  c.rect_px(plot.min(), plot.max(), {Color::hex("#555555"), {}, 1.0});
  if (!o.title.empty()) c.text_px({left, 20}, o.title, 18, kInk);
  if (!o.x_label.empty())
    c.text_px({plot.center().x(), o.height_px - 16.0}, o.x_label, 13, kInk, Align::centre);
  if (!o.y_label.empty())
    c.text_px({18, plot.center().y()}, o.y_label, 13, kInk, Align::centre, true);
  draw_plot_legend(c, series, o);
}

void write_plot(const std::filesystem::path& out, const std::vector<Series>& series,
                const PlotOptions& options) {
  auto canvas = make_canvas(out);
  draw_plot(*canvas, series, options);
  canvas->save(out);
}

}  // namespace rownav::io
