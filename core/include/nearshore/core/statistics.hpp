#pragma once
// Small order statistics shared by the loop tools and the benchmarks.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace nearshore {

/// The median of `values` (the upper one of the two middle values for an even count); 0 when empty.
/// Takes a copy: nth_element reorders it.
inline double median_of(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace nearshore
