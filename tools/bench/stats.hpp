#pragma once
// Small statistics shared by the benchmark programs.
#include <algorithm>
#include <cmath>
#include <vector>

namespace mdrmap::bench {

/// Median of x (NaN for an empty x).
inline double median(std::vector<double> x) {
  if (x.empty()) return std::nan("");
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

} // namespace mdrmap::bench
