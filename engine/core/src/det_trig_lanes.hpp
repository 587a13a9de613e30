// Deterministic sin and cos of many angles at once: the same bits as det::sincos for each
// (det_math.hpp), four at a time in the lanes of a vector where the CPU has AVX2. The shape
// phase turns every moving body's angle into a rotation several times a tick. Internal: not
// installed.
#pragma once

#include <span>

#include "fixstep/core/simd.hpp"

namespace fixstep::det {

/// sine[i] and cosine[i] of x[i] (rad) for every i < x.size(): the same bits as
/// sincos(x[i], sine[i], cosine[i]). At SimdLevel::avx2 or avx512 (where supported), four
/// angles at a time: a four whose every angle needs only the first step of sincos's
/// reduction (|x| ≤ π/4, or x − nπ/2 not within 2^-15·|x| of 0) in the lanes of a vector,
/// any other four (an angle near a multiple of π/2, NaN, ±inf, or beyond trig_max_argument)
/// one by one through sincos; at baseline, every angle through sincos. Errors: as sincos
/// (std::domain_error for a finite |x| > trig_max_argument, with that four's outputs
/// unwritten). Preconditions: sine and cosine at least as long as x; none of the three
/// overlap.
void sincos_each(std::span<const double> x, std::span<double> sine, std::span<double> cosine,
                 SimdLevel level);

}  // namespace fixstep::det
