// The disc-contact benchmark (bench_discs.cpp): its two scenes, built once by one generator
// and stepped by fixstep (discs_fixstep.cpp), Chipmunk2D 7 (discs_chipmunk.cpp) and Box2D 2.4
// (discs_box2d.cpp) and, where its source archive is present, Box2D v3 (discs_box2d3.cpp) behind
// one interface; the overlap and energy measured on every engine's
// state the same way (discs_scene.cpp); the report (discs_report.cpp). Internal to bench/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fixstep/core/types.hpp"

namespace discs {

inline constexpr double tick = 1.0 / 60.0;    ///< s, every engine's step
inline constexpr double small_radius = 0.05;  ///< m, every disc of the pile and the gas
/// m, every disc of the large pile: the peers' home scale (Box2D's manual: moving objects of
/// 0.1 to 10 m; its b2_linearSlop, 5 mm, is 10 % of the small radius and 1 % of this one).
inline constexpr double large_radius = 0.5;
inline constexpr double mass = 1.0;  ///< kg, every disc

// The pile: N discs packed hexagonally `pile_layers` rows deep in a box that fits the rows
// exactly (even rows wall to wall, odd rows one disc fewer in their pockets; the top row
// partly filled; every gap 0.1 % of the diameter, so nothing overlaps at tick 0): ground y = 0
// and walls x = 0 and x = width, under gravity, e = 0, μ = 0.5 (disc-disc and disc-wall). It
// is warmed up for `pile_warmup` ticks, untimed, then timed: its discs are then nearly at rest,
// but fixstep's resting solver still needs more iterations a tick than it will once the pile
// has settled. `pile_settled` is the same pile timed after `pile_settled_warmup` ticks (N <=
// 10⁴ only: the warm-up of 10⁵ discs would take minutes per engine), when every engine's cost
// a tick has stopped falling. The depth is the same at every N, so the work per disc is too.
inline constexpr int pile_layers = 10;
inline constexpr double pile_gravity = 9.81;  ///< m/s², along -y
inline constexpr double pile_restitution = 0.0;
inline constexpr double pile_friction = 0.5;
inline constexpr int pile_warmup = 40;
inline constexpr int pile_settled_warmup = 360;
// The gas: N discs in a closed square box at 10 % area fraction, no gravity, e = 1, μ = 0,
// each at a random spot of its own cell of a square grid (so nothing overlaps at tick 0) with
// a speed uniform in [1, 3] m/s in a uniform random direction. Warmed up for `gas_warmup` ticks.
inline constexpr double gas_area_fraction = 0.1;
inline constexpr double gas_restitution = 1.0;
inline constexpr double gas_friction = 0.0;
inline constexpr double gas_speed_min = 1.0, gas_speed_max = 3.0;  ///< m/s
inline constexpr int gas_warmup = 5;

/// pile_large: the pile with discs of large_radius (N = 10³ and 10⁴ only); pile_settled: the
/// pile timed after pile_settled_warmup ticks (N = 10³ and 10⁴ only); pile_ball: the settled
/// pile and one more disc, a ball without gravity flying level above it (timed with sleeping
/// islands only: the pile asleep and the ball awake, so the cost of a world mostly asleep).
enum class SceneKind { pile, gas, pile_large, pile_settled, pile_ball };
[[nodiscard]] const char* scene_name(SceneKind s);

/// One scene as every engine builds it: discs of `radius` and `mass` in a box whose walls are
/// the lines x = 0, x = width, y = 0 and (gas only) y = height; free space inside.
struct Scene {
  SceneKind kind = SceneKind::pile;
  double radius = small_radius;           ///< m, every disc
  std::vector<fixstep::Vec2> position{};  ///< m, disc centres
  std::vector<fixstep::Vec2> velocity{};  ///< m/s
  double width = 0.0, height = 0.0;       ///< m, the box (pile: height of the walls drawn)
  bool lid = false;                       ///< a wall at y = height (the gas)
  double gravity = 0.0;                   ///< m/s² along -y
  double restitution = 0.0, friction = 0.0;
  int warmup = 0;  ///< ticks stepped before timing
  /// The last disc is a ball that no gravity acts on (pile_ball), else every disc falls.
  bool ball = false;
};
/// The ball of pile_ball: its height above the pile's top and its speed along +x (m, m/s).
/// It starts above the pile's first quarter and stays within the walls for 10 s.
inline constexpr double ball_height = 1.0, ball_speed = 0.2;

[[nodiscard]] Scene make_pile(std::size_t n, double radius = small_radius);
[[nodiscard]] Scene make_gas(std::size_t n, std::uint64_t seed = 19);
[[nodiscard]] Scene make_scene(SceneKind kind, std::size_t n);

/// What one engine's discs look like, measured the same way for every engine.
struct Quality {
  double disc_overlap = 0.0;  ///< deepest 2r - |x_a - x_b| over all pairs, m (>= 0)
  double wall_overlap = 0.0;  ///< deepest r - distance to a wall over discs, m (>= 0)
  double kinetic = 0.0;       ///< ½ m |v|² summed, J (translation only)
};
/// Overlaps by a uniform grid of cell 2r (each disc against its 3 x 3 cells): O(N log N).
[[nodiscard]] Quality measure(const Scene& s, std::span<const fixstep::Vec2> x,
                              std::span<const fixstep::Vec2> v);
/// The deepest disc-disc overlap by testing all pairs (the grid's check), m.
[[nodiscard]] double overlap_brute_force(std::span<const fixstep::Vec2> x, double radius);
/// Translational kinetic energy of the scene's initial state, J.
[[nodiscard]] double initial_kinetic(const Scene& s);

/// What an engine reports about its own contacts, NaN where it reports nothing.
struct Stats {
  double candidate_pairs = 0.0;   ///< fixstep: broadphase pairs in the last tick
  double touching = 0.0;          ///< fixstep: pairs touching at the end of the last tick
  double impacts = 0.0;           ///< fixstep: impacts resolved in the last tick
  double self_overlap = 0.0;      ///< fixstep: its own deepest overlap left, m
  double broadphase_share = 0.0;  ///< Box2D: b2Profile broadphase / step since the start
  double collide_share = 0.0;     ///< Box2D: b2Profile collide (narrow phase) / step
  int threads = 1;
  /// fixstep: the resting solver's velocity and position iterations in the last tick
  /// (ContactStats::velocity_sweeps, position_sweeps).
  int velocity_sweeps = 0, position_sweeps = 0;
  /// fixstep: the last tick's time by phase (World::profile()), s: broadphase, impacts,
  /// resting solver, and the rest of the tick (integration and events).
  double broadphase_s = 0.0, impacts_s = 0.0, resting_s = 0.0, other_s = 0.0;
};

/// An engine stepping a scene at `tick`: fixstep, Chipmunk2D or Box2D.
class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual void step() = 0;
  /// Positions and velocities of the discs, in scene order.
  virtual void state(std::vector<fixstep::Vec2>& x, std::vector<fixstep::Vec2>& v) const = 0;
  [[nodiscard]] virtual Stats stats() const = 0;
};

// The steppers, by key:
// - fixstep_f64_t1, fixstep_f64_t2, fixstep_f32_t1: fixstep::detail::WorldKernel<Real> with
//   WorldSettings::contacts;
// - fixstep_f64_off: the same world without contacts (discs meet only the walls);
// - fixstep_roll_t1, fixstep_roll_t2: f64 with rolling discs (the pile only), as the peers'
//   rotating circles;
// - fixstep_sleep_t1, fixstep_sleep_t2: f64 with sleeping islands (ContactSettings::sleep at
//   its defaults; the settled pile only, where it sleeps);
// - chipmunk_hash: cpSpace with cpSpaceUseSpatialHash(2r, N);
// - chipmunk_tree: cpSpace with its default bounding-box tree;
// - chipmunk_hasty2: cpHastySpace on 2 threads (its default tree);
// - box2d: Box2D 2.4's b2World, b2CircleShape, Step(dt, 8, 3);
// - box2d3_w1, box2d3_w2: Box2D v3.1.1's b2World_Step(dt, 4) on 1 and 2 workers (where built);
// - box2d32_w1, box2d32_w2: Box2D v3.2's, the same (where built);
// - box2d32_sleep_w1, box2d32_sleep_w2: Box2D v3.2 with its sleeping on (the settled pile only).
/// The keys of the steppers this build has (Box2D v3's only where box2d3_built()).
[[nodiscard]] std::span<const char* const> stepper_keys();
[[nodiscard]] std::string stepper_label(const std::string& key);
[[nodiscard]] std::unique_ptr<Stepper> make_stepper(const std::string& key, const Scene& s);

/// fixstep on the scene; box2d_iterations: the resting solver at Box2D 2.4's iteration counts
/// (box2d_velocity_iterations, box2d_position_iterations) instead of its defaults; rolling:
/// rolling discs (ContactSettings::rolling; uniform discs, I = ½ m r²), as the peers' circles,
/// which rotate; sleep: sleeping islands (ContactSettings::sleep, its default speed and time).
[[nodiscard]] std::unique_ptr<Stepper> make_fixstep(const Scene& s, bool f32, int threads,
                                                    bool contacts, bool box2d_iterations = false,
                                                    bool rolling = false, bool sleep = false);
enum class ChipmunkIndex { hash, tree, hasty };
[[nodiscard]] std::unique_ptr<Stepper> make_chipmunk(const Scene& s, ChipmunkIndex index);
[[nodiscard]] std::string chipmunk_version();
inline constexpr int chipmunk_iterations = 10;  ///< its default
/// Chipmunk's collision slop set to Box2D's b2_linearSlop (its default, 0.1, is in pixels).
inline constexpr double chipmunk_slop = 0.005;  ///< m
[[nodiscard]] std::unique_ptr<Stepper> make_box2d(const Scene& s);
[[nodiscard]] std::string box2d_version();
[[nodiscard]] double box2d_linear_slop();  ///< m
inline constexpr int box2d_velocity_iterations = 8;
inline constexpr int box2d_position_iterations = 3;
/// The Box2D v3 releases bench/box2d3.cmake builds where their source archives are present:
/// v3.1.1 (the newest release) and v3.2 (Box2D's main branch of 2026-08-20, which reports
/// 3.2.0). Both are compiled from discs_box2d3.cpp and boxes_box2d3.cpp, once per release.
enum class Box2d3Release { v3_1, v3_2 };
inline constexpr Box2d3Release box2d3_releases[] = {Box2d3Release::v3_1, Box2d3Release::v3_2};
/// Whether the release was built (false otherwise: its steppers are absent and its checks
/// skipped; box2d3_peers.cpp).
[[nodiscard]] bool box2d3_built(Box2d3Release r = Box2d3Release::v3_1);
/// Box2D v3 on `workers` threads: 1, its own serial task functions; 2, for v3.1 Box2d3Tasks
/// (discs_box2d3_tasks.hpp), for v3.2 its own scheduler (b2WorldDef::workerCount = 2 without
/// task callbacks: it runs a thread of its own).
/// sleep: Box2D's sleeping islands on (b2WorldDef::enableSleep at its defaults), for the
/// asleep settled pile.
[[nodiscard]] std::unique_ptr<Stepper> make_box2d3(const Scene& s, int workers,
                                                   Box2d3Release r = Box2d3Release::v3_1,
                                                   bool sleep = false);
/// "3.1.1", "3.2.0" (b2GetVersion), or "3.1.1 (not built)" or "3.2 (not built)".
[[nodiscard]] std::string box2d3_version(Box2d3Release r = Box2d3Release::v3_1);
[[nodiscard]] double box2d3_linear_slop(Box2d3Release r = Box2d3Release::v3_1);  ///< m
inline constexpr int box2d3_substeps = 4;  ///< b2World_Step's subStepCount: v3's default
/// A release's stepper key prefix: "box2d3" (v3.1) and "box2d32" (v3.2), then _w1 or _w2.
[[nodiscard]] const char* box2d3_key(Box2d3Release r);
/// The keys of a shapes or joints benchmark's steppers: fixstep on 1 and 2 threads
/// ("fixstep_t1", "fixstep_t2"), then each built Box2D v3 release on 1 and 2 workers.
[[nodiscard]] std::vector<std::string> shape_stepper_keys();
/// "fixstep f64, 1 thread", "Box2D 3.2.0 (f32), 2 workers", ... for one of those keys (the key
/// itself for another).
[[nodiscard]] std::string shape_stepper_label(const std::string& key);

/// A disc dropped from rest onto the ground by the stepper `key`: falls ½ g t² and rests at
/// y = r within tolerances (discs_checks.cpp); what failed, empty if nothing.
[[nodiscard]] std::vector<std::string> check_drop(const std::string& key);

// --- results and the report (discs_report.cpp) --------------------------------------------

/// One timed case: "<scene>/<stepper>/<N>".
struct CaseResult {
  double ns_per_body_step = 0.0;  ///< median real time of a step / discs
  double bodies = 0.0;
  double ticks = 0.0;          ///< ticks stepped when the quality was measured (warm-up included)
  double disc_overlap = 0.0;   ///< / r, after the timed steps
  double wall_overlap = 0.0;   ///< / r
  double kinetic_ratio = 0.0;  ///< kinetic energy then / at tick 0 (gas); rms speed, m/s (pile)
  Stats stats{};               ///< self_overlap here as a fraction of r
};

/// fixstep f64's cost per disc at N = 10³ and 10⁵ on one thread, the two sizes timed in turn
/// in each round (discs_scaling.cpp): the groups of the main run (every 10³ case, then every
/// 10⁴, then every 10⁵) lie minutes apart, and a shared machine's speed drifts between them.
inline constexpr std::size_t scaling_small = 1000, scaling_large = 100'000;
/// Worlds of 10³ stepped in a round, one after another, each through the round's ticks: a round
/// of one lasts about a millisecond, a round of 10⁵ a few hundred.
inline constexpr int scaling_copies = 20;
/// Sets of those worlds, each built afresh and stepped through the same ticks: more rounds
/// than one world's window holds.
inline constexpr int scaling_sets = 3;
struct Scaling {
  std::vector<double> small{}, large{};  ///< ns per body-step, by round
  /// The median over the rounds of large / small; NaN without rounds.
  [[nodiscard]] double ratio() const;
};
/// For each of scaling_sets sets: builds `kind`'s worlds (scaling_copies of 10³, one of 10⁵)
/// and warms them up as the main run does, then times `rounds` rounds of `ticks_per_round` ticks of
/// each size, in turn (which goes first alternates), each round after a buffer of 256 MiB was
/// written untimed so that both sizes start from memory; a line of progress per round on stderr.
[[nodiscard]] Scaling scaling(SceneKind kind, int rounds, int ticks_per_round);

struct Results {
  std::map<std::string, CaseResult> cases{};
  std::map<SceneKind, Scaling> scaling{};  ///< by scene; empty when not run
  std::vector<std::int64_t> sizes{};
  int repetitions = 1, repetitions_largest = 1;
  double load_start = 0.0, load_end = 0.0;  ///< 1-minute load average
  /// A cache line's round trip between the first two CPUs (core_round_trip_ns()), ns; NaN
  /// where not measured.
  double round_trip_start = std::numeric_limits<double>::quiet_NaN(),
         round_trip_end = std::numeric_limits<double>::quiet_NaN();
};

[[nodiscard]] std::string report_markdown(const Results& r);
/// Its targets section: the targets as measured ratios, met or not.
[[nodiscard]] std::string targets_markdown(const Results& r);

}  // namespace discs
