// Estimates the HMM motion transition model of the map stage the way Emmi 2021
// (002_806e72d300173f73.txt, sec. "Current state estimation") describes it: random poses
// (position and heading) in simulated fields, one motion step forward, the true place before
// and after counted. Transitions the field model forbids (Fig. 1b: lane <-> alley) are
// removed before the rows are normalised, as the paper simplifies Weiss and Biber's model.
// Prints include/rownav/map/transition_model_data.hpp on stdout:
//   build/place_transitions_bench [samples per field] [seed] > include/rownav/map/transition_model_data.hpp
// Not a Google Benchmark: a tool with its own main, built with the benches.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "map_fields.hpp"
#include "rownav/map/place.hpp"
#include "rownav/sim/field_truth.hpp"

namespace {

using Counts = std::array<std::array<double, 3>, 3>;
constexpr double kStep = 0.1;  // [m] one motion step (PlaceHmmConfig::step_length)

int index_of(rownav::sim::Place p) {
  switch (p) {
    case rownav::sim::Place::headland: return 0;
    case rownav::sim::Place::lane: return 1;
    case rownav::sim::Place::alley: return 2;
    default: return -1;
  }
}

void count_field(const rownav::sim::Field& field, long samples, std::mt19937_64& rng, Counts& c) {
  const rownav::sim::FieldTruth truth(field);
  Eigen::AlignedBox2d box = field.row_bounds();
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(field.headland_width);
  box.extend(box.min() - margin);
  box.extend(box.max() + margin);
  std::uniform_real_distribution<double> ux(box.min().x(), box.max().x()),
      uy(box.min().y(), box.max().y()), ut(-M_PI, M_PI);
  for (long i = 0; i < samples; ++i) {
    const rownav::core::Pose2 a(ux(rng), uy(rng), ut(rng));
    const rownav::core::Pose2 b = a * rownav::core::Pose2(kStep, 0.0, 0.0);
    const int from = index_of(truth.at(a, 0.0, 0.0).place);
    const int to = index_of(truth.at(b, 0.0, 0.0).place);
    if (from < 0 || to < 0) continue;  // outside the field
    c[static_cast<std::size_t>(from)][static_cast<std::size_t>(to)] += 1.0;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const long samples = argc > 1 ? std::atol(argv[1]) : 400000;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  std::mt19937_64 rng(seed);
  Counts counts{};
  for (const auto& f : {rownav::bench_map::field_b1(seed), rownav::bench_map::field_v1(seed)})
    count_field(rownav::sim::generate_field(f.config), samples, rng, counts);
  std::printf("#pragma once\n/// @file transition_model_data.hpp HMM motion transition model of "
              "the map stage (generated).\n");
  std::printf("///\n/// Made by bench/place_transitions_bench.cpp (%ld random poses per field, "
              "seed %llu,\n/// fields B1 and V1 of bench/map_fields.hpp, step %.2f m): counts "
              "from -> to (headland, lane, alley)\n",
              samples, static_cast<unsigned long long>(seed), kStep);
  for (const auto& r : counts) std::printf("///   %.0f %.0f %.0f\n", r[0], r[1], r[2]);
  std::printf("/// Forbidden transitions (Emmi 2021 Fig. 1b: lane <-> alley) zeroed, rows "
              "normalised.\n#include <array>\n\nnamespace rownav::map {\n\n");
  std::printf("/// [m] forward travel of one motion step.\ninline constexpr double "
              "kMotionStepLength = %.2f;\n",
              kStep);
  std::printf("/// P(to | from, motion), row-major (headland, lane, alley).\n"
              "inline constexpr std::array<double, 9> kMotionTransitions{\n");
  for (std::size_t i = 0; i < 3; ++i) {
    double sum = 0.0;
    std::array<double, 3> row{};
    for (std::size_t j = 0; j < 3; ++j) {
      const bool allowed = rownav::map::transition_allowed(rownav::map::filtered_place(int(i)),
                                                           rownav::map::filtered_place(int(j)));
      row[j] = allowed ? counts[i][j] : 0.0;
      sum += row[j];
    }
    std::printf("    %.8f, %.8f, %.8f%s\n", row[0] / sum, row[1] / sum, row[2] / sum,
                i < 2 ? "," : "};");
  }
  std::printf("\n}  // namespace rownav::map\n");
  return 0;
}
