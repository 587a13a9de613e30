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
#else
#define FIXSTEP_HAS_SIMD_CLONES 0
#endif
