// The floating-point mode fixstep computes a state in: IEEE-754 defaults, whatever
// the caller set. A state may not depend on the FPU mode, so every entry point that computes
// one holds an IeeeFloatMode: round-to-nearest with gradual underflow (no flush-to-zero, no
// denormals-are-zero) for its duration, the caller's mode restored after. They are
// World::step, accelerations, create_body, create_link, set_body, add_plane and the lazy
// rebuild of the force terms after a component changed; the readers of scenes, recordings and
// input scripts (strtod rounds by the mode); PointerDrag::apply; and the stability verdicts
// (judge_stability, check_stability), so a world is accepted or refused the same everywhere.
// Subnormals are flushed in software instead, the same on every platform
// (WorldSettings::flush_denormals, world_step.cpp). A game's own rules (TickRules), which run
// between ticks in the caller's mode, can hold one too.
//   x86: MXCSR rounding (bits 13-14), FTZ (15) and DAZ (6) cleared; exception masks and flags
//        kept, including flags raised inside (Intel SDM vol. 1, 10.2.3); the x87 control word's
//        rounding (bits 10-11) cleared too (SDM vol. 1, 8.1.5): no float or double arithmetic runs
//        on x87 on x86-64, but glibc's strtod rounds by it.
//   aarch64: FPCR RMode (bits 22-23), FZ (24), FZ16 (19) and AH/FIZ (1, 0) cleared (Arm ARM,
//        FPCR). wasm32 has no floating-point modes: IEEE defaults always.
#pragma once

#include <cstdint>

namespace fixstep {

/// Holds the IEEE-754 default floating-point mode (round to nearest, no FTZ/DAZ) from its
/// construction to its destruction, then restores the caller's. Costs a control-register
/// read or two (and the writes when the mode was not the default). Never throws; not copyable.
class IeeeFloatMode {
 public:
  IeeeFloatMode() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    saved_ = read_mxcsr();
    if ((saved_ & sse_bits) != 0) write_mxcsr(saved_ & ~sse_bits), changed_ = true;
    // The x87 control word's rounding (bits 10-11): glibc's fegetround reads it, so strtod
    // (the loader's numbers) rounds by it; fesetround sets it together with MXCSR's.
    asm volatile("fnstcw %0" : "=m"(saved_x87_) : : "memory");
    if ((saved_x87_ & x87_bits) != 0) {
      const std::uint16_t ieee = saved_x87_ & std::uint16_t(~x87_bits);
      asm volatile("fldcw %0" : : "m"(ieee) : "memory");
      changed_x87_ = true;
    }
#elif defined(__aarch64__)
    asm volatile("mrs %0, fpcr" : "=r"(saved_) : : "memory");
    if ((saved_ & fpcr_bits) != 0) {
      const std::uint64_t ieee = saved_ & ~fpcr_bits;
      asm volatile("msr fpcr, %0" : : "r"(ieee) : "memory");
      changed_ = true;
    }
#endif
  }
  ~IeeeFloatMode() {
#if defined(__x86_64__) || defined(__i386__)
    // The caller's mode bits back; the exception flags raised meanwhile stay raised.
    if (changed_) write_mxcsr((read_mxcsr() & ~sse_bits) | (saved_ & sse_bits));
    if (changed_x87_) asm volatile("fldcw %0" : : "m"(saved_x87_) : "memory");
#elif defined(__aarch64__)
    if (changed_) asm volatile("msr fpcr, %0" : : "r"(saved_) : "memory");  // no flags in FPCR
#endif
  }
  IeeeFloatMode(const IeeeFloatMode&) = delete;
  IeeeFloatMode& operator=(const IeeeFloatMode&) = delete;

 private:
  // The asm statements clobber "memory": the compiler keeps loads, stores and calls on their
  // side of a mode switch (the guarded work is reached through calls and memory).
#if defined(__x86_64__) || defined(__i386__)
  static constexpr unsigned sse_bits = 0x6000u | 0x8000u | 0x0040u;  // rounding, FTZ, DAZ
  static constexpr std::uint16_t x87_bits = 0x0C00u;                 // rounding
  static unsigned read_mxcsr() noexcept {
    unsigned csr = 0;
    asm volatile("stmxcsr %0" : "=m"(csr) : : "memory");
    return csr;
  }
  static void write_mxcsr(unsigned csr) noexcept {
    asm volatile("ldmxcsr %0" : : "m"(csr) : "memory");
  }
  unsigned saved_ = 0;
  std::uint16_t saved_x87_ = 0;
  bool changed_x87_ = false;
#elif defined(__aarch64__)
  static constexpr std::uint64_t fpcr_bits = (3ull << 22) | (1ull << 24) | (1ull << 19) | 3ull;
  std::uint64_t saved_ = 0;
#endif
  [[maybe_unused]] bool changed_ = false;
};

}  // namespace fixstep
