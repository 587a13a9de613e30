// No subnormal number in any tick of a decaying state (WorldSettings::flush_denormals). A
// strongly damped state decays towards zero; on CPUs where an operation with a subnormal
// operand or result takes a microcode assist (Intel's), every tick whose intermediates fall in
// that range costs many times a normal one. The test counts what the CPU reports instead of
// timing it, so a machine where subnormals are cheap still catches the cliff: after every tick,
// the IEEE underflow flag (a tiny result, fenv: raised on x86-64 and aarch64 alike), on x86 the
// denormal-operand flag (MXCSR bit 1: an operand was subnormal), and the subnormal values in the
// state arrays.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <cstdint>
#include <limits>

#include "fixstep/core/components.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace fixstep {
namespace {

/// The flags one tick raised: the IEEE underflow flag and, on x86, the denormal-operand flag.
/// Cleared before the tick (World::step keeps flags raised inside it: float_mode.hpp).
class TickFlags {
 public:
  TickFlags() {
    std::feclearexcept(FE_UNDERFLOW);
#if defined(__x86_64__) || defined(__i386__)
    _mm_setcsr(_mm_getcsr() & ~denormal_flag);
#endif
  }
  [[nodiscard]] static bool underflow() {
    return std::fetestexcept(FE_UNDERFLOW) != 0;
  }
  [[nodiscard]] static bool denormal_operand() {
#if defined(__x86_64__) || defined(__i386__)
    return (_mm_getcsr() & denormal_flag) != 0;
#else
    return false;
#endif
  }

 private:
  [[maybe_unused]] static constexpr unsigned denormal_flag = 0x2u;
};

struct Produced {
  int underflow_ticks = 0;         ///< ticks that raised the underflow flag
  int denormal_operand_ticks = 0;  ///< ticks with a subnormal operand (x86; 0 elsewhere)
  long subnormal_values = 0;       ///< subnormal x, y, vx, vy after a tick, summed over ticks
  int first = -1;                  ///< the first tick with any of them (-1: none)
  double largest_left = 0;         ///< the largest |x|, |v| after the last tick
};

template <class Real>
long count_subnormal(std::span<const Real> v) {
  long n = 0;
  for (const Real e : v) n += std::fpclassify(e) == FP_SUBNORMAL ? 1 : 0;
  return n;
}

/// Steps w `ticks` times, counting after each tick what it produced (TickFlags, and the
/// subnormal values of the state); largest_left from the state after the last.
template <class Real>
Produced step_counting(detail::WorldKernel<Real>& w, int ticks) {
  Produced p;
  for (int t = 1; t <= ticks; ++t) {
    const TickFlags flags;
    w.step();
    const bool underflow = TickFlags::underflow(), denormal = TickFlags::denormal_operand();
    const long values = count_subnormal(w.x()) + count_subnormal(w.y()) + count_subnormal(w.vx()) +
                        count_subnormal(w.vy());
    p.underflow_ticks += underflow ? 1 : 0;
    p.denormal_operand_ticks += denormal ? 1 : 0;
    p.subnormal_values += values;
    if (p.first < 0 && (underflow || denormal || values > 0)) p.first = t;
  }
  for (auto s : {w.x(), w.y(), w.vx(), w.vy()}) {
    for (const Real e : s) p.largest_left = std::max(p.largest_left, double(std::abs(e)));
  }
  return p;
}

/// `springs` bodies of 1 kg on springs of k = 100 N/m and dampers of b = 10 N·s/m (ζ = 0.5:
/// the amplitude falls as e^{-5t}, below the least normal float after about 17 s, the least
/// normal double after about 141 s) stepped at dt = 1/240 s for `ticks` ticks, each
/// starting at its own phase. Track: the dissipation account (the multi-pass path the CLI steps
/// in) instead of the fused sweep.
template <class Real>
Produced decay(Integrator integrator, bool track, int springs, int ticks, bool flush = true) {
  detail::WorldKernel<Real> w(WorldSettings{.dt = 1.0 / 240.0,
                                            .integrator = integrator,
                                            .flush_denormals = flush,
                                            .track_dissipation = track});
  for (int i = 0; i < springs; ++i) {
    const double phase = 6.283185307179586 * i / springs;
    BodyDef d;
    d.body.position = {0.5 * std::cos(phase), 0.25 * std::sin(3 * phase)};
    d.body.velocity = {std::sin(phase), -0.5 * std::cos(2 * phase)};
    d.spring = SpringDamper{.anchor = {}, .stiffness = 100.0, .damping = 10.0};
    w.create_body(d);
  }
  return step_counting(w, ticks);
}

void expect_none(const Produced& p, const std::string& what) {
  EXPECT_EQ(p.underflow_ticks, 0) << what << ": first at tick " << p.first;
  EXPECT_EQ(p.denormal_operand_ticks, 0) << what << ": first at tick " << p.first;
  EXPECT_EQ(p.subnormal_values, 0) << what << ": first at tick " << p.first;
}

// The case that was measured on an Intel Xeon: 20 000 damped f32 springs, 20 000 ticks (the
// state passes the least normal float around tick 4000). Every tick, not only every 64th, must
// keep its intermediates normal; and the state must still come to rest (zero, not held above).
TEST(Subnormals, TwentyThousandDampedF32SpringsProduceNoSubnormalInAnyTick) {
  const Produced p = decay<float>(Integrator::semi_implicit_euler, false, 20'000, 20'000);
  expect_none(p, "semi-implicit Euler, f32");
  EXPECT_EQ(p.largest_left, 0.0);
}

// Every integrator, f32 and f64, in the fused sweep and in the multi-pass path with the
// dissipation account (whose ½|v|² terms square the velocities).
TEST(Subnormals, EveryIntegratorAndPathDecaysWithoutASubnormal) {
  for (const Integrator integrator : all_integrators) {
    for (const bool track : {false, true}) {
      const std::string what =
          fmt::format("{}{}", integrator_name(integrator), track ? ", dissipation account" : "");
      expect_none(decay<float>(integrator, track, 500, 8'000), what + ", f32");
      expect_none(decay<double>(integrator, track, 500, 40'000), what + ", f64");
    }
  }
}

/// A chain of 3 bodies of 1 kg from a static body at the origin, on damped links of rest
/// length 0 (k = 100 N/m, b = 20 N·s/m), released from a bend: the links' dampers alone take
/// it to rest at the origin, its positions and velocities towards zero.
template <class Real>
Produced chain(Integrator integrator, bool track, int ticks, bool flush = true) {
  detail::WorldKernel<Real> w(WorldSettings{.dt = 1.0 / 240.0,
                                            .integrator = integrator,
                                            .flush_denormals = flush,
                                            .track_dissipation = track});
  BodyDef fixed;
  fixed.type = BodyType::static_body;
  Entity previous = w.create_body(fixed);
  for (int i = 1; i <= 3; ++i) {
    BodyDef d;
    d.body.position = {0.13 * i, 0.01 * (i % 3)};
    const Entity e = w.create_body(d);
    w.create_link(LinkDef{.body_a = previous,
                          .body_b = e,
                          .spring = {.stiffness = 100.0, .damping = 20.0, .rest_length = 0.0}});
    previous = e;
  }
  return step_counting(w, ticks);
}

// A linked world whose links are damped (the multi-pass path): its values below flush_below are
// flushed every 64th tick, as any damped world's. Two positions or velocities above it can still
// differ by less (the links' passes subtract them), so a few ticks of a chain at rest still
// produce a subnormal: without the flush, 3200-7300 of these 8000 ticks do (the dissipation
// account, implicit Euler); with it, at most 11 (measured), bounded here at 100.
TEST(Subnormals, ADampedChainComesToRestWithFewTicksOfSubnormals) {
  for (const Integrator integrator :
       {Integrator::semi_implicit_euler, Integrator::implicit_euler}) {
    const Produced off = chain<float>(integrator, true, 8'000, false);
    EXPECT_GT(off.underflow_ticks, 3000) << integrator_name(integrator) << ", unflushed";
  }
  for (const Integrator integrator : all_integrators) {
    for (const bool track : {false, true}) {
      const Produced p = chain<float>(integrator, track, 8'000);
      const std::string what = fmt::format("chain, {}{}", integrator_name(integrator),
                                           track ? ", dissipation account" : "");
      EXPECT_LE(p.underflow_ticks, 100) << what;
      EXPECT_LE(p.denormal_operand_ticks, 100) << what;
      EXPECT_EQ(p.subnormal_values, 0) << what;
    }
  }
}

// The flags and the count see the cliff at all: with the flush off, the same decay produces
// subnormals (what the test above would miss if the flags were never raised on this CPU).
TEST(Subnormals, WithoutTheFlushTheDecayProducesSubnormals) {
  const Produced p = decay<float>(Integrator::semi_implicit_euler, false, 500, 8'000, false);
  EXPECT_GT(p.underflow_ticks, 1000);
  EXPECT_GT(p.subnormal_values, 0);
}

}  // namespace
}  // namespace fixstep
