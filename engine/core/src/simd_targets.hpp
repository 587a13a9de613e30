// The function attributes that compile one function for an instruction-set level of simd.hpp
// (world_step.cpp's sweeps; the benchmarks' raw loops). Internal: not installed.
#pragma once

// Function attributes that compile one function for a level (x86-64 GCC/Clang only). GCC's
// generic tuning would split AVX-512 loops into 256-bit halves unless told to prefer 512-bit
// vectors; Clang has no such attribute option (it chooses by its own tuning).
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define FIXSTEP_HAS_SIMD_CLONES 1
#define FIXSTEP_TARGET_AVX2 __attribute__((target("avx2")))
#if defined(__clang__)
#define FIXSTEP_TARGET_AVX512 __attribute__((target("avx512f")))
#else
#define FIXSTEP_TARGET_AVX512 __attribute__((target("avx512f,prefer-vector-width=512")))
#endif
// AVX-512 with its 256-bit forms (AVX-512VL): 32 vector registers for code written in vectors of
// four doubles (the shape sweep's lanes).
#define FIXSTEP_TARGET_AVX512VL __attribute__((target("avx512f,avx512vl")))
#else
#define FIXSTEP_HAS_SIMD_CLONES 0
#endif

#if FIXSTEP_HAS_SIMD_CLONES
namespace fixstep::detail {
/// Whether the CPU and OS run AVX-512VL (checked once, as simd_supported checks a level): the
/// shape sweep's clone for the AVX-512 level needs it, and takes AVX2's without it.
[[nodiscard]] inline bool simd_avx512vl() {
  static const bool yes = __builtin_cpu_supports("avx512vl");
  return yes;
}
}  // namespace fixstep::detail
#endif
