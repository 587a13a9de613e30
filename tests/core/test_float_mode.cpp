// The caller's FPU mode cannot reach a state (fixstep/core/float_mode.hpp). Everything
// that computes one runs in the IEEE default mode whatever the caller set, so a caller that
// set flush-to-zero / denormals-are-zero (x86 MXCSR) or a directed rounding gets the bits of
// one that did not: stepping, loading a scene, building and editing a world, reading a
// recording or an input script.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cfenv>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/scene/input_script.hpp"
#include "fixstep/scene/scene.hpp"
#include "world_kernel.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace fixstep {
namespace {

constexpr int directed_roundings[] = {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO};

/// Sets FTZ and DAZ in MXCSR for its lifetime (x86), restoring the caller's on the way out
/// (also when a check throws).
class FtzDaz {
 public:
  FtzDaz() {
#if defined(__x86_64__) || defined(__i386__)
    saved_ = _mm_getcsr();
    _mm_setcsr(saved_ | 0x8040u);
#endif
  }
  ~FtzDaz() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_setcsr(saved_);
#endif
  }
  FtzDaz(const FtzDaz&) = delete;
  FtzDaz& operator=(const FtzDaz&) = delete;
  /// Whether this platform has the mode (x86 only).
  static constexpr bool exists() {
#if defined(__x86_64__) || defined(__i386__)
    return true;
#else
    return false;
#endif
  }

 private:
  [[maybe_unused]] unsigned saved_ = 0;
};

/// Sets a rounding mode (fesetround) for its lifetime, round-to-nearest restored after.
class Rounding {
 public:
  explicit Rounding(int mode) { EXPECT_EQ(std::fesetround(mode), 0) << "mode " << mode; }
  ~Rounding() { std::fesetround(FE_TONEAREST); }
  Rounding(const Rounding&) = delete;
  Rounding& operator=(const Rounding&) = delete;
};

/// f() in the default mode, then under FTZ/DAZ and each directed rounding: every result must
/// equal the first. `what` names the case in failures.
template <class F>
void expect_mode_independent(const std::string& what, F f) {
  const auto ieee = f();
  if (FtzDaz::exists()) {
    const FtzDaz ftz;
    EXPECT_EQ(f(), ieee) << what << ": FTZ/DAZ";
  }
  for (const int mode : directed_roundings) {
    const Rounding r(mode);
    EXPECT_EQ(f(), ieee) << what << ": rounding mode " << mode;
  }
}

// Stepping, with the flush on and off, through the subnormal range (a damped f32 spring, every
// tick's hash of 20 000), for semi-implicit Euler and a velocity Verlet world whose damping
// factors use det::exp.
std::uint64_t damped_hash(bool flush, Integrator integrator) {
  detail::WorldKernel<float> w(
      WorldSettings{.dt = 0.01, .integrator = integrator, .flush_denormals = flush});
  BodyDef d;
  d.body.position = {1.0, 1.0};
  d.spring = SpringDamper{.anchor = {}, .stiffness = 100.0, .damping = 50.0};
  w.create_body(d);
  std::uint64_t h = 0;
  for (int i = 0; i < 20'000; ++i) {
    w.step();
    h = h * 31 + w.state_hash();  // every tick: the state crosses 1e-38 on the way to zero
  }
  return h;
}

TEST(FloatHygiene, TheCallersFpuModeDoesNotReachTheState) {
  for (bool flush : {true, false}) {
    for (Integrator integrator : {Integrator::semi_implicit_euler, Integrator::velocity_verlet}) {
      expect_mode_independent(
          fmt::format("{}, flush_denormals = {}", integrator_name(integrator), flush),
          [&] { return damped_hash(flush, integrator); });
    }
  }
}

// Before the first tick: a scene loaded and its world built in the caller's mode.
// tests/scenes/cross/hypot_rest.toml's numbers are read by strtod (which rounds in the current
// mode) and its shear rest lengths come from det::hypot, whose exact products need
// round-to-nearest; both scenes' springs are given in the frequency form (stiffness and damping
// computed at load) and damped_exp.toml's damping factors are inexact. In f32, create_body
// narrows every double. Fails without the loader's or create_body's guard.
std::uint64_t loaded_hash(const char* name, Precision precision) {
  Scene s = load_scene(std::string(FIXSTEP_SOURCE_DIR) + "/tests/scenes/cross/" + name);
  s.def.precision = precision;
  World sim = World(s.def);
  for (int i = 0; i < 300; ++i) sim.step({});
  return sim.state_hash();
}

TEST(FloatHygiene, TheCallersFpuModeDoesNotReachALoadedWorld) {
  for (const char* name : {"hypot_rest.toml", "damped_exp.toml"}) {
    for (const Precision p : {Precision::f64, Precision::f32}) {
      expect_mode_independent(fmt::format("{} {}", name, precision_name(p)),
                              [&] { return loaded_hash(name, p); });
    }
  }
}

// A component changed on a running world: its coefficients are rebuilt lazily, by the next
// step or by accelerations(), which a caller may call in its own mode. Fails without both
// accelerations' and rebuild_terms' guards (either one covers this path).
std::uint64_t edited_hash(bool accelerations_in_callers_mode, int mode) {
  detail::WorldKernel<float> w(
      WorldSettings{.dt = 0.01, .integrator = Integrator::velocity_verlet});
  BodyDef d;
  d.body.position = {0.3, 0.7};
  const Entity e = w.create_body(d);
  w.step();
  w.set(e, SpringDamper{.anchor = {0.1, 0.0}, .stiffness = 0.3, .damping = 0.7});
  if (accelerations_in_callers_mode) {
    const Rounding r(mode);
    std::vector<float> ax(1), ay(1);
    w.accelerations(ax, ay, {});
  }
  for (int i = 0; i < 100; ++i) w.step();
  return w.state_hash();
}

TEST(FloatHygiene, TheCallersFpuModeDoesNotReachCoefficientsRebuiltOutsideAStep) {
  const std::uint64_t plain = edited_hash(false, FE_TONEAREST);
  for (const int mode : directed_roundings) {
    EXPECT_EQ(edited_hash(true, mode), plain) << "rounding mode " << mode;
  }
}

// Reading what a replay steps with: a recording's inputs and an input script's numbers, written
// as shortest decimals (0.1, 0.3) that strtod rounds by the current mode. Fails without the
// readers' guards.
TEST(FloatHygiene, TheCallersFpuModeDoesNotReachARecordingOrAnInputScript) {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef b;
  b.name = "b";
  def.bodies = {b};
  World sim = World(def);
  Recorder recorder(def, "scenes/b.toml", 1);
  for (std::uint64_t t = 0; t < 5; ++t) {
    const TickInput in{.tick = t, .push = {0.1 * double(t), -0.3}, .pointer = {0.7, 1.1}};
    sim.step(in);
    recorder.record(in, sim);
  }
  const std::string text = format_recording(recorder.finish(sim));
  expect_mode_independent("recording", [&] { return parse_recording(text, "r.rec"); });

  const std::string script = "[[at]]\ntick = 1\npush = [0.1, -0.3]\npointer = [0.7, 1.1]\n";
  expect_mode_independent("input script", [&] {
    return script_inputs(parse_input_script(script, "s.toml", def.bodies), 3);
  });
}

}  // namespace
}  // namespace fixstep
