// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the withinDistance tests.
#pragma once

#include <cstdint>
#include <cstring>

namespace tricyl::test {

/// The double k ulps above (k > 0) or below (k < 0) x >= 0, clamped at 0
/// (the bit patterns of non-negative doubles are ordered like the values).
inline double ulpsFrom(double x, std::int64_t k) {
  std::int64_t b;
  std::memcpy(&b, &x, sizeof b);
  b += k;
  if (b < 0) b = 0;
  double y;
  std::memcpy(&y, &b, sizeof y);
  return y;
}

}  // namespace tricyl::test
