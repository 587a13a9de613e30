// Instruction-set levels of the stepping sweeps (function multiversioning).
//
// The per-tick sweeps (world_step.cpp) are compiled three times: for the baseline ISA of the
// build (x86-64: SSE2, 2 doubles per vector), AVX2 (4) and AVX-512F (8). The first World::step
// picks the widest level this CPU and its OS support. Every level computes bit-identical
// results: the sweeps do element-wise IEEE-754 arithmetic only (add, mul, div, sqrt, each
// correctly rounded at any vector width), never reductions, and -ffp-contract=off keeps the
// compiler from fusing a multiply and an add into an FMA (which rounds once instead of twice).
// tests/core/test_simd.cpp checks the identity for every integrator, field and precision.
#pragma once

#include <string_view>

namespace fixstep {

/// A vector instruction-set level the sweeps are compiled for, narrowest first.
enum class SimdLevel { baseline, avx2, avx512 };

/// "baseline", "avx2" or "avx512".
[[nodiscard]] std::string_view simd_level_name(SimdLevel level);

/// True if this build has sweeps for `level` (x86-64 GCC/Clang builds have all three; other
/// targets have baseline only) and the CPU and OS can run them (CPUID and XGETBV, via
/// __builtin_cpu_supports).
[[nodiscard]] bool simd_supported(SimdLevel level);

/// The level World::step uses: the widest supported one, unless set_simd_level() chose another.
[[nodiscard]] SimdLevel simd_level();

/// Makes every later World::step (in any thread) use `level`; for tests and benchmarks that
/// compare levels. Results do not change, only speed. Throws std::invalid_argument naming the
/// level if !simd_supported(level).
void set_simd_level(SimdLevel level);

}  // namespace fixstep
