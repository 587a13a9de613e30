// The floating-point mode fixstep computes a state in (issue 23): IEEE-754 defaults, whatever
// the caller set. A state may not depend on the FPU mode, so every entry point that computes
// one (World::step, World::create_body / create_link / set_body / add_plane, the scene loader,
// PointerDrag::apply) holds an IeeeFloatMode: round-to-nearest with gradual underflow (no
// flush-to-zero, no denormals-are-zero) for its duration, the caller's mode restored after.
// Subnormals are flushed in software instead, the same on every platform
// (WorldSettings::flush_denormals, world_step.cpp). A game's own rules (TickRules), which run
// between ticks in the caller's mode, can hold one too.
//   x86: MXCSR rounding (bits 13-14), FTZ (15) and DAZ (6) cleared; exception masks and flags
//        kept (Intel SDM vol. 1, 10.2.3); the x87 control word's rounding (bits 10-11)
//        cleared too (SDM vol. 1, 8.1.5): no float or double arithmetic runs on x87 on x86-64,
//        but glibc's strtod rounds by it.
//   aarch64: FPCR RMode (bits 22-23), FZ (24), FZ16 (19) and AH/FIZ (1, 0) cleared (Arm ARM,
//        FPCR). wasm32 has no floating-point modes: IEEE defaults always.
#pragma once

#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace fixstep {

/// Holds the IEEE-754 default floating-point mode (round to nearest, no FTZ/DAZ) from its
/// construction to its destruction, then restores the caller's. Costs a control-register
/// read or two (and the writes when the mode was not the default). Never throws; not copyable.
class IeeeFloatMode {
 public:
  IeeeFloatMode() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    constexpr unsigned sse_bits = 0x6000u | 0x8000u | 0x0040u;  // rounding, FTZ, DAZ
    saved_ = _mm_getcsr();
    if ((saved_ & sse_bits) != 0) _mm_setcsr(saved_ & ~sse_bits), changed_ = true;
    // The x87 control word's rounding (bits 10-11): glibc's fegetround reads it, so strtod
    // (the loader's numbers) rounds by it; fesetround sets it together with MXCSR's.
    asm volatile("fnstcw %0" : "=m"(saved_x87_));
    if ((saved_x87_ & 0x0C00u) != 0) {
      const std::uint16_t ieee = saved_x87_ & std::uint16_t(~0x0C00u);
      asm volatile("fldcw %0" : : "m"(ieee));
      changed_x87_ = true;
    }
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
  ~IeeeFloatMode() {
#if defined(__x86_64__) || defined(__i386__)
    if (changed_) _mm_setcsr(saved_);
    if (changed_x87_) asm volatile("fldcw %0" : : "m"(saved_x87_));
#elif defined(__aarch64__)
    if (changed_) asm volatile("msr fpcr, %0" : : "r"(saved_));
#endif
  }
  IeeeFloatMode(const IeeeFloatMode&) = delete;
  IeeeFloatMode& operator=(const IeeeFloatMode&) = delete;

 private:
#if defined(__x86_64__) || defined(__i386__)
  [[maybe_unused]] unsigned saved_ = 0;
  std::uint16_t saved_x87_ = 0;
  bool changed_x87_ = false;
#else
  [[maybe_unused]] std::uint64_t saved_ = 0;
#endif
  [[maybe_unused]] bool changed_ = false;
};

}  // namespace fixstep
