#pragma once

#include <algorithm>
#include <vector>

namespace mcquad {

//! The quantile (0.5: the median, the upper one of an even count) of
//! `values`; 0 when there are none.
inline double quantile_of(std::vector<double> values, double quantile) {
  if (values.empty()) return 0.0;
  auto at = values.begin() + long(std::min(values.size() - 1, size_t(quantile * double(values.size()))));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

}  // namespace mcquad
