// The golden bit patterns of fixstep::det (det_math_golden.inc: argument and result bits, as
// computed on x86-64) as one table, with the call each row names. Shared by
// DetMath.GoldenBitPatterns (test_det_math.cpp) and tests/cross/det_checks.cpp, which checks
// them on aarch64 and wasm32.
#pragma once

#include <cstdint>
#include <cstring>

#include "fixstep/det_math.hpp"

namespace fixstep::det_golden {

struct Case {
  int f;                    ///< 0 exp(x), 1 expm1(x), 2 hypot(x, y)
  std::uint64_t x, y, out;  ///< IEEE-754 double bits of the arguments and of the result
};

inline constexpr Case cases[] = {
#include "det_math_golden.inc"
};

inline double from_bits(std::uint64_t b) {
  double d = 0.0;
  std::memcpy(&d, &b, sizeof d);
  return d;
}

inline std::uint64_t bits(double d) {
  std::uint64_t b = 0;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

/// The bits fixstep::det gives for the case's call on this platform.
inline std::uint64_t result_bits(const Case& c) {
  const double x = from_bits(c.x), y = from_bits(c.y);
  return bits(c.f == 0 ? det::exp(x) : c.f == 1 ? det::expm1(x) : det::hypot(x, y));
}

}  // namespace fixstep::det_golden
