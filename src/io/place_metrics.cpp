/// @file place_metrics.cpp The map stage against the truth (io/place_metrics.hpp).
#include "rownav/io/place_metrics.hpp"

#include <algorithm>
#include <limits>

namespace rownav::io {

namespace {

constexpr double kMedian = 0.5;

double nearest_corridor_end(const sim::FieldTruth& truth, int block, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < truth.corridor_count(block); ++k) {
    const auto& c = truth.corridor_centre(block, k);
    if (c.empty()) continue;
    best = std::min({best, (c.front() - p).norm(), (c.back() - p).norm()});
  }
  return best;
}

}  // namespace

map::Place map_place(sim::Place p) {
  switch (p) {
    case sim::Place::lane: return map::Place::lane;
    case sim::Place::alley: return map::Place::alley;
    default: return map::Place::headland;
  }
}

PlaceMetrics place_metrics(const RunResult& run, const sim::FieldTruth& truth, int block) {
  PlaceMetrics m;
  int right = 0;
  for (const auto& s : run.places) {
    ++m.frames;
    right += s.estimated == map_place(s.truth) ? 1 : 0;
  }
  if (m.frames > 0) m.accuracy = static_cast<double>(right) / m.frames;
  std::vector<double> errors;
  for (const auto& k : run.key_locations) {
    KeyLocationMetric km{std::string(core::enum_name(k.key.from)),
                         std::string(core::enum_name(k.key.to)), k.world,
                         nearest_corridor_end(truth, block, k.world)};
    errors.push_back(km.error);
    m.keys.push_back(std::move(km));
  }
  if (!errors.empty()) {
    std::sort(errors.begin(), errors.end());
    m.key_error_median = errors[static_cast<std::size_t>(kMedian * (errors.size() - 1))];
    m.key_error_max = errors.back();
  }
  return m;
}

}  // namespace rownav::io
