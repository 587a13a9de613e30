// The binary exponent of a double without libm (det_math.cpp's hypot, det_trig.cpp's
// argument reduction): the same on every target. Internal to the engine: not installed.
#pragma once

#include <cmath>

#include "fixstep/core/bits.hpp"

namespace fixstep::det {

/// Exponent e with |a| in [2^e, 2^(e+1)) for finite a ≠ 0 (subnormals included): ilogb(a).
inline int binary_exponent(double a) {
  const int biased = static_cast<int>((bits_of(a) >> 52) & 0x7ff);
  if (biased != 0) return biased - 1023;
  const double normal = std::fabs(a) * 0x1p64;  // exact
  return static_cast<int>(bits_of(normal) >> 52) - 1023 - 64;
}

}  // namespace fixstep::det
