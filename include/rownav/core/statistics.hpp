#pragma once
/// @file statistics.hpp Order statistics of small samples (row spacings, lattice gaps, widths),
/// shared so that every stage takes its median the same way.
#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

namespace rownav::core {

/// Upper median of `values` (the element at index size / 2 once sorted: one of the values, never
/// an average of two), or `empty_value` when there are none. Copies the values (the caller's
/// container keeps its order); O(n).
template <class Range>
double median(const Range& values, double empty_value = 0.0) {
  std::vector<double> v(std::begin(values), std::end(values));
  if (v.empty()) return empty_value;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace rownav::core
