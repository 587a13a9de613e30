// The benchmarks' raw loops run with x86 flush-to-zero and denormals-are-zero, so that they
// never meet subnormal arithmetic. World::step no longer does the same: it runs in
// the IEEE default mode (fixstep/core/float_mode.hpp) and flushes its state in software every 64th
// tick (WorldSettings::flush_denormals).
#pragma once

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace fixstep::bench {

/// Sets x86 flush-to-zero and denormals-are-zero for its scope.
class FlushDenormals {
 public:
  FlushDenormals() {
#if defined(__x86_64__) || defined(__i386__)
    saved_ = _mm_getcsr();
    _mm_setcsr(saved_ | 0x8040u);
#endif
  }
  ~FlushDenormals() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_setcsr(saved_);
#endif
  }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned saved_ = 0;
};

}  // namespace fixstep::bench
