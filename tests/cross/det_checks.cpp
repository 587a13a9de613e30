// det_checks: the arithmetic the cross builds rely on, checked on the build's own platform
// (aarch64 under qemu, wasm32 under node), where GoogleTest is not built:
//   1. fixstep::det's golden bit patterns (tests/support/det_math_golden.inc,
//   DetMath.GoldenBitPatterns
//      natively): exp, expm1 and hypot give the x86-64 bits for every listed argument;
//   2. the caller's FPU mode does not reach a state (FloatHygiene.TheCallersFpuMode* natively):
//      tests/scenes/cross/hypot_rest.toml loaded, built and stepped 300 ticks in f64 and f32
//      under each directed rounding, and on aarch64 with FPCR.FZ (flush-to-zero), gives the
//      default mode's state hash (aarch64: FPCR RMode, which qemu honours; checked to fail
//      without the loader's and create_body's IeeeFloatMode). A mode that changes no
//      arithmetic is skipped and said so: qemu 7's aarch64 accepts FPCR.FZ but does not flush,
//      and wasm32 has no modes (emscripten's fesetround accepts and does nothing).
// Prints each failure and a summary; exit 0 when all pass, 1 otherwise.
#include <cfenv>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

#include "det_golden_cases.hpp"
#include "fixstep/core/bits.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/scene/scene.hpp"

namespace {

using namespace fixstep;

/// Failures among the golden bit patterns, each printed.
int golden_failures() {
  int failed = 0;
  for (const det_golden::Case& c : det_golden::cases) {
    if (const std::uint64_t got = det_golden::result_bits(c); got != c.out) {
      ++failed;
      std::printf("det function %d of %a, %a: got %a, golden %a\n", c.f, double_from_bits(c.x),
                  double_from_bits(c.y), double_from_bits(got), double_from_bits(c.out));
    }
  }
  std::printf("det_checks: %d of %zu golden bit patterns match\n",
              int(std::size(det_golden::cases)) - failed, std::size(det_golden::cases));
  return failed;
}

std::uint64_t loaded_hash(const std::string& file, Precision precision) {
  Scene s = load_scene(file);
  s.def.precision = precision;
  World sim = World(s.def);
  for (int i = 0; i < 300; ++i) sim.step({});
  return sim.state_hash();
}

/// Quotients any directed rounding changes: upward 1/3, downward -1/3, toward zero 1/10.
struct Probe {
  double third, minus_third, tenth, tiny_half;
  bool operator==(const Probe&) const = default;
};

Probe probe() {
  volatile double one = 1.0, three = 3.0, ten = 10.0, tiny = 0x1p-1060, half = 0.5;
  return {one / three, -one / three, one / ten, tiny * half};
}

/// A mode to try: its name, and how to enter and leave it (enter returns false when the
/// platform refuses it).
struct Mode {
  const char* name;
  bool (*enter)();
  void (*leave)();
};

#if defined(__aarch64__)
bool set_fz(bool on) {
  std::uint64_t fpcr = 0;
  asm volatile("mrs %0, fpcr" : "=r"(fpcr) : : "memory");
  fpcr = on ? fpcr | (1ull << 24) : fpcr & ~(1ull << 24);
  asm volatile("msr fpcr, %0" : : "r"(fpcr) : "memory");
  return true;
}
#endif

const Mode modes[] = {
    {"round upward", [] { return std::fesetround(FE_UPWARD) == 0; },
     [] { std::fesetround(FE_TONEAREST); }},
    {"round downward", [] { return std::fesetround(FE_DOWNWARD) == 0; },
     [] { std::fesetround(FE_TONEAREST); }},
    {"round toward zero", [] { return std::fesetround(FE_TOWARDZERO) == 0; },
     [] { std::fesetround(FE_TONEAREST); }},
#if defined(__aarch64__)
    {"flush-to-zero (FPCR.FZ)", [] { return set_fz(true); }, [] { set_fz(false); }},
#endif
};

/// Failures of the FPU-mode check, each printed. A mode the platform accepts but that changes
/// no arithmetic (wasm32's fesetround) is reported as not checked.
int fpu_mode_failures() {
  const std::string file = FIXSTEP_SOURCE_DIR "/tests/scenes/cross/hypot_rest.toml";
  const Probe nearest_probe = probe();
  int failed = 0, checked = 0;
  for (const Mode& m : modes) {
    if (!m.enter()) {
      std::printf("det_checks: %s: not a mode of this platform, not checked\n", m.name);
      continue;
    }
    const bool effective = !(probe() == nearest_probe);
    m.leave();
    if (!effective) {
      std::printf("det_checks: %s: accepted but changes no arithmetic here, not checked\n", m.name);
      continue;
    }
    for (const Precision p : {Precision::f64, Precision::f32}) {
      const std::uint64_t nearest = loaded_hash(file, p);
      m.enter();
      const std::uint64_t other = loaded_hash(file, p);
      m.leave();
      ++checked;
      if (other != nearest) {
        ++failed;
        std::printf("hypot_rest.toml %s under %s: %016" PRIx64 ", default mode %016" PRIx64 "\n",
                    precision_name(p).data(), m.name, other, nearest);
      }
    }
  }
  std::printf("det_checks: %d of %d runs in another FPU mode give the default mode's hash\n",
              checked - failed, checked);
  return failed;
}

}  // namespace

int main() {
  try {
    const int failed = golden_failures() + fpu_mode_failures();
    return failed == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("det_checks: %s\n", e.what());
    return 1;
  }
}
