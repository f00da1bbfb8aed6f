// Hough / iterative skewing: mean-threshold segmentation of the best column (Nehme 2021
// sec. 3.2.3) with the rownav valley splitting and rejections.
#include <algorithm>

#include "rownav/detect/hough_skew.hpp"

namespace rownav::detect {

void HoughSkewDetector::split(int from, int to, int depth) {
  // rownav: a run above the threshold may hold several rows joined by weed / noise bins. It is
  // cut at every deep valley (below valley_ratio x the lower of the two neighbouring peaks) found
  // between the sub-runs above the run's own mean; each part is examined again.
  const auto h = [&](int i) { return double(hist_[static_cast<std::size_t>(i)]); };
  double mean = 0.0;
  for (int i = from; i < to; ++i) mean += h(i);
  mean /= (to - from);
  std::vector<int> cuts{from};
  int i = from;
  while (i < to && h(i) <= mean) ++i;
  while (i < to && depth < 6) {
    double peak = 0.0;
    while (i < to && h(i) > mean) peak = std::max(peak, h(i++));
    int valley = i;
    while (i < to && h(i) <= mean) valley = h(i) < h(valley) ? i : valley, ++i;
    if (i < to) {
      double next_peak = 0.0;
      for (int j = i; j < to && h(j) > mean; ++j) next_peak = std::max(next_peak, h(j));
      if (h(valley) < config_.valley_ratio * std::min(peak, next_peak)) cuts.push_back(valley);
    }
  }
  cuts.push_back(to);
  if (cuts.size() > 2) {
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) split(cuts[k], cuts[k + 1], depth + 1);
    return;
  }
  accept(from, to);
}

void HoughSkewDetector::accept(int from, int to) {
  const double bw = (config_.y_max - config_.y_min) / config_.bins;
  double votes = 0.0, moment = 0.0;
  int lo = to, hi = from;
  for (int i = from; i < to; ++i) {
    const double c = hist_[static_cast<std::size_t>(i)];
    if (c <= threshold_) continue;  // shoulders below the column mean are not the row
    lo = std::min(lo, i), hi = std::max(hi, i + 1);
    votes += c;
    moment += c * (config_.y_min + (i + 0.5) * bw);  // count-weighted mean (Nehme 2021)
  }
  if (hi - lo < config_.min_segment_bins || votes < config_.min_segment_points) return;
  if ((hi - lo) * bw > config_.max_segment_width) return;
  segments_.push_back({moment / votes, config_.y_min + lo * bw, config_.y_min + hi * bw,
                       static_cast<int>(votes)});
}

double HoughSkewDetector::lower_quartile() {
  int first = 0, last = config_.bins - 1;
  while (first < last && hist_[static_cast<std::size_t>(first)] == 0) ++first;
  while (last > first && hist_[static_cast<std::size_t>(last)] == 0) --last;
  quartile_.assign(hist_.begin() + first, hist_.begin() + last + 1);
  const auto q = quartile_.begin() + static_cast<long>(quartile_.size() / 4);
  std::nth_element(quartile_.begin(), q, quartile_.end());
  return *q;
}

void HoughSkewDetector::segment() {
  // Nehme 2021 sec. 3.2.3: bins above the column mean form segments; each segment's position is
  // the count-weighted mean of its bins.
  segments_.clear();
  threshold_ = 0.0;
  for (const int h : hist_) threshold_ += h;
  threshold_ /= config_.bins;
  for (int i = 0; i < config_.bins;) {
    if (hist_[static_cast<std::size_t>(i)] <= threshold_) { ++i; continue; }
    int j = i;
    while (j < config_.bins && hist_[static_cast<std::size_t>(j)] > threshold_) ++j;
    if (config_.split_segments) split(i, j, 0);
    else accept(i, j);
    i = j;
  }
  // rownav: weak segments (weed strips, far rows seen by a few points) are dropped, and so are
  // segments that do not stand out of the background (lower quartile of the occupied bins).
  int strongest = 0;
  for (const auto& s : segments_) strongest = std::max(strongest, s.votes);
  const double background = lower_quartile();
  const double bw = (config_.y_max - config_.y_min) / config_.bins;
  std::erase_if(segments_, [&](const Segment& s) {
    const double density = s.votes / std::max(1.0, (s.hi - s.lo) / bw);
    return s.votes < config_.min_relative_support * strongest ||
           density < config_.min_contrast * background;
  });
  std::sort(segments_.begin(), segments_.end(),
            [](const Segment& a, const Segment& b) { return a.position < b.position; });
}

}  // namespace rownav::detect
