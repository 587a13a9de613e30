#include "fixstep/core/simd.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

#include "simd_targets.hpp"

namespace fixstep {

namespace {

SimdLevel widest_supported() {
  for (SimdLevel l : {SimdLevel::avx512, SimdLevel::avx2}) {
    if (simd_supported(l)) return l;
  }
  return SimdLevel::baseline;
}

std::atomic<SimdLevel>& chosen() {
  static std::atomic<SimdLevel> level{widest_supported()};
  return level;
}

}  // namespace

std::string_view simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::baseline:
      return "baseline";
    case SimdLevel::avx2:
      return "avx2";
    case SimdLevel::avx512:
      return "avx512";
  }
  return "unknown";
}

bool simd_supported(SimdLevel level) {
  switch (level) {
    case SimdLevel::baseline:
      return true;
#if FIXSTEP_HAS_SIMD_CLONES
    // libgcc's (and compiler-rt's) CPU model checks both CPUID and that the OS saves the
    // YMM/ZMM registers (XGETBV), so a supported level is safe to run.
    case SimdLevel::avx2:
      return __builtin_cpu_supports("avx2");
    case SimdLevel::avx512:
      return __builtin_cpu_supports("avx512f");
#else
    case SimdLevel::avx2:
    case SimdLevel::avx512:
      return false;
#endif
  }
  return false;
}

SimdLevel simd_level() {
  return chosen().load(std::memory_order_relaxed);
}

void set_simd_level(SimdLevel level) {
  if (!simd_supported(level)) {
    throw std::invalid_argument("set_simd_level: " + std::string(simd_level_name(level)) +
                                " is not supported by this CPU or build");
  }
  chosen().store(level, std::memory_order_relaxed);
}

}  // namespace fixstep
