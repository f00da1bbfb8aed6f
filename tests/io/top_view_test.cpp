#include "rownav/io/top_view.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "rownav/core/line2.hpp"
#include "rownav/io/cairo_canvas.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

/// Straight or gently curved rows along x, with vines, posts, end posts and weeds.
sim::Field make_field(int n_rows, double length, double spacing, double bend, unsigned seed) {
  sim::Field f;
  f.row_spacing = spacing;
  f.headland_width = 4.0;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto lateral = [&](int k, double x) { return k * spacing + bend * std::sin(x / 12.0); };
  for (int k = 0; k < n_rows; ++k) {
    sim::Row r;
    r.id = k;
    for (double x = 0.0; x <= length + 1e-9; x += 2.0) r.polyline.emplace_back(x, lateral(k, x));
    r.half_width = 0.35;
    f.rows.push_back(r);
    for (double x = 0.6; x < length; x += 1.2)
      f.plants.push_back({{x, lateral(k, x)}, 0.06, 1.6, k, sim::PlantKind::vine});
    for (double x = 6.0; x < length; x += 6.0)
      f.plants.push_back({{x, lateral(k, x)}, 0.05, 1.9, k, sim::PlantKind::post});
    for (double x : {0.0, length})
      f.plants.push_back({{x, lateral(k, x)}, 0.08, 2.0, k, sim::PlantKind::end_post});
  }
  for (int i = 0; i < 12 * n_rows; ++i) {
    const double x = u(rng) * length, y = (u(rng) * (n_rows - 1)) * spacing;
    f.plants.push_back({{x, y + bend * std::sin(x / 12.0)}, 0.05, 0.2, -1, sim::PlantKind::weed});
  }
  return f;
}

/// Planar scan against the canopy bands (ray marching), with range noise.
core::Scan2D fake_scan(const sim::Field& f, const core::Pose2& T_world_lidar, unsigned seed) {
  core::Scan2D s;
  s.angle_min = -M_PI;
  s.angle_increment = M_PI / 360.0;
  s.range_min = 0.3;
  s.range_max = 15.0;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.03);
  for (int i = 0; i < 720; ++i) {
    float hit = std::numeric_limits<float>::infinity();
    const Eigen::Vector2d dir(std::cos(s.angle(i)), std::sin(s.angle(i)));
    for (double r = s.range_min; r < s.range_max && !std::isfinite(hit); r += 0.05) {
      const Eigen::Vector2d p = T_world_lidar * (r * dir);
      for (const auto& row : f.rows)
        for (std::size_t j = 1; j < row.polyline.size(); ++j)
          if (core::Segment2{row.polyline[j - 1], row.polyline[j]}.distance(p) < row.half_width)
            hit = static_cast<float>(r + noise(rng));
    }
    s.ranges.push_back(hit);
  }
  return s;
}

/// 3D cloud in the lidar frame (0.8 m above the ground): canopy returns behind every scan hit
/// at random heights, ground rings in front of them.
core::PointCloud fake_cloud(const core::Scan2D& scan, unsigned seed) {
  core::PointCloud cloud;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t i = 0; i < scan.ranges.size(); i += 2) {
    const float a = static_cast<float>(scan.angle(i)), c = std::cos(a), s = std::sin(a);
    const float reach = scan.valid(i) ? scan.ranges[i] : 10.0f;
    for (int k = 0; k < 5 && scan.valid(i); ++k) {
      const float r = reach + 0.5f * u(rng), z = -0.6f + 1.6f * u(rng);
      cloud.points.push_back({r * c, r * s, z});
    }
    for (float r = 1.5f; r < std::min(reach, 10.0f); r += 0.8f)
      cloud.points.push_back({r * c, r * s, -0.8f + 0.04f * u(rng)});
  }
  return cloud;
}

TEST(TopView, CorridorCentreIsTheMidline) {
  sim::Row a, b;
  a.polyline = {{0, 0}, {10, 0}};
  b.polyline = {{10, 2}, {4, 2}, {0, 2}};  // opposite direction, uneven vertices
  const auto mid = corridor_centre(a, b, 11);
  ASSERT_EQ(mid.size(), 11u);
  for (std::size_t i = 0; i < mid.size(); ++i) {
    EXPECT_NEAR(mid[i].y(), 1.0, 1e-12);
    EXPECT_NEAR(mid[i].x(), static_cast<double>(i), 1e-12);
  }
}

TEST(TopView, ViridisEndsAndClamps) {
  EXPECT_EQ(viridis(0.0), Color::hex("#440154"));
  EXPECT_EQ(viridis(1.0), Color::hex("#fde725"));
  EXPECT_EQ(viridis(7.0), Color::hex("#fde725"));
  EXPECT_EQ(viridis(std::nan("")), Color::hex("#440154"));
  EXPECT_GT(viridis(0.75).g, viridis(0.25).g);  // gets lighter
}

TEST(TopView, ThreeRowFieldBothFormats) {
  const sim::Field f = make_field(3, 20.0, 2.5, 0.0, 1);
  TopViewOptions o;
  o.title = "three rows";
  for (const char* name : {"rownav_three_rows.svg", "rownav_three_rows.png"}) {
    const fs::path out = fs::temp_directory_path() / name;
    auto c = make_canvas(out);
    draw_field(*c, f, o);
    // Window: x in [-4, 24], y in [-4, 9] at 20 px/m + margins 24 / 200 and 48 / 74.
    EXPECT_EQ(c->width(), 28 * 20 + 24 + 200);
    EXPECT_EQ(c->height(), 13 * 20 + 48 + 74);
    c->save(out);
    ASSERT_GT(fs::file_size(out), 1000u);
  }
  const RgbaImage img = read_png(fs::temp_directory_path() / "rownav_three_rows.png");
  auto c = make_canvas("x.png");
  draw_field(*c, f, o);
  const auto at = [&](double x, double y) {
    const Eigen::Vector2d p = c->to_pixel({x, y});
    return img.at(static_cast<int>(p.x()), static_cast<int>(p.y()));
  };
  EXPECT_EQ(at(-2.0, -2.0), Color::hex("#efe6d2"));  // soil in the headland
  const Color canopy = at(3.0, 2.5 + 0.25);          // on the canopy band, off the centre line
  EXPECT_GT(canopy.g, canopy.r);
  EXPECT_GT(canopy.g, canopy.b);
  const Color corridor = at(3.1, 1.25);  // dashed corridor centre: blue or soil
  EXPECT_TRUE(corridor.b > corridor.r || corridor == Color::hex("#efe6d2"));
}

TEST(TopView, EveryPlantIsDrawnInItsColour) {
  const sim::Field f = make_field(3, 20.0, 2.5, 0.0, 1);
  CairoCanvas c;
  TopViewOptions o;
  o.posts = false;
  draw_field(c, f, o);
  const RgbaImage img = c.raster();
  const auto near = [](Color a, Color b) {
    return std::abs(a.r - b.r) <= 3 && std::abs(a.g - b.g) <= 3 && std::abs(a.b - b.b) <= 3;
  };
  // Dots of >= 1.5 px radius cover the pixel holding their centre entirely.
  std::size_t vines = 0, vines_seen = 0, weeds = 0, weeds_seen = 0;
  for (const auto& p : f.plants) {
    const Eigen::Vector2d q = c.to_pixel(p.position);
    const Color px = img.at(static_cast<int>(q.x()), static_cast<int>(q.y()));
    if (p.kind == sim::PlantKind::vine) ++vines, vines_seen += near(px, Color::hex("#2f7d32"));
    if (p.kind == sim::PlantKind::weed) ++weeds, weeds_seen += near(px, Color::hex("#a9d65c"));
  }
  EXPECT_GT(vines, 40u);
  EXPECT_GE(vines_seen, vines * 9 / 10);  // a weed drawn later may cover a vine
  EXPECT_EQ(weeds_seen, weeds);
  const std::string svg = c.svg();  // the same drawing as vectors
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_GT(std::count(svg.begin(), svg.end(), '\n'), static_cast<long>(vines + weeds));
}

TEST(TopView, DemoVineyardWithScanCloudAndRobot) {
  const sim::Field f = make_field(6, 40.0, 2.5, 0.6, 7);
  const core::Pose2 T_world_base(12.0, 3.75 + 0.6 * std::sin(1.0), 0.08);
  const core::Pose2 T_world_lidar = T_world_base * core::Pose2(0.3, 0.0, 0.0);
  const core::Scan2D scan = fake_scan(f, T_world_lidar, 3);
  const core::PointCloud cloud = fake_cloud(scan, 5);
  Eigen::Isometry3d T_wl = T_world_lidar.to_isometry();
  T_wl.translation().z() = 0.8;
  const Color red = Color::hex("#d62728"), orange = Color::hex("#ff7f0e");
  const Color magenta = Color::hex("#c51b7d");
  TopViewOptions o;
  o.title = "rownav demo: 6-row vineyard, simulated scan";
  o.extra_legend = {{"robot", robot_legend_style(red)},
                    {"LiDAR scan", scan_legend_style(orange)},
                    {"path", {magenta, {}, 2.0}}};
  std::vector<Eigen::Vector2d> path;
  for (double x = 0.0; x <= 12.0; x += 0.5) path.emplace_back(x, 3.75 + 0.6 * std::sin(x / 12.0));
  const auto render = [&](const fs::path& out) {
    auto c = make_canvas(out);
    draw_field(*c, f, o);
    draw_cloud(*c, cloud, T_wl, 0.0, 1.8);
    draw_scan(*c, scan, T_world_lidar, orange, 1.4);
    draw_path(*c, path, {magenta, {}, 2.0});
    draw_robot(*c, T_world_base, 1.3, 0.8, red);
    c->save(out);
    return c;
  };
  const fs::path out = fs::temp_directory_path() / "render_demo.png";
  const auto c = render(out);
  o.window = Eigen::AlignedBox2d(Eigen::Vector2d(5, -0.5), Eigen::Vector2d(21, 8.5));
  o.pixels_per_metre = 50;
  render(fs::temp_directory_path() / "render_demo_zoom.svg");
  render(fs::temp_directory_path() / "render_demo_zoom.png");
  render(fs::temp_directory_path() / "render_demo_zoom.pdf");
  const RgbaImage img = read_png(out);
  EXPECT_EQ(img.width, c->width());
  EXPECT_GT(std::count_if(scan.ranges.begin(), scan.ranges.end(),
                          [](float r) { return std::isfinite(r); }),
            200);
}

}  // namespace
}  // namespace rownav::io
