// The median of a benchmark's rounds or repetitions, where a reporter keeps them itself.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace fixstep::bench {

/// The median of `v` (the mean of the middle two where their count is even); `v` not empty.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace fixstep::bench
