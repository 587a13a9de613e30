// Determinism: the physics state after N ticks is the same bits whatever drives it. Modelled on
// Box2D v3's test_determinism.c (a state hash compared with a stored value) and Jolt's
// determinism hash in CI.
//
// tests/golden/state_hashes.txt holds, for every shipped scene x integrator x precision the
// stability guard accepts, World::state_hash() after a fixed tick count. Every build in CI
// (GCC RelWithDebInfo, GCC Debug + ASan/UBSan, Clang) checks the same file, so the hashes
// must agree across optimisation levels and compilers. To change the physics on purpose,
// regenerate the file and commit it with the change:
//   FIXSTEP_REFRESH_GOLDEN=1 build/ci/bin/test_determinism --gtest_filter='*Golden*'
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "determinism_cases.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/capture/capture.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/summary.hpp"
#include "fixstep/scene/scene.hpp"
#include "scene_session.hpp"

namespace fixstep {
namespace {

using determinism::all_cases;
using determinism::Case;
using determinism::golden_file;
using determinism::golden_ticks;
using determinism::hash_direct;
using determinism::read_golden;
using determinism::scene_for;
using determinism::scenes_dir;
using determinism::ticks_for;

/// State hash after exactly `ticks` ticks (ticks_for) driven by the fixed-step loop, frames of
/// `frame_seconds()` each (the loop decides how many ticks each frame runs).
template <class FrameTime>
std::uint64_t hash_through_loop(const Case& c, std::uint64_t ticks, FrameTime frame_seconds) {
  World sim = World(scene_for(c).def);
  ticks = ticks_for(c.scene, ticks);
  FixedStepLoop loop(sim);
  while (sim.tick() < ticks) {
    loop.advance(frame_seconds(), TickInput{}, [&](const TickInput& in) {
      if (sim.tick() < ticks) sim.step(in);
    });
  }
  return sim.state_hash();
}

TEST(Determinism, GoldenStateHashesOfEveryShippedScene) {
  const auto cases = all_cases();
  ASSERT_GE(cases.size(), 20u) << "expected most scene x integrator x precision combinations";
  if (const char* refresh = std::getenv("FIXSTEP_REFRESH_GOLDEN"); refresh && *refresh == '1') {
    std::string text = fmt::format(
        "# World::state_hash() after {} ticks ({} for ball_pit.toml, {} for galton_board.toml: "
        "ticks_for in tests/cross/determinism_cases.cpp): scene integrator precision hash.\n"
        "# Regenerate on purpose only: FIXSTEP_REFRESH_GOLDEN=1 build/ci/bin/test_determinism "
        "--gtest_filter='*Golden*'\n",
        golden_ticks, ticks_for("ball_pit.toml", golden_ticks),
        ticks_for("galton_board.toml", golden_ticks));
    for (const Case& c : cases)
      text += fmt::format("{} {}\n", c.key(), hex_hash(hash_direct(c, golden_ticks)));
    write_file_atomic(golden_file(), text);
    GTEST_SKIP() << "rewrote " << golden_file() << " with " << cases.size() << " hashes";
  }
  const auto golden = read_golden();
  ASSERT_FALSE(golden.empty()) << "no hashes in " << golden_file();
  EXPECT_EQ(golden.size(), cases.size()) << "scenes or integrators changed: refresh the file";
  for (const Case& c : cases) {
    const auto it = golden.find(c.key());
    ASSERT_NE(it, golden.end()) << c.key() << " has no golden hash";
    EXPECT_EQ(hex_hash(hash_direct(c, golden_ticks)), it->second) << c.key();
  }
}

TEST(Determinism, SameStateAtAnyFrameRateAndAcrossRuns) {
  for (const Case& c : all_cases()) {
    if (c.integrator != Integrator::semi_implicit_euler && c.integrator != Integrator::rk4)
      continue;
    const std::uint64_t reference = hash_direct(c, 600);
    EXPECT_EQ(hash_direct(c, 600), reference) << c.key() << ": a second run";
    for (double fps : {30.0, 60.0, 144.0}) {
      EXPECT_EQ(hash_through_loop(c, 600, [fps] { return 1.0 / fps; }), reference)
          << c.key() << " at " << fps << " fps";
    }
    std::mt19937 rng(7);  // jittery frames of 1..40 ms, hitches included
    std::uniform_real_distribution<double> frame(0.001, 0.040);
    EXPECT_EQ(hash_through_loop(c, 600, [&] { return frame(rng); }), reference)
        << c.key() << " with jittery frames";
  }
}

TEST(Determinism, SameStateAtEverySimdLevel) {
  const SimdLevel saved = simd_level();
  for (const Case& c : all_cases()) {
    set_simd_level(SimdLevel::baseline);
    const std::uint64_t reference = hash_direct(c, 300);
    for (SimdLevel level : {SimdLevel::avx2, SimdLevel::avx512}) {
      if (!simd_supported(level)) continue;
      set_simd_level(level);
      EXPECT_EQ(hash_direct(c, 300), reference) << c.key() << " at " << simd_level_name(level);
    }
  }
  set_simd_level(saved);
}

// Two threads asked for (WorldSettings::threads = 2) on every shipped scene in its own
// integrator, both precisions: the states of one thread, bit for bit. Links and disc contacts
// split their passes between the threads; bodies with shapes (boxes.toml) are solved on one,
// in one order, and must not see the split either.
TEST(Determinism, SameStateOnOneAndTwoThreads) {
  for (const Case& c : all_cases()) {
    Scene scene = scene_for(c);
    if (c.integrator != load_scene(scenes_dir() / c.scene).def.settings.integrator) continue;
    std::uint64_t hashes[2] = {0, 0};
    for (const int threads : {1, 2}) {
      scene.def.settings.threads = threads;
      World sim = World(scene.def);
      const std::uint64_t ticks = ticks_for(c.scene, 300);
      for (std::uint64_t t = 0; t < ticks; ++t) sim.step();
      hashes[threads - 1] = sim.state_hash();
    }
    EXPECT_EQ(hashes[1], hashes[0]) << c.key() << " on two threads";
  }
}

TEST(Determinism, HeadlessSessionReachesTheSameState) {
  // The frame pipeline `render` and `view` share: drawing must not touch the physics.
  for (const char* file : {"default.toml", "projectile.toml", "spring_damper.toml"}) {
    const Case c{file, load_scene(scenes_dir() / file).def.settings.integrator,
                 load_scene(scenes_dir() / file).def.precision};
    Session session = testing::scene_session(scene_for(c), 64, 64);
    const VirtualClock clock(60.0);
    std::uint64_t frames = 0;
    while (session.simulation().tick() < 120) {
      session.advance(clock.frame_seconds());
      session.draw();
      ++frames;
    }
    EXPECT_EQ(session.simulation().state_hash(), hash_direct(c, session.simulation().tick()))
        << file << " after " << frames << " frames";
  }
}

TEST(Determinism, OneBitOfInitialStateChangesTheHash) {
  // The golden comparison fails when a single bit of the physics changes: flip one mantissa
  // bit of one body's starting position (and, separately, of the stiffness) and the state
  // after the golden tick count differs. (The lowest bit is not used: a one-ulp change of
  // x0 = 1000 m can round away in the first ticks, leaving nothing to detect.)
  auto flip = [](double v, int bit) {
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) ^ (std::uint64_t{1} << bit));
  };
  for (Precision p : {Precision::f64, Precision::f32}) {
    const Case c{"spring_damper.toml", Integrator::semi_implicit_euler, p};
    const std::uint64_t reference = hash_direct(c, golden_ticks);
    for (int which = 0; which < 2; ++which) {
      Scene s = scene_for(c);
      if (which == 0)
        s.def.bodies[0].body.position.x = flip(s.def.bodies[0].body.position.x, 40);
      else
        s.def.bodies[0].spring->stiffness = flip(s.def.bodies[0].spring->stiffness, 40);
      World changed = World(s.def);
      for (std::uint64_t t = 0; t < golden_ticks; ++t) changed.step();
      EXPECT_NE(changed.state_hash(), reference)
          << precision_name(p) << (which == 0 ? ": x0" : ": stiffness") << " with bit 40 flipped";
    }
  }
}

}  // namespace
}  // namespace fixstep
