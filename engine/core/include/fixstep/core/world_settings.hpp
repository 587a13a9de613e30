// A world's settings: the step length dt (s), the integrator, substeps, threads, contacts and
// the determinism switches; set when a world is made, the same for every body in it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "fixstep/core/components.hpp"
#include "fixstep/core/integrators.hpp"

namespace fixstep {

/// Where velocity Verlet and Forest–Ruth apply the damping of a network's links: each link's
/// exact damping flow, swept over the links by colours before (C↑) and after (C↓) a drift
/// (link_damping.hpp, docs/INTEGRATORS.md). Verlet has one stage per step: both choices give
/// the same step. Other integrators and networks without damped links ignore it.
enum class DampingSplit {
  /// Around every stage's drift: Forest–Ruth keeps order 4 with damped links, at 6 sweeps
  /// over the links per step (about 5x semi-implicit Euler's tick on a cloth). The default:
  /// order 4 is why one picks Forest–Ruth.
  per_stage,
  /// Once around each Forest–Ruth step, C↑(h/2) FR(h) C↓(h/2): 2 sweeps per step (about 3.5x
  /// semi-implicit Euler's tick), order 4 on the springs but 2 in the link damping (measured
  /// on the damped chain: tests/core/test_coupled.cpp). Without damped links, the same bits as
  /// per_stage.
  per_step,
};

/// "per_stage" / "per_step".
[[nodiscard]] std::string_view damping_split_name(DampingSplit split);
/// The DampingSplit named `name`, or nullopt.
[[nodiscard]] std::optional<DampingSplit> parse_damping_split(std::string_view name);

/// How a world seeds its random generator (World::random()) from WorldSettings::seed.
enum class Seeding : std::uint8_t {
  /// Random(seed): the seed through SplitMix64's mix, then PCG32 (random.hpp). Every seed bit
  /// matters. The default, and every recording of format version 5 or later.
  splitmix,
  /// Random::pcg32(seed, 0): the seed added to PCG32's state unmixed, so that seeds differing
  /// only in their top bits give rotated streams. For replaying recordings of format version 4
  /// and older, made with it; a recording made with it is written as version 4 (3 without
  /// rules). Seed 0 gives the same generator both ways.
  pcg32_srandom,
};

/// World-wide simulation settings.
struct WorldSettings {
  double dt = 1.0 / 60.0;  ///< fixed physics step (one tick), s; finite and > 0
  Integrator integrator = Integrator::semi_implicit_euler;
  /// Integration steps per tick, each of dt / substeps (>= 1). A tick is still dt.
  int substeps = 1;
  /// Keep a decaying state out of the subnormal numbers, in software, the same bits on every
  /// platform (no FTZ/DAZ: World::step runs in the IEEE default FPU mode whatever the caller
  /// set). A strongly damped state decays towards zero, and long before the state itself is
  /// subnormal the tick's intermediates are (products such as γ v dt, squares in the energy
  /// account); on CPUs where such an operation takes a microcode assist (Intel's) a tick then
  /// costs many times a normal one. With this on, at the end of every tick whose number is a
  /// multiple of flush_denormals_every (64):
  ///  - in a world with damping (a body's damper or drag, a damped link) every x, y, vx, vy
  ///    whose magnitude is below 2^8 √(least normal) (2^-55 ≈ 2.8e-17 in f32, 2^-503 ≈
  ///    3.8e-152 in f64) becomes a zero of its sign: what is left, its sums (at least 2^-24 of
  ///    it unless 0) and what 64 ticks of damping leave of it keep every product with the
  ///    tick's coefficients normal while the damping takes less than 2^27 in 64 ticks (γ dt
  ///    below about 0.29) and the coefficients (dt, k dt/m, γ dt) are above 2^-20;
  ///  - in any other world every subnormal x, y, vx, vy (0 < |v| < the least normal: 1.2e-38
  ///    f32, 2.2e-308 f64) becomes a zero of its sign.
  /// The dissipation account squares a velocity component below 2^-55 (f32) as 0, and implicit
  /// Euler writes a value below it back as 0, in every tick. Off: gradual underflow throughout
  /// (the same bits everywhere too, slower on such CPUs).
  bool flush_denormals = true;
  /// Keep account of the energy dissipated by damping and drag (dissipated_energy()), so that
  /// the energy balance E + E_dissipated - E0 measures the integrator alone. Off by default:
  /// a world without links then steps in today's fused pass; with it on (fixstep's CLI and
  /// sessions) a damped world steps in the multi-pass path, which computes the same states
  /// bit for bit and adds each tick's dissipation (see World::dissipated_energy).
  bool track_dissipation = false;
  /// Threads a tick of a world with links, disc contacts, shapes or joints may use: 1, 2, or 0 =
  /// automatic (2 when the machine has a second core, and for links the world has at least
  /// parallel_min_bodies bodies; for disc contacts from 256 awake discs, and for shapes and
  /// joints from 256 shapes or joints, whichever of 1 and 2 stepped that phase faster in the
  /// last trial: every few seconds the world times the phase on each, alternately, for a few
  /// ticks, since what a second core saves depends on the machine and on whether its ticks
  /// run back to back or paced by frames). On two,
  /// disc contacts share their passes from 256 awake discs and run a tick's impacts in two
  /// lanes of the candidate pairs' groups from 128 pairs, shapes from 1024 shapes or a sweep's
  /// colour of 256 manifolds, joints from 256 joints in two groups that share no body. The states
  /// are bit-identical for every thread count: each body gathers its link forces in a fixed order,
  /// the passes split into halves whose items are independent (docs/JOINTS.md: joints that share a
  /// body stay together; two impact lanes whose discs' paths would meet run the tick's impacts
  /// again in one), and no float is ever added atomically. Always 1 in a wasm32 build without
  /// pthreads (emscripten's default), which cannot start a thread.
  int threads = 0;
  /// Where velocity Verlet and Forest–Ruth apply damped links' flows (see DampingSplit).
  DampingSplit damping_split = DampingSplit::per_stage;
  /// Body-vs-body contacts of discs (world_discs.cpp); unset (the default): none are computed
  /// and the world pays nothing for them. Contacts with planes need no setting.
  std::optional<ContactSettings> contacts = std::nullopt;
  /// Seed of the world's random generator for game rules (World::random(); any value). Part
  /// of the definition hash only when not 0, so worlds that never set it hash as before.
  std::uint64_t seed = 0;
  /// How `seed` seeds the generator (Seeding). Part of the definition hash only for a seed
  /// other than 0 seeded by splitmix, so a world replaying an older recording
  /// (pcg32_srandom) hashes as it did when it was recorded.
  Seeding seeding = Seeding::splitmix;
};

/// Ticks between two software flushes of subnormal state (WorldSettings::flush_denormals).
inline constexpr std::uint64_t flush_denormals_every = 64;

/// Bodies from which an automatic (threads = 0) world with links steps on two threads.
inline constexpr std::size_t parallel_min_bodies = 16384;

/// Bits of World::active_terms(): which force terms run each tick.
enum ForceTermBits : unsigned {
  term_spring = 1u << 0,
  term_constant_force = 1u << 1,
  term_gravity = 1u << 2,
  term_drag = 1u << 3,
  term_link = 1u << 4,  ///< springs between bodies: the gather over the link list runs
};

}  // namespace fixstep
