#include "detect_picture.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/core/angle.hpp"
#include "rownav/io/canvas.hpp"
#include "rownav/io/top_view.hpp"

namespace rownav::app {

namespace {

// Base frame (x forward, y left) to picture world (right, up): forward is up, left is left.
Eigen::Vector2d view(double x, double y) {
  return {-y, x};
}

const io::Color kPoints = io::Color::hex("#40b255");
const io::Color kLeft = io::Color::hex("#d62728");
const io::Color kRight = io::Color::hex("#1f77b4");
const io::Color kOther = io::Color::hex("#7f7f7f");
const io::Color kCorridor = io::Color::hex("#ff7f0e");

Eigen::AlignedBox2d view_box(const std::vector<Eigen::Vector2f>& pts) {
  Eigen::AlignedBox2d box(view(-0.2, 0.5), view(1.0, -0.5));  // at least the robot's surroundings
  for (const auto& p : pts)
    if (p.allFinite())
      box.extend(view(std::clamp(p.x(), -5.0f, 20.0f), std::clamp(p.y(), -10.0f, 10.0f)));
  box.min().array() -= 0.1;
  box.max().array() += 0.1;
  return box;
}

void draw_row(io::Canvas& c, const core::RowLine& r, io::Color colour, double width) {
  const double x0 = std::min(r.x_min, 0.0), x1 = r.x_max;
  if (std::abs(r.line.direction.x()) < 1e-6) return;
  c.line(view(x0, r.line.y_at(x0)), view(x1, r.line.y_at(x1)), {colour, {}, width, false, false});
}

void draw_robot_marker(io::Canvas& c) {
  const io::Style s{io::Color::hex("#222222"), io::Color::hex("#222222"), 1.0, true, false};
  c.polygon({view(0.12, 0.0), view(-0.06, 0.06), view(-0.06, -0.06)}, s);
}

}  // namespace

void write_detection_picture(const std::filesystem::path& out,
                             const std::vector<Eigen::Vector2f>& points,
                             const core::RowObservation& obs, const std::string& title) {
  auto canvas = io::make_canvas(out);
  io::Canvas& c = *canvas;
  const Eigen::AlignedBox2d box = view_box(points);
  const double ppm = std::clamp(700.0 / box.sizes().maxCoeff(), 20.0, 250.0);
  c.set_view(box, ppm, io::Margins{40, 50, 230, 90});
  for (const auto& p : points)
    if (p.allFinite()) c.dot(view(p.x(), p.y()), 2.0, kPoints);
  for (std::size_t i = 0; i < obs.rows.size(); ++i) {
    const int k = static_cast<int>(i);
    const bool side = k == obs.left || k == obs.right;
    draw_row(c, obs.rows[i],
             k == obs.left    ? kLeft
             : k == obs.right ? kRight
                              : kOther,
             side ? 3.0 : 1.5);
  }
  if (obs.corridor) {
    const auto& co = *obs.corridor;
    const double x1 = box.max().y(), t = std::tan(co.heading);
    c.line(view(0.0, co.offset), view(x1, co.offset + x1 * t), {kCorridor, {}, 2.0, false, true});
  }
  draw_robot_marker(c);
  io::draw_title(c, title);
  io::draw_legend(c, {{"points (detector input)", {kPoints, kPoints, 0.0, true, false}},
                      {"left row", {kLeft, {}, 3.0, false, false}},
                      {"right row", {kRight, {}, 3.0, false, false}},
                      {"other rows", {kOther, {}, 1.5, false, false}},
                      {"corridor centre", {kCorridor, {}, 2.0, false, true}},
                      {"robot (base origin)",
                       {io::Color::hex("#222222"), io::Color::hex("#222222"), 1.0, true, false}}});
  const Eigen::AlignedBox2d plot = c.plot_rect();
  c.text_px({plot.min().x(), plot.max().y() + 62},
            "base frame: x forward (up), y left (left), metres", 12, io::Color::hex("#333333"));
  io::draw_scale_bar(c);
  c.save(out);
}

}  // namespace rownav::app
