// The floating-point mode a tick runs in (issue 23): IEEE-754 defaults, whatever the caller
// set. A state may not depend on the FPU mode, so World::step forces round-to-nearest with
// gradual underflow (no flush-to-zero, no denormals-are-zero) for its duration and restores the
// caller's mode afterwards. Subnormals are flushed in software instead, the same on every
// platform (WorldSettings::flush_denormals, world_step.cpp). Internal: not installed.
//   x86: MXCSR rounding (bits 13-14), FTZ (15) and DAZ (6) cleared; exception masks and flags
//        kept (Intel SDM vol. 1, 10.2.3).
//   aarch64: FPCR RMode (bits 22-23), FZ (24), FZ16 (19) and AH/FIZ (1, 0) cleared (Arm ARM,
//        FPCR). wasm32 has no floating-point modes: IEEE defaults always.
#pragma once

#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace fixstep {
namespace {

class DefaultFloatMode {
 public:
  DefaultFloatMode() {
#if defined(__x86_64__) || defined(__i386__)
    constexpr unsigned mode_bits = 0x6000u | 0x8000u | 0x0040u;  // rounding, FTZ, DAZ
    saved_ = _mm_getcsr();
    if ((saved_ & mode_bits) != 0) _mm_setcsr(saved_ & ~mode_bits), changed_ = true;
#elif defined(__aarch64__)
    constexpr std::uint64_t mode_bits = (3ull << 22) | (1ull << 24) | (1ull << 19) | 3ull;
    asm volatile("mrs %0, fpcr" : "=r"(saved_));
    if ((saved_ & mode_bits) != 0) {
      const std::uint64_t ieee = saved_ & ~mode_bits;
      asm volatile("msr fpcr, %0" : : "r"(ieee));
      changed_ = true;
    }
#endif
  }
  ~DefaultFloatMode() {
#if defined(__x86_64__) || defined(__i386__)
    if (changed_) _mm_setcsr(saved_);
#elif defined(__aarch64__)
    if (changed_) asm volatile("msr fpcr, %0" : : "r"(saved_));
#endif
  }
  DefaultFloatMode(const DefaultFloatMode&) = delete;
  DefaultFloatMode& operator=(const DefaultFloatMode&) = delete;

 private:
#if defined(__x86_64__) || defined(__i386__)
  [[maybe_unused]] unsigned saved_ = 0;
#else
  [[maybe_unused]] std::uint64_t saved_ = 0;
#endif
  [[maybe_unused]] bool changed_ = false;
};

}  // namespace
}  // namespace fixstep
