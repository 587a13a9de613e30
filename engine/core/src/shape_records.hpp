// The shape world's records (shape_world.hpp has the tick that uses them): a shaped body, a
// shape, a body's pose and velocity through the tick, a manifold point's row and its velocity
// row, the impulses kept for warm starting, what a tick reads of the world and what it reports.
// Internal to the engine: not installed.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "fixstep/core/collision_filter.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/pre_solve.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "shape_geom.hpp"

namespace fixstep::detail {

struct JointRecord;
class SecondThread;
class SegmentSet;

/// Most shapes one body may carry.
inline constexpr std::size_t max_shapes_per_body = 64;

/// A body with shapes (or a disc meeting them): its kernel index, mass properties and shapes.
struct ShapedBody {
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  std::uint32_t body = 0;    ///< dense index in the kernel
  std::uint32_t set = none;  ///< its ShapeSet in the kernel's store (none: a disc)
  BodyType type = BodyType::dynamic;
  bool disc = false;  ///< a disc (Collider): its contacts with discs are the disc phase's
  /// A dynamic body asleep this tick (ContactSettings::sleep): solved as a static one (its
  /// inverse mass and inertia 0) unless a moving body pairs with it, which wakes its island.
  bool asleep = false;
  double inv_mass = 0.0, inv_inertia = 0.0;  ///< 1/kg, 1/(kg·m²); 0 for static and kinematic
  std::uint32_t first = 0, count = 0;        ///< its shapes in ShapeWorld::shapes_
  double extent = 0.0;                       ///< m, the farthest point from its centre
  double thinnest = 0.0;  ///< m, the least distance from its centre to a face of a shape
};

/// One shape in the kernel's form.
struct ShapeEntry {
  Convex convex;
  std::uint32_t owner = 0;  ///< index into ShapeWorld::bodies_
  double friction = 0.0, restitution = 0.0;
  double rolling = 0.0;  ///< ShapeDef::rolling_resistance
  CollisionFilter filter{};
  bool sensor = false;
  std::uint32_t key = 0;  ///< (entity slot << 6) | shape index: stable across rebuilds
  bool one_way = false;   ///< ShapeDef::one_way
  Vec2 up{0.0, 1.0};      ///< a one-way shape's up in its body's frame (its frame's +y)
};

/// The start and running state of one shaped body in a tick (double; the kernel's Real state
/// is read in and written back).
struct ShapeState {
  double x0 = 0, y0 = 0, a0 = 0;  ///< start of the tick (m, m, rad)
  double x = 0, y = 0, a = 0;     ///< now
  double vx = 0, vy = 0, w = 0;   ///< m/s, rad/s
  Rot q{}, q0{}, turn{};          ///< of a, a0, a − a0
};

/// One manifold point's solver row. ShapeWorld::add_manifold gives every field in this order
/// (parenthesized aggregate initialization): a field moved or added here is moved or added there.
struct ShapeRow {
  std::uint32_t a = 0, b = 0;  ///< bodies_ indices (a may be `none`: a plane or segment)
  Vec2 n{}, ra{}, rb{};        ///< normal A→B, lever arms (m)
  double separation = 0.0;     ///< m, at the manifold's poses
  double friction = 0.0, restitution = 0.0;  ///< μ, e of the pair
  double approach = 0.0;                     ///< the closing speed before the solve, m/s (>= 0)
  double ln = 0.0, lt = 0.0;                 ///< accumulated impulses (N·s)
  /// Rolling resistance (on a manifold's first row only): c · r (m), the bound of the angular
  /// impulse per unit of the manifold's normal impulse; its effective mass 1/(1/I_a + 1/I_b);
  /// the accumulated angular impulse (N·m·s, on B; −lr on A).
  double rolling = 0.0, rolling_mass = 0.0, lr = 0.0;
  double bn = 0.0, bt = 0.0;  ///< the impact pass's impulses (N·s): its bounces, apart from ln
  std::uint64_t pair = 0;     ///< the two shapes' keys, for warm starting
  std::uint32_t id = 0;       ///< the manifold point's feature id
};

/// A manifold point's row as the velocity solve reads it (made from its ShapeRow by
/// ShapeWorld::prepare_rows; its impulses are copied back after the sweeps): the normal n, the
/// lever arms' moments r × n and r × t about each body's centre (t = perp(n), so that a point's
/// relative normal velocity is (v_B − v_A)·n + ω_B (r_B × n) − ω_A (r_A × n)), and each body's
/// inverse mass and inertia (0 for a plane or segment A), so that a sweep reads no more than
/// the row and the two bodies' velocities.
struct ShapeSolveRow {
  /// flags:
  /// - block_first: the first of a manifold's two points, whose normal impulses are solved
  ///   together (Box2D v2.4's block solver): K = [[kn, k12], [k12, kn of the next]];
  /// - redundant: a point whose row all but repeats its partner's (K near singular: the two
  ///   points nearly coincide as constraints), left out of the velocity solve, which the
  ///   partner (the deeper) does alone, as Box2D v2.4 keeps one point of such a manifold;
  ///   solving both one after the other converges slowly here and leaves an elastic bounce
  ///   unfinished;
  /// - rolls: the manifold's first row, with rolling resistance (ShapeRow::rolling_mass > 0);
  ///   rolls_pair: and the manifold has a second row.
  static constexpr std::uint8_t block_first = 1, redundant = 2, rolls = 4, rolls_pair = 8;
  std::uint32_t a = 0, b = 0;  ///< bodies_ indices (a may be ShapeWorld::none)
  std::uint8_t flags = 0;
  double nx = 0.0, ny = 0.0;
  double rna = 0.0, rnb = 0.0, rta = 0.0, rtb = 0.0;  ///< m: r_A × n, r_B × n, r_A × t, r_B × t
  double ma = 0.0, ia = 0.0, mb = 0.0, ib = 0.0;      ///< 1/kg, 1/(kg·m²)
  double kn = 0.0;                                    ///< 1/kg: the normal row's K (1/normal_mass)
  double kt = 0.0;                                    ///< 1/kg: the tangent row's K
  double normal_mass = 0.0, tangent_mass = 0.0;
  double k12 = 0.0;     ///< a block's coupling, 1/kg
  double target = 0.0;  ///< the normal velocity the row asks for, m/s
  /// A block's K⁻¹ (kg), on its first row: [[m11, m12], [m12, m22]] as {m11, m12, m22}.
  std::array<double, 3> block_mass{};
  double friction = 0.0;
  double ln = 0.0, lt = 0.0;  ///< accumulated impulses (N·s)
};

/// The impulses a manifold point carried last tick, by key.
struct ShapeWarm {
  std::uint64_t pair = 0;
  std::uint32_t id = 0;
  double ln = 0.0, lt = 0.0, lr = 0.0;
  friend bool operator<(const ShapeWarm& l, const ShapeWarm& r) {
    return l.pair != r.pair ? l.pair < r.pair : l.id < r.id;
  }
};

/// Everything the solver reads of the world for one tick.
struct ShapeTick {
  double dt = 0.0, kappa = 1.0;
  double friction = 0.0, restitution = 0.0;  ///< ContactSettings defaults
  double restitution_threshold = 1.0;        ///< m/s, ContactSettings::restitution_threshold
  int velocity_iterations = 8, position_iterations = 3;
  std::span<const PlaneDef> planes;
  std::span<const SegmentDef> segments;
  /// The same segments with their grid (SegmentSet::query), so that a shape meets only those
  /// near it; set whenever `segments` is not empty.
  const SegmentSet* segment_grid = nullptr;
  /// With sleeping bodies: called once the broadphase paired a sleeper with a moving body
  /// (ShapeWorld::woken()); it wakes their islands and clears their `asleep` (and sets their
  /// masses back), and the broadphase runs again.
  void (*wake)(void* context) = nullptr;
  void* wake_context = nullptr;
  /// The joints (joint_solver.hpp), solved with the contacts: warm-started after them, each
  /// velocity sweep before theirs, each position sweep after theirs. Broken ones are left out.
  std::span<JointRecord> joints;
  /// Pairs of bodies (bodies_ indices, lower << 32 | higher, sorted) whose shapes do not
  /// collide: the two ends of a joint without JointDef::collide_connected; and by body a, the
  /// first pair whose lower end is a or after (a body past its end is in none).
  std::span<const std::uint64_t> unpaired;
  std::span<const std::uint32_t> unpaired_start;
  /// Threads the shape phase may use (World's threads, 1 or 2): with 2, a world of
  /// min_split_shapes shapes or more makes its broadphase and manifolds by halves, and a colour
  /// of the velocity sweeps with many manifolds is solved by halves (its manifolds move no body
  /// in common): the same bits as one thread. On `thread` when given (the discs' second
  /// thread, whose run is open through the shape phase), else on the shape world's own.
  int threads = 1;
  SecondThread* thread = nullptr;
  /// The pre-solve hook (World::set_pre_solve; null: none) and its context, and each body's
  /// handle by dense index (the kernel's), for the contacts it is shown.
  PreSolveFn pre_solve = nullptr;
  void* pre_solve_context = nullptr;
  std::span<const Entity> entities;
};

/// What one tick's shape contacts did, for the statistics and the energy account.
struct ShapeTally {
  std::size_t pairs = 0, points = 0, ccd_hits = 0;
  double deepest = 0.0;     ///< m, the deepest overlap left after the solve
  int velocity_sweeps = 0;  ///< the velocity sweeps the solve ran (ShapeWorld::solve_velocities)
  /// A work limit the broadphase reached (its name in limits.hpp), its value and the body
  /// (bodies_ index) with the widest box; the tick's shape contacts were not solved.
  const char* cap = nullptr;
  std::uint64_t limit = 0;
  std::uint32_t cap_body = 0;
};

}  // namespace fixstep::detail
