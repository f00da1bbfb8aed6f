// Picture speed (issue 14): draw and write the demo's top view (config/fields/demo_vineyard.yaml,
// 12 px/m, legend, a serpentine path over every corridor, row-end dots) as PNG, SVG, PDF, so a
// change of backend can be compared on the same drawing. Uses only make_canvas and the top-view
// API: the same source measures any backend.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>

#include "rownav/io/canvas.hpp"
#include "rownav/io/top_view.hpp"
#include "rownav/sim/field_config.hpp"

namespace {

using namespace rownav;
namespace fs = std::filesystem;

const sim::Field& demo_field() {
  static const sim::Field field = [] {
    sim::FieldConfig f;  // the keys of config/fields/demo_vineyard.yaml
    f.seed = 7;
    f.vineyard.rows = 10;
    f.vineyard.row_length = 50.0;
    f.vineyard.row_spacing = 1.8;
    f.vineyard.stage = sim::GrowthStage::medium;
    f.vineyard.missing_plants_percent = 3.0;
    f.vineyard.weeds = sim::WeedLevel::some;
    return sim::generate_field(f);
  }();
  return field;
}

/// Every corridor centre in turn, joined at the row ends: about as many vertices as the demo's
/// recorded path segments (10 cm apart).
std::vector<Eigen::Vector2d> serpentine(const sim::Field& f) {
  std::vector<Eigen::Vector2d> path;
  for (std::size_t i = 1; i < f.rows.size(); ++i) {
    auto mid = io::corridor_centre(f.rows[i - 1], f.rows[i], 500);
    if (i % 2 == 0) std::reverse(mid.begin(), mid.end());
    path.insert(path.end(), mid.begin(), mid.end());
  }
  return path;
}

void draw_demo_top_view(io::Canvas& c, const sim::Field& f, const std::vector<Eigen::Vector2d>& p) {
  io::TopViewOptions o;
  o.pixels_per_metre = 12;
  o.title = "closed-loop run: true path coloured by navigator state";
  const io::Color blue = io::Color::hex("#1f77b4"), red = io::Color::hex("#d62728");
  o.extra_legend = {{"in_row", io::Style{blue, {}, 2.0}},
                    {"row ends (estimated)", io::Style{red, red, 1.0, true}}};
  io::draw_field(c, f, o);
  io::draw_path(c, p, io::Style{blue, {}, 2.0});
  for (const auto& r : f.rows) c.dot(r.start(), 4.0, red);
}

void draw_and_write(benchmark::State& state, const char* name) {
  const sim::Field& field = demo_field();
  const auto path = serpentine(field);
  const fs::path out = fs::temp_directory_path() / name;
  for (auto _ : state) {
    auto canvas = io::make_canvas(out);
    draw_demo_top_view(*canvas, field, path);
    canvas->save(out);
  }
  state.counters["bytes"] = static_cast<double>(fs::file_size(out));
  state.counters["plants"] = static_cast<double>(field.plants.size());
}

void BM_DemoTopViewPng(benchmark::State& state) {
  draw_and_write(state, "rownav_render_bench.png");
}
void BM_DemoTopViewSvg(benchmark::State& state) {
  draw_and_write(state, "rownav_render_bench.svg");
}
void BM_DemoTopViewPdf(benchmark::State& state) {
  draw_and_write(state, "rownav_render_bench.pdf");
}
BENCHMARK(BM_DemoTopViewPng)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DemoTopViewSvg)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DemoTopViewPdf)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
