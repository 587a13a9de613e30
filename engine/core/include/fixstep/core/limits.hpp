// The limits on the work and memory one world may ask for, in one place: a few bytes of scene
// or code must not buy hours of CPU per tick or an allocation that crashes. A program checks a
// definition before stepping it (check_world_limits: LimitError naming the claim, the limit and
// the way out); the caps a tick meets while stepping (candidate pairs, predictions) are recorded
// as a located StateFault instead. The limits of one command (ticks, total work) are
// fixstep::io's (command_limits.hpp).
//
// Work is counted in body-substeps: one body or one link advanced by one substep, what a tick of
// the fused per-body pass and the link gather cost. Implicit Euler on a linked world counts each
// body 64·√n times more for its sparse solve (n linked bodies; limits.cpp has the model). What a
// body-substep costs, and so what the limits mean in seconds: docs/ROBUSTNESS.md, "Limits on
// work and memory".
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

/// Most body-substeps in one tick ((bodies + links) × substeps; see tick_work): 10^9 (about 10 s of
/// CPU: docs/ROBUSTNESS.md). A tick may not take hours; one of seconds is still stopped within a
/// second by a stop request (stop_request.hpp), which the tick polls every substep.
inline constexpr std::uint64_t max_tick_work = 1'000'000'000;
/// Most memory implicit Euler's sparse factorisation (Eigen's SparseLU or SimplicialLDLT over
/// the bodies) may take, by implicit_solve_bytes' estimate: 2 GiB, about 230 000 bodies in a
/// grid of rest-length links.
inline constexpr std::uint64_t max_implicit_solve_bytes = std::uint64_t{2} << 30;

/// Most bodies implicit Euler may solve together (the bodies links join): 25 000. Its sparse
/// factorisation is one Eigen call a stop request cannot interrupt, and its time grows with the
/// network: this many keeps a stop within a second (measured: docs/ROBUSTNESS.md, "Stop
/// requests inside a tick"). Far inside max_implicit_solve_bytes (about 0.2 GiB at this size).
inline constexpr std::uint64_t max_implicit_bodies = 25'000;

/// Most candidate pairs (discs whose boxes swept over the tick, or over one of its windows,
/// overlap) the broadphase may find at once in a world of `discs` discs: max(64 n, 10^6), and
/// never more than n(n - 1)/2 (a settled pile has about 3 per disc; 64 per disc is a dense gas at
/// several radii per tick). Fast discs through a crowd are paired over up to 64 windows of the
/// tick, each disc's box covering its motion over one window (ContactStats::windows); a crowd
/// moving hundreds of radii a window (two grids at 10^5 m/s) still reaches it. Past it the tick's
/// disc contacts are not resolved: World::step records a StateFault naming this cap, the tick and
/// the disc with the largest swept box, and ContactStats::capped counts it.
[[nodiscard]] std::uint64_t max_candidate_pairs(std::uint64_t discs);
/// Most pairs of overlapping swept boxes the broadphase may drop in one tick of a world of
/// `discs` discs because they can never touch (linked discs, collision filters that keep them
/// apart): 16 max_candidate_pairs(discs), a bound on its work only (dropped pairs take no
/// memory and do not count against max_candidate_pairs). 2000 discs a filter keeps apart at one
/// point drop 2·10^6. Past it World::step records a StateFault naming this cap, the tick
/// and the disc with the largest swept box, and ContactStats::capped counts it.
[[nodiscard]] inline std::uint64_t max_vetoed_pairs(std::uint64_t discs) {
  return 16 * max_candidate_pairs(discs);
}
/// Most times of impact one tick of a world of `bodies` discs (or plane colliders) may predict
/// again after impacts: a disc pair's after an impact of either disc, and a body's plane tests
/// after its 8th plane event of the tick (one per plane). max(2^26, 256 n): a disc pair's
/// prediction (a quartic's roots) costs about 16 body-substeps, so 2^26 of them are about
/// max_tick_work, and a tick is polled for stop requests every 2^16. Piles and gases
/// stay far below it (docs/ROBUSTNESS.md, "No physics dropped by a cap"); a row of hundreds of
/// fast elastic discs driven into a peg, or a disc bouncing between two planes millions of
/// times a tick, reaches it. Past it World::step records a StateFault naming this cap, the
/// tick and the bodies of the impact it could not resolve, and ContactStats::capped counts it.
/// (A body coming to rest in a corner of two planes settles over ticks: that is not an impact
/// and is not counted.)
[[nodiscard]] constexpr std::uint64_t max_tick_predictions(std::uint64_t bodies) {
  return std::max<std::uint64_t>(std::uint64_t{1} << 26, 256 * bodies);
}

/// A claim beyond one of the limits above. what() names the claim, the limit and the way out.
class LimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Weight of one (dynamic collider, plane) pair in a tick, in body-substeps: the plane pass
/// tests each collider against every plane about three times a tick (push-out, the search for
/// the first impact, the end check) and more after each impact (world_contacts.cpp).
inline constexpr std::uint64_t plane_pair_work = 1;
/// Weight of one (dynamic collider, segment) pair in a tick, in body-substeps: the plane pass
/// queries the segment grid about three times a tick per collider and more after each impact,
/// and a query may return every segment (a disc's reach wider than the grid, a segment over
/// more than 64 cells, a segment a kinematic body carries); a segment test (closest feature and
/// time of impact) costs about 16 body-substeps (docs/ROBUSTNESS.md, "Limits on work and
/// memory"). A polyline of n points is n - 1 segments (n closed).
inline constexpr std::uint64_t segment_pair_work = 16;
/// Weight of one disc of a world with contacts in a tick, in body-substeps: its swept box in the
/// broadphase, its candidate pairs' times of impact, and the resting solver's sweeps over its
/// contacts (about three per disc in a pile; disc_contacts.hpp).
inline constexpr std::uint64_t disc_work = 128;

/// Body-substeps of one tick of the world of `bodies`, `links` (as in a WorldDef),
/// `planes` and `settings`, the sum of its terms:
///  - (bodies + links) × substeps (the fused per-body pass and the link gather);
///  - bodies × 64·√n × substeps for implicit Euler on a world with links (its sparse solve over
///    n linked bodies: limits.cpp has the model and its measurements);
///  - dynamic colliders × planes × plane_pair_work (the plane contacts, once a tick);
///  - dynamic colliders × segments × segment_pair_work (the segment contacts, once a tick);
///  - discs × disc_work when settings.contacts is set (every collider with collide = true),
///    times (velocity_iterations + position_iterations) / 30 when those are more than the
///    default 20 + 10 (rounded up).
/// At most ~10^17 (the scene limits), never overflowing.
[[nodiscard]] std::uint64_t tick_work(std::span<const BodyDef> bodies,
                                      std::span<const LinkDef> links,
                                      std::span<const PlaneDef> planes,
                                      const WorldSettings& settings,
                                      std::span<const SegmentDef> segments = {});
/// tick_work of def's world.
[[nodiscard]] std::uint64_t tick_work(const WorldDef& def);

/// An upper estimate of the bytes implicit Euler's factorisation of `def`'s linked bodies asks
/// for; 0 for another integrator or a world without links. Fitted to Eigen 3.4's SparseLU on
/// square grids of links (the worst shipped shape: fill-in grows as n^1.5 for n linked bodies),
/// measured as peak RSS (docs/ROBUSTNESS.md, "Limits"); a chain takes far less.
[[nodiscard]] std::uint64_t implicit_solve_bytes(std::span<const BodyDef> bodies,
                                                 std::span<const LinkDef> links,
                                                 const WorldSettings& settings);

/// Whether implicit Euler's solve of this world is within max_implicit_bodies and
/// max_implicit_solve_bytes (true for another integrator or a world without links).
[[nodiscard]] bool implicit_solve_within_limits(std::span<const BodyDef> bodies,
                                                std::span<const LinkDef> links,
                                                const WorldSettings& settings);

/// Throws LimitError when one tick of the world (with `segments`, a WorldDef's) would exceed
/// max_tick_work ("N bodies + M links × S substeps + ... = W body-substeps per tick; a tick may do
/// at most 1e+09 ...", each term of tick_work named) or its implicit solve max_implicit_bodies or
/// max_implicit_solve_bytes (naming the integrator, the linked body count, the estimate and the
/// way out: semi_implicit_euler with substeps). check_limits(def) calls it (definition_checks.hpp),
/// the scene loader too (locating the message at [world] substeps). Throws std::invalid_argument
/// for a link index out of range.
void check_world_limits(std::span<const BodyDef> bodies, std::span<const LinkDef> links,
                        std::span<const PlaneDef> planes, const WorldSettings& settings,
                        std::span<const SegmentDef> segments = {});

}  // namespace fixstep
