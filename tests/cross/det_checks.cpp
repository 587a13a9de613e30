// det_checks: the arithmetic the cross builds rely on, checked on the build's own platform
// (aarch64 under qemu, wasm32 under node), where GoogleTest is not built:
//   1. fixstep::det's golden bit patterns (tests/det_math_golden.inc, DetMath.GoldenBitPatterns
//      natively): exp, expm1 and hypot give the x86-64 bits for every listed argument;
//   2. the caller's FPU mode does not reach a state (FloatHygiene.TheCallersFpuMode* natively):
//      tests/scenes/cross/hypot_rest.toml loaded, built and stepped 300 ticks in f64 and f32
//      under each directed rounding fesetround accepts gives the round-to-nearest state hash
//      (aarch64: FPCR RMode, which qemu honours; checked to fail without the loader's and
//      create_body's IeeeFloatMode. wasm32 has no modes: emscripten's fesetround accepts and
//      changes nothing, so there the runs match trivially).
// Prints each failure and a summary; exit 0 when all pass, 1 otherwise.
#include <cfenv>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "../det_golden_cases.hpp"
#include "fixstep/scene.hpp"
#include "fixstep/simulation.hpp"

namespace {

using namespace fixstep;

/// Failures among the golden bit patterns, each printed.
int golden_failures() {
  int failed = 0;
  for (const det_golden::Case& c : det_golden::cases) {
    if (const std::uint64_t got = det_golden::result_bits(c); got != c.out) {
      ++failed;
      std::printf("det function %d of %a, %a: got %a, golden %a\n", c.f, det_golden::from_bits(c.x),
                  det_golden::from_bits(c.y), det_golden::from_bits(got),
                  det_golden::from_bits(c.out));
    }
  }
  std::printf("det_checks: %d of %zu golden bit patterns match\n",
              int(std::size(det_golden::cases)) - failed, std::size(det_golden::cases));
  return failed;
}

std::uint64_t loaded_hash(const std::string& file, Precision precision) {
  Scene s = load_scene(file);
  s.precision = precision;
  Simulation sim = make_simulation(world_def(s));
  for (int i = 0; i < 300; ++i) sim.step({});
  return sim.state_hash();
}

/// Failures of the FPU-mode check, each printed.
int fpu_mode_failures() {
  const std::string file = FIXSTEP_SOURCE_DIR "/tests/scenes/cross/hypot_rest.toml";
  int failed = 0, checked = 0;
  for (const Precision p : {Precision::f64, Precision::f32}) {
    const std::uint64_t nearest = loaded_hash(file, p);
    for (const int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
      if (std::fesetround(mode) != 0) continue;  // a mode this platform does not have
      const std::uint64_t other = loaded_hash(file, p);
      std::fesetround(FE_TONEAREST);
      ++checked;
      if (other != nearest) {
        ++failed;
        std::printf("hypot_rest.toml %s under rounding mode %d: %016" PRIx64 ", nearest %016" PRIx64
                    "\n",
                    precision_name(p).data(), mode, other, nearest);
      }
    }
  }
  std::printf("det_checks: %d of %d runs under a directed rounding give the nearest hash\n",
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
