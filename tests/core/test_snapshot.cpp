// Input per tick, snapshots, pick and drag, and the sync test.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "determinism_cases.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/core/pointer_drag.hpp"
#include "fixstep/core/rewind.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/sync_test.hpp"
#include "fixstep/core/work_progress.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"

// count_new.cpp: this program's operator new, counting the bytes asked for while counting.
extern std::atomic<bool> counting;
extern std::atomic<std::size_t> counted_bytes;

namespace fixstep {
namespace {

const std::filesystem::path scenes_dir = FIXSTEP_SOURCE_DIR "/assets/scenes";

// --- input per tick -----------------------------------------------------------------------

/// A scripted frame: events that happen during it (before its ticks), then its frame time.
struct Frame {
  std::vector<std::pair<bool, std::uint32_t>> events;  ///< (press?, buttons)
  double seconds = 0.0;
};

/// Runs the frames through a loop of dt = 10 ms and returns every tick's input.
std::vector<TickInput> run_frames(const std::vector<Frame>& frames) {
  FixedStepLoop loop(0.01);
  InputSampler sampler;
  std::vector<TickInput> seen;
  for (const Frame& f : frames) {
    for (const auto& [press, buttons] : f.events) {
      press ? sampler.press(buttons) : sampler.release(buttons);
    }
    loop.advance(f.seconds, sampler, [&](const TickInput& in) { seen.push_back(in); });
  }
  return seen;
}

int count_pressed(const std::vector<TickInput>& ticks, std::uint32_t button) {
  return static_cast<int>(std::count_if(ticks.begin(), ticks.end(),
                                        [&](const TickInput& in) { return in.pressed & button; }));
}

TEST(InputPerTick, APressDuringAFrameWithoutTicksReachesTheNextFramesFirstTick) {
  // Frame 1 runs no tick (4 ms < 10 ms); the press made before it waits for frame 2.
  const auto ticks = run_frames({{{{true, button_left}}, 0.004}, {{}, 0.006}, {{}, 0.01}});
  ASSERT_EQ(ticks.size(), 2u);
  EXPECT_EQ(ticks[0].tick, 0u);
  EXPECT_EQ(ticks[0].pressed, button_left);
  EXPECT_EQ(ticks[0].held, button_left);
  EXPECT_EQ(ticks[1].pressed, 0u);  // never seen twice
  EXPECT_EQ(ticks[1].held, button_left);
}

TEST(InputPerTick, AFrameOfManyTicksShowsThePressToItsFirstTickOnly) {
  const auto ticks = run_frames({{{{true, button_action}}, 0.05}});
  ASSERT_EQ(ticks.size(), 5u);
  EXPECT_EQ(ticks[0].pressed, button_action);
  EXPECT_EQ(count_pressed(ticks, button_action), 1);
  for (const TickInput& in : ticks) EXPECT_EQ(in.held, button_action);
}

TEST(InputPerTick, ATapBetweenTwoTicksIsNeverLost) {
  // Pressed and released within one frame: the next tick sees both edges, not held.
  const auto ticks = run_frames(
      {{{}, 0.01}, {{{true, button_pointer_primary}, {false, button_pointer_primary}}, 0.01}});
  ASSERT_EQ(ticks.size(), 2u);
  EXPECT_EQ(ticks[1].pressed, button_pointer_primary);
  EXPECT_EQ(ticks[1].released, button_pointer_primary);
  EXPECT_EQ(ticks[1].held, 0u);
}

TEST(InputPerTick, EveryPressAndReleaseOfARandomScriptReachesExactlyOneTick) {
  // 2000 frames of random length (0 to 3.5 ticks) with random events: each edge is reported
  // once, by the first tick after it, and the held bits always follow the events.
  std::uint64_t seed = 12345;
  auto next = [&] { return (seed = seed * 6364136223846793005ull + 1442695040888963407ull) >> 33; };
  std::vector<Frame> frames;
  int presses = 0, releases = 0;
  std::uint32_t held = 0;
  for (int f = 0; f < 2000; ++f) {
    Frame frame;
    frame.seconds = 0.035 * double(next() % 1000) / 1000.0;
    const int events = static_cast<int>(next() % 3);
    for (int e = 0; e < events; ++e) {
      const std::uint32_t b = 1u << (next() % 5);
      const bool press = (held & b) == 0;
      frame.events.emplace_back(press, b);
      press ? (held |= b, ++presses) : (held &= ~b, ++releases);
    }
    frames.push_back(frame);
  }
  frames.push_back({{}, 0.01});  // a last tick to deliver the last frame's events
  const auto ticks = run_frames(frames);
  int seen_presses = 0, seen_releases = 0;
  for (const TickInput& in : ticks) {
    seen_presses += std::popcount(in.pressed);
    seen_releases += std::popcount(in.released);
  }
  // Presses of one button between two ticks merge (a set of bits); count them the same way.
  FixedStepLoop loop(0.01);
  int expected_presses = 0, expected_releases = 0;
  std::uint32_t pending_p = 0, pending_r = 0, h = 0;
  std::size_t ticks_run = 0;
  for (const Frame& f : frames) {
    for (const auto& [press, b] : f.events) {
      if (press)
        pending_p |= b & ~h, h |= b;
      else
        pending_r |= b & h, h &= ~b;
      // The event belongs to the first tick after it.
      ASSERT_LT(ticks_run, ticks.size());
      EXPECT_TRUE((press ? ticks[ticks_run].pressed : ticks[ticks_run].released) & b);
    }
    loop.advance(f.seconds, TickInput{}, [&](const TickInput&) {
      expected_presses += std::popcount(pending_p), expected_releases += std::popcount(pending_r);
      pending_p = pending_r = 0;
      ++ticks_run;
    });
  }
  EXPECT_GT(presses, 900);
  EXPECT_EQ(seen_presses, expected_presses);
  EXPECT_EQ(seen_releases, expected_releases);
  EXPECT_EQ(ticks.back().held, held);
}

// --- snapshots ----------------------------------------------------------------------------

Scene scene_with(const std::string& file, Integrator integrator, Precision precision) {
  Scene s = load_scene(scenes_dir / file);
  s.def.settings.integrator = integrator;
  s.def.precision = precision;
  return s;
}

/// An input that changes every few ticks: pushes, and a drag of body 0 towards a point (shared
/// with tests/cross/sync_matrix.cpp).
using determinism::scripted_input;

TEST(Snapshot, RestoringGivesTheSameBitsAsNeverHavingLeft) {
  for (const char* file : {"default.toml", "chain.toml", "rope.toml"}) {
    for (Integrator integrator :
         {Integrator::semi_implicit_euler, Integrator::rk4, Integrator::implicit_euler}) {
      for (Precision p : {Precision::f64, Precision::f32}) {
        SCOPED_TRACE(fmt::format("{} {} {}", file, integrator_name(integrator), precision_name(p)));
        Scene scene = scene_with(file, integrator, p);
        scene.def.allow_unstable = true;
        World sim = World(scene.def);
        for (std::uint64_t t = 0; t < 100; ++t) sim.step(scripted_input(t));
        WorldSnapshot snap;
        EXPECT_TRUE(snap.empty());
        sim.save(snap);
        EXPECT_EQ(snap.tick(), 100u);
        for (std::uint64_t t = 100; t < 300; ++t) sim.step(scripted_input(t));
        const std::uint64_t hash = sim.state_hash();
        const double dissipated = sim.dissipated_energy();
        sim.restore(snap);
        EXPECT_EQ(sim.tick(), 100u);
        for (std::uint64_t t = 100; t < 300; ++t) sim.step(scripted_input(t));
        EXPECT_EQ(sim.state_hash(), hash);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(sim.dissipated_energy()),
                  std::bit_cast<std::uint64_t>(dissipated));
      }
    }
  }
}

TEST(Snapshot, APileRestoredOverALaterTickOrIntoAFreshWorldStepsTheSameBits) {
  // A snapshot copies the sizes of the per-tick arrays of the disc contacts and the contact
  // events but not their elements (scratch_vector.hpp), nor the broadphase's grid: whatever a
  // world's own scratch holds (a later tick's, or none yet), the restored state steps to the
  // same bits and the same contact events.
  Scene scene = load_scene(scenes_dir / "ball_pit.toml");
  // Each tick's state hash and contact events begun and ended (slots and speeds).
  auto run = [](World& w) {
    std::vector<std::uint64_t> seen;
    for (int t = 0; t < 12; ++t) {
      w.step(TickInput{w.tick()});
      seen.push_back(w.state_hash());
      for (const auto events : {w.contacts_begun(), w.contacts_ended()}) {
        seen.push_back(events.size());
        for (const ContactEvent& e : events) {
          seen.push_back(e.a.slot() * 4096 + e.b.slot());
          seen.push_back(std::bit_cast<std::uint64_t>(e.normal_speed));
        }
      }
    }
    return seen;
  };
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(fmt::format("{} threads", threads));
    scene.def.settings.threads = threads;
    World sim = World(scene.def);
    for (int t = 0; t < 150; ++t) sim.step(TickInput{sim.tick()});
    WorldSnapshot snap;
    sim.save(snap);
    const std::vector<std::uint64_t> first = run(sim);
    EXPECT_GT(first.size(), 12u * 3u);  // some contacts begin or end
    sim.restore(snap);                  // over the scratch of 12 ticks later
    EXPECT_EQ(run(sim), first);
    World fresh = World(scene.def);  // never stepped: its scratch is empty
    fresh.restore(snap);
    EXPECT_EQ(run(fresh), first);
    WorldSnapshot copy = snap;  // a copy of a snapshot holds the state too
    sim.restore(copy);
    EXPECT_EQ(run(sim), first);
  }
}

TEST(Snapshot, AStateTakenBeforeAComponentChangeComesBackWhole) {
  Scene scene = load_scene(scenes_dir / "default.toml");
  World sim = World(scene.def);
  for (int t = 0; t < 30; ++t) sim.step();
  WorldSnapshot snap;
  sim.save(snap);
  for (int t = 0; t < 30; ++t) sim.step();
  const std::uint64_t expected = sim.state_hash();
  sim.restore(snap);
  // A game rule removes a spring; restoring must bring the spring back.
  sim.remove<SpringDamper>(sim.bodies()[0]);
  for (int t = 0; t < 30; ++t) sim.step();
  EXPECT_NE(sim.state_hash(), expected);
  sim.restore(snap);
  for (int t = 0; t < 30; ++t) sim.step();
  EXPECT_EQ(sim.state_hash(), expected);
}

#if defined(__linux__)
/// This process's threads (Linux: /proc/self/task), by id.
std::vector<std::string> thread_ids() {
  std::vector<std::string> ids;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) {
    ids.push_back(entry.path().filename().string());
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

// A rollback restores a snapshot every frame. A world's worker threads (the integration's and
// the links' Workers, the discs' and the shapes' SecondThread) hold nothing a tick's result
// depends on, so restoring keeps them: the same threads step on, with the same bits. Each
// restore used to stop them, and the next tick started new ones (51 threads for 50 rollbacks).
TEST(Snapshot, RestoringKeepsTheWorldsWorkerThreads) {
  for (const char* file : {"ball_pit.toml", "boxes.toml", "cloth.toml", "ragdoll.toml"}) {
    SCOPED_TRACE(file);
    Scene scene = load_scene(scenes_dir / file);
    scene.def.settings.threads = 2;
    World sim = World(scene.def);
    for (int t = 0; t < 5; ++t) sim.step();
    WorldSnapshot snap;
    sim.save(snap);
    for (int t = 0; t < 3; ++t) sim.step();
    const std::uint64_t expected = sim.state_hash();
    const std::vector<std::string> before = thread_ids();
    ASSERT_GT(before.size(), 1u);  // a worker runs beside this thread
    for (int k = 0; k < 3; ++k) {
      sim.restore(snap);
      for (int t = 0; t < 3; ++t) sim.step();
      EXPECT_EQ(sim.state_hash(), expected);
    }
    EXPECT_EQ(thread_ids(), before);
  }
}
#endif

TEST(Snapshot, RestoringAnEmptySnapshotIsRefused) {
  World sim = World(load_scene(scenes_dir / "default.toml").def);
  EXPECT_THROW(sim.restore(WorldSnapshot{}), std::invalid_argument);
}

TEST(Snapshot, SessionSnapshotsKeepTheLoopsAccumulatorAndTick) {
  Session session(load_scene(scenes_dir / "spring_damper.toml").def);
  session.advance(0.0371);  // leaves a part of a tick in the accumulator
  Session::Snapshot snap;
  session.save(snap);
  const double alpha = session.alpha();
  ASSERT_GT(alpha, 0.0);
  for (int f = 0; f < 20; ++f) session.advance(0.013);
  const std::uint64_t hash = session.simulation().state_hash();
  session.restore(snap);
  EXPECT_EQ(session.alpha(), alpha);
  EXPECT_EQ(session.loop().ticks(), snap.loop.ticks);
  for (int f = 0; f < 20; ++f) session.advance(0.013);
  EXPECT_EQ(session.simulation().state_hash(), hash);
  EXPECT_THROW(session.loop().restore({.accumulator = 1.0, .ticks = 0}), std::invalid_argument);
}

TEST(Rewind, StepsBackOneTickAtATimeThroughTheLastCapacityTicks) {
  World sim = World(load_scene(scenes_dir / "default.toml").def);
  RewindBuffer rewind(5);
  std::vector<std::uint64_t> hashes;
  rewind.push(sim);
  hashes.push_back(sim.state_hash());
  for (int t = 0; t < 8; ++t) {
    sim.step();
    rewind.push(sim);
    hashes.push_back(sim.state_hash());
  }
  EXPECT_EQ(rewind.size(), 5u);  // ticks 4..8
  EXPECT_EQ(rewind.oldest_tick(), 4u);
  for (std::uint64_t back = 7; back >= 4; --back) {
    const WorldSnapshot* past = rewind.step_back();
    ASSERT_NE(past, nullptr);
    sim.restore(*past);
    EXPECT_EQ(sim.tick(), back);
    EXPECT_EQ(sim.state_hash(), hashes[back]);
  }
  EXPECT_EQ(rewind.step_back(), nullptr);  // tick 4 is the oldest kept
  // Resuming from tick 4 replaces the future that was rewound.
  sim.step();
  rewind.push(sim);
  EXPECT_EQ(rewind.size(), 2u);
  EXPECT_EQ(sim.state_hash(), hashes[5]);
  EXPECT_THROW(RewindBuffer(0), std::invalid_argument);
}

TEST(Rewind, CapacitySpansTheSecondsWithinTheMemoryBudget) {
  constexpr std::size_t MiB = std::size_t{1} << 20;
  EXPECT_EQ(rewind_capacity(10.0, 1.0 / 60.0, 1000, 512 * MiB), 600u);  // 10 s of 1/60 s ticks
  EXPECT_EQ(rewind_capacity(10.0, 0.1, 1000, 512 * MiB), 100u);
  EXPECT_EQ(rewind_capacity(10.0, 1.0 / 60.0, 48 * MiB, 512 * MiB), 10u);  // 90 000 bodies
  EXPECT_EQ(rewind_capacity(10.0, 1.0 / 60.0, 600 * MiB, 512 * MiB), 1u);  // always one state
  EXPECT_EQ(rewind_capacity(10.0, 1e-300, 1, 512 * MiB), 512 * MiB);       // no overflow
  EXPECT_EQ(rewind_capacity(0.0, 0.01, 1000, 512 * MiB), 1u);
  for (const double dt : {0.0, -0.01, std::nan("")})
    EXPECT_THROW((void)rewind_capacity(10.0, dt, 1000, MiB), std::invalid_argument) << dt;
  EXPECT_THROW((void)rewind_capacity(-1.0, 0.01, 1000, MiB), std::invalid_argument);
}

TEST(Snapshot, SnapshotBytesIsWhatACopyAllocates) {
  // The reference: the bytes operator new is asked for (counted below) while a snapshot is
  // taken into an empty WorldSnapshot.
  for (const char* file :
       {"cloth.toml", "default.toml", "bounce.toml", "chain.toml", "boxes.toml", "car.toml",
        "ragdoll.toml", "platforms.toml", "ball_pit.toml", "sleeping_pile.toml", "level.toml"}) {
    for (const Precision p : {Precision::f32, Precision::f64}) {
      Scene scene = load_scene(scenes_dir / file);
      scene.def.precision = p;
      World sim = World(scene.def);
      sim.step();  // the force terms and scratch arrays are built at the first tick
      WorldSnapshot snap;
      counted_bytes = 0;
      counting = true;
      sim.save(snap);
      counting = false;
      EXPECT_EQ(counted_bytes.load(), sim.snapshot_bytes()) << file;
      EXPECT_GT(sim.snapshot_bytes(), sim.body_count() * 4 * (p == Precision::f32 ? 4 : 8));
    }
  }
}

// --- pick and drag ------------------------------------------------------------------------

WorldDef free_bodies(Integrator integrator, double dt) {
  WorldDef def;
  def.settings.dt = dt;
  def.settings.integrator = integrator;
  BodyDef a, b;
  a.name = "a";
  b.name = "b";
  b.body = {.mass = 50.0, .position = {3, 0}, .velocity = {}};
  b.appearance = Appearance{.radius = 1.0};
  def.bodies = {a, b};
  return def;
}

TEST(PointerDrag, ADraggedBodyFollowsThePointerAtAnyDtAndMass) {
  // The drag spring (5 Hz, ζ = 0.7) settles within a few of its periods (0.2 s) whatever the
  // mass (per unit mass) and stays stable at dt = 0.1 s, where ω·dt = 3.1 would blow up an
  // explicit spring.
  for (Integrator integrator : all_integrators) {
    for (double dt : {1.0 / 60, 0.1}) {
      SCOPED_TRACE(fmt::format("{} dt={}", integrator_name(integrator), dt));
      World sim = World(free_bodies(integrator, dt));
      TickInput in;
      in.pointer = {4.0, 2.0};
      in.drag_body = fixstep::defined_entity(1);
      for (int t = 0; t < int(3.0 / dt); ++t) sim.step(in);
      EXPECT_NEAR(sim.body(sim.bodies()[1]).position.x, 4.0, 1e-3);
      EXPECT_NEAR(sim.body(sim.bodies()[1]).position.y, 2.0, 1e-3);
      EXPECT_EQ(sim.body(sim.bodies()[0]).position.x, 0.0);  // the other body is left alone
    }
  }
}

TEST(PointerDrag, APressPicksTheBodyUnderThePointerAndAReleaseLetsGo) {
  World sim = World(free_bodies(Integrator::semi_implicit_euler, 1.0 / 60));
  EXPECT_EQ(pick_body(sim, {3.5, 0.5}, 0.1),
            fixstep::defined_entity(1));  // within b's radius of 1 m
  EXPECT_EQ(pick_body(sim, {0.05, 0.0}, 0.1),
            fixstep::defined_entity(0));  // a has no radius: the tolerance
  EXPECT_EQ(pick_body(sim, {1.5, 0.0}, 0.1), null_entity);
  PointerDrag drag(0.1);
  TickInput in{
      .held = button_pointer_primary, .pressed = button_pointer_primary, .pointer = {3.2, 0.0}};
  drag.apply(in, sim);
  EXPECT_EQ(in.drag_body, fixstep::defined_entity(1));
  TickInput hold{.held = button_pointer_primary, .pointer = {0.0, 0.0}};
  drag.apply(hold, sim);  // held: still b, although the pointer is now over a
  EXPECT_EQ(hold.drag_body, fixstep::defined_entity(1));
  TickInput up{.released = button_pointer_primary};
  drag.apply(up, sim);
  EXPECT_EQ(up.drag_body, null_entity);
  EXPECT_THROW(PointerDrag(-1.0), std::invalid_argument);
}

// --- the sync test ------------------------------------------------------------------------

/// Cases: every shipped scene x integrator x precision the stability guard accepts.
struct SyncCase {
  std::string file;
  Integrator integrator;
  Precision precision;
};

std::vector<SyncCase> sync_cases() {
  std::vector<SyncCase> cases;
  for (const auto& e : std::filesystem::directory_iterator(scenes_dir)) {
    if (e.path().extension() != ".toml") continue;
    for (Integrator i : all_integrators) {
      for (Precision p : {Precision::f64, Precision::f32}) {
        try {
          (void)World(scene_with(e.path().filename().string(), i, p).def);
        } catch (const UnstableDefinition&) {
          continue;  // refused by the stability guard
        }
        cases.push_back({e.path().filename().string(), i, p});
      }
    }
  }
  return cases;
}

TEST(SyncTest, EveryShippedSceneIntegratorAndPrecisionRollsBackBitExactly) {
  const auto cases = sync_cases();
  EXPECT_GE(cases.size(), 60u);
  for (const SyncCase& c : cases) {
    SCOPED_TRACE(fmt::format("{} {} {}", c.file, integrator_name(c.integrator),
                             precision_name(c.precision)));
    const Scene scene = scene_with(c.file, c.integrator, c.precision);
    // Implicit Euler on a large network factorizes per Newton iteration (~7 ms a tick for
    // cloth.toml, a second in the Debug ASan build), and a thousand discs in contact
    // (ball_pit.toml) take ~1.5 ms a tick: fewer ticks there, every path still run.
    const bool slow = (c.integrator == Integrator::implicit_euler && scene.def.links.size() > 40) ||
                      (scene.def.settings.contacts && scene.def.bodies.size() > 1000);
#ifdef NDEBUG
    const std::uint64_t ticks = slow ? 12 : 120;
#else
    const std::uint64_t ticks = slow ? 3 : 40;
#endif
    World plain = World(scene.def);
    World tested = World(scene.def);
    SyncTest sync(tested, 7);
    for (std::uint64_t t = 0; t < ticks; ++t) {
      plain.step(scripted_input(t));
      ASSERT_TRUE(sync.step(scripted_input(t))) << "mismatch after tick " << sync.mismatch()->tick;
    }
    EXPECT_EQ(tested.state_hash(), plain.state_hash());
    std::uint64_t expected = 0;  // tick t re-simulates min(7, t + 1) ticks
    for (std::uint64_t t = 0; t < ticks; ++t) expected += std::min<std::uint64_t>(7, t + 1);
    EXPECT_EQ(sync.resimulated(), expected);
  }
}

TEST(SyncTest, ARuleAppliedOutsideTheRollbackIsCaught) {
  // A program that changes the world between ticks without the sync test seeing it (here:
  // moving a body) breaks re-simulation; the sync test reports the first tick it shows.
  World sim = World(load_scene(scenes_dir / "default.toml").def);
  SyncTest sync(sim, 4);
  for (std::uint64_t t = 0; t < 20; ++t) ASSERT_TRUE(sync.step(TickInput{.tick = t}));
  const Entity first = sim.bodies()[0];
  Body b = sim.body(first);
  b.position.x += 1e-9;
  sim.set_body(first, b);
  EXPECT_FALSE(sync.step(TickInput{.tick = 20}));
  ASSERT_TRUE(sync.mismatch());
  EXPECT_EQ(sync.mismatch()->tick, 21u);  // the first tick stepped from the changed state
  EXPECT_NE(sync.mismatch()->expected, sync.mismatch()->actual);
  EXPECT_THROW(SyncTest(sim, 0), std::invalid_argument);
}

// --- a stop request inside a tick --------------------------------------

TEST(StopRequest, AStopFromAnotherThreadInterruptsATickAndASnapshotStepsOn) {
  // The cloth (400 bodies, 1540 links) at 20 000 substeps: a tick of a few tenths of a second
  // that ran to its end, without throwing, before the substeps polled the request.
  Scene scene = load_scene(scenes_dir / "cloth.toml");
  scene.def.settings.substeps = 20000;
  World sim = World(scene.def);
  WorldSnapshot before;
  sim.save(before);
  clear_stop_request();
  std::atomic<bool> started{false};
  std::thread stopper([&] {
    while (!started.load()) std::this_thread::yield();
    request_stop(2);
  });
  started.store(true);
  try {
    sim.step(TickInput{.tick = 0});
    ADD_FAILURE() << "the tick ran to its end despite the stop request";
  } catch (const StopRequested& e) {
    EXPECT_EQ(e.signal(), 2);
  }
  stopper.join();
  EXPECT_EQ(sim.tick(), 0u);  // the torn tick is not counted
  clear_stop_request();
  // A fresh world from the snapshot taken before the torn tick steps on as if nothing happened.
  World fresh = World(scene.def);
  fresh.restore(before);
  fresh.step(TickInput{.tick = 0});
  World reference = World(scene.def);
  reference.step(TickInput{.tick = 0});
  EXPECT_EQ(fresh.tick(), 1u);
  EXPECT_EQ(fresh.state_hash(), reference.state_hash());
}

TEST(StopRequest, APendingStopStopsImplicitEulerAndTheStabilityGuard) {
  Scene scene = load_scene(scenes_dir / "cloth.toml");
  scene.def.settings.integrator = Integrator::implicit_euler;
  World sim = World(scene.def);
  request_stop(15);
  EXPECT_THROW(sim.step(TickInput{.tick = 0}), StopRequested);
  // The guard's power iteration (make_world checks the network) polls too.
  scene.def.settings.integrator = Integrator::semi_implicit_euler;
  EXPECT_THROW((void)World(scene.def), StopRequested);
  clear_stop_request();
  EXPECT_NO_THROW(sim.step(TickInput{.tick = 0}));  // the same world steps again once cleared
}

TEST(StopRequest, AStopScopeStopsItsThreadOnlyAndAnotherThreadStepsOn) {
  // A background load stopped by its owner while the owner steps its own world: only the
  // thread under the scope sees the flag.
  Scene scene = load_scene(scenes_dir / "cloth.toml");
  scene.def.settings.substeps = 20000;  // a tick of a few tenths of a second
  World background = World(scene.def);
  clear_stop_request();
  std::atomic<int> flag{0};
  std::atomic<bool> started{false};
  int stopped_with = 0;
  std::thread worker([&] {
    const StopScope scope(flag);
    started.store(true);
    try {
      background.step(TickInput{.tick = 0});
    } catch (const StopRequested& e) {
      stopped_with = e.signal();
    }
  });
  while (!started.load()) std::this_thread::yield();
  flag.store(7);
  Scene small = load_scene(scenes_dir / "cloth.toml");
  World foreground = World(small.def);
  EXPECT_NO_THROW(foreground.step(TickInput{.tick = 0}));  // this thread has no scope
  worker.join();
  EXPECT_EQ(stopped_with, 7);
  EXPECT_EQ(stop_requested(), 0);  // nothing process-wide was requested
}

TEST(StopRequest, GeneratorsOfManyBodiesReportProgressAndPollTheRequest) {
  // 300 x 300 bodies and 179 400 links: reports at every 65 536 of either, the last total the
  // scene's count; a pending stop throws before the grid is made.
  const std::string text =
      "[world]\ndt = 0.01\n[[grid]]\ncolumns = 300\nrows = 300\norigin = [0.0, 0.0]\n"
      "spacing = [0.1, -0.1]\nbody = { mass = 1.0 }\nlink = { stiffness = 10.0 }\n";
  std::vector<std::string> reports;
  {
    const WorkProgressScope scope(
        [&](std::string_view what, std::string_view unit, std::uint64_t done, std::uint64_t total) {
          reports.push_back(fmt::format("{}: {} {}/{}", what, unit, done, total));
        });
    (void)parse_scene(text, "grid.toml");
  }
  const std::vector<std::string> expected{"generating the scene: body 65536/90000",
                                          "generating the scene: link 65536/179400",
                                          "generating the scene: link 131072/179400"};
  EXPECT_EQ(reports, expected);
  std::atomic<int> flag{3};
  const StopScope scope(flag);
  EXPECT_THROW((void)parse_scene(text, "grid.toml"), StopRequested);
}

}  // namespace
}  // namespace fixstep
