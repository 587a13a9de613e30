// The golden bit patterns of fixstep::det (det_math_golden.inc: argument and result bits, as
// computed on x86-64) as one table, with the call each row names. Shared by
// DetMath.GoldenBitPatterns (test_det_math.cpp) and tests/cross/det_checks.cpp, which checks
// them on aarch64 and wasm32.
#pragma once

#include <cstdint>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/det_math.hpp"

namespace fixstep::det_golden {

struct Case {
  int f;  ///< 0 exp(x), 1 expm1(x), 2 hypot(x, y), 3 sin(x), 4 cos(x), 5 atan(x), 6 atan2(x, y)
  std::uint64_t x, y, out;  ///< IEEE-754 double bits of the arguments and of the result
};

inline constexpr Case cases[] = {
#include "det_math_golden.inc"
};

/// The bits fixstep::det gives for the case's call on this platform.
inline std::uint64_t result_bits(const Case& c) {
  const double x = double_from_bits(c.x), y = double_from_bits(c.y);
  switch (c.f) {
    case 0:
      return bits_of(det::exp(x));
    case 1:
      return bits_of(det::expm1(x));
    case 2:
      return bits_of(det::hypot(x, y));
    case 3:
      return bits_of(det::sin(x));
    case 4:
      return bits_of(det::cos(x));
    case 5:
      return bits_of(det::atan(x));
    default:
      return bits_of(det::atan2(x, y));
  }
}

}  // namespace fixstep::det_golden
