// Row spacing centre to centre from every row seen (issue 10, track/row_spacing.hpp).
#include "rownav/track/row_spacing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "rownav/core/statistics.hpp"
#include "rownav/track/row_geometry.hpp"

namespace rownav::track {

namespace {

void push(std::deque<double>& q, double v, int window) {
  if (!std::isfinite(v)) return;
  q.push_back(v);
  while (static_cast<int>(q.size()) > window) q.pop_front();
}

}  // namespace

void RowSpacingEstimator::add(const core::RowObservation& obs) {
  std::vector<double> centres;
  for (const auto& r : obs.rows)
    if (std::isfinite(r.offset) && std::isfinite(r.centre_shift)) centres.push_back(core::centre_offset(r));
  if (const double s = robust_spacing(centres); s > 0.0) push(spacings_, s, window_);
  for (const int side : {0, 1}) {
    const int i = side ? obs.left : obs.right;
    if (i < 0 || i >= static_cast<int>(obs.rows.size())) continue;
    const auto& r = obs.rows[static_cast<std::size_t>(i)];
    push(shifts_[side], r.centre_shift, window_);
    push(half_widths_[side], r.half_width, window_);
  }
}

double RowSpacingEstimator::spacing() const { return core::median(spacings_); }
double RowSpacingEstimator::shift(bool left) const { return core::median(shifts_[left ? 1 : 0]); }
double RowSpacingEstimator::half_width(bool left) const {
  return core::median(half_widths_[left ? 1 : 0]);
}

void RowSpacingEstimator::reset() {
  spacings_.clear();
  for (auto& q : shifts_) q.clear();
  for (auto& q : half_widths_) q.clear();
}

}  // namespace rownav::track
