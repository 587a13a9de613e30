// The world a program holds (World), made from a WorldDef: everything a world is built from,
// whether written in code or read from a scene file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "fixstep/core/entity.hpp"
#include "fixstep/core/pre_solve.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

// The types of World's interface, declared here and defined in the headers named: include
// those (or fixstep/core.hpp, all of core) to use what a call takes or returns.
struct WorldDef;                     // world_def.hpp
struct WorldSettings;                // world_settings.hpp
struct Body;                         // components.hpp
struct BodyDef;                      // components.hpp
struct LinkDef;                      // components.hpp
struct PlaneDef;                     // components.hpp
enum class BodyType : std::uint8_t;  // components.hpp
struct SegmentDef;                   // segment.hpp
struct ShapeDef;                     // shape.hpp
struct JointDef;                     // joint.hpp
struct JointState;                   // joint.hpp
struct JointBreak;                   // joint.hpp
struct MoverState;                   // mover.hpp
struct TickInput;                    // input.hpp
struct BodyInput;                    // input.hpp
struct EnergyReport;                 // step_results.hpp
struct ContactStats;                 // step_results.hpp
struct StepProfile;                  // step_results.hpp
struct Impact;                       // step_results.hpp
struct ContactEvent;                 // step_results.hpp
struct SensorEvent;                  // step_results.hpp
struct StateFault;                   // step_results.hpp
struct QueryFilter;                  // query.hpp
struct QueryHit;                     // query.hpp
struct RayHit;                       // query.hpp
class Random;                        // random.hpp
struct StabilityFinding;             // definition_checks.hpp
struct StateFields;                  // state_difference.hpp

namespace detail {
struct WorldState;     // the kernel behind a World (engine/core/src/world_state.hpp)
struct SnapshotState;  // a saved kernel (engine/core/src/world_state.hpp)
}  // namespace detail

/// A restorable state of a World (what game physics calls a snapshot): a complete copy of
/// its world, taken by World::save and put back by World::restore, bit for bit.
/// Memory: about the world's own (every per-body and per-link array).
class WorldSnapshot {
 public:
  WorldSnapshot();
  WorldSnapshot(const WorldSnapshot& other);
  WorldSnapshot& operator=(const WorldSnapshot& other);
  WorldSnapshot(WorldSnapshot&& other) noexcept;
  WorldSnapshot& operator=(WorldSnapshot&& other) noexcept;
  ~WorldSnapshot();
  /// True until something is saved into it.
  [[nodiscard]] bool empty() const { return !state_; }
  /// The tick of the saved state; 0 when empty.
  [[nodiscard]] std::uint64_t tick() const;

 private:
  friend class World;
  std::unique_ptr<detail::SnapshotState> state_;
};

/// The one object a program holds: bodies, their components, links and planes, stepped at a
/// fixed dt in the precision chosen at creation (f32 or f64). Its state lives behind a pointer
/// (the kernel, its arrays structure-of-arrays, is not part of the interface); a World copies
/// deeply (a copy steps on to the same bits) and moves cheaply. A moved-from World may only be
/// assigned to or destroyed.
class World {
 public:
  World(const World& other);
  World& operator=(const World& other);
  World(World&& other) noexcept;
  World& operator=(World&& other) noexcept;
  ~World();

  /// The one way to make a world, checked (definition_checks.hpp): the work limits first,
  /// before anything is allocated for the bodies; then a World with def.precision and
  /// def.settings and the bodies in order, the links, the planes and the segments, each
  /// validated; then the overlap of discs at tick 0 and the stability guard. The guard's findings
  /// that did not refuse the definition (near the bound, or unstable with def.allow_unstable) are
  /// kept in warnings(). Throws UnstableDefinition (a std::invalid_argument) for an unstable body
  /// or network unless def.allow_unstable, std::invalid_argument for discs overlapping at tick 0
  /// (naming both) and for invalid settings, bodies, links, planes or segments (the message names
  /// the body and field; for a plane, plane[i]; for a segment, segment[i]; for a link whose end is
  /// not one of def's bodies, link[i]), LimitError (limits.hpp) when a tick would exceed the work
  /// limits, and StopRequested (stop_request.hpp) when a stop is requested while the guard
  /// iterates.
  explicit World(const WorldDef& def);

  /// The precision the world steps in (WorldDef::precision).
  [[nodiscard]] Precision precision() const;
  // Bodies and links are named by handles (Entity, Link), which stay valid until destroyed;
  // bodies() lists the live ones in the order the world steps them.

  // --- bodies by handle -----------------------------------------------------------------
  Entity create_body(const BodyDef& def);
  /// Every live body's handle, in the order the world steps them (`for (Entity e :
  /// world.bodies())`). Valid until the next create or destroy.
  [[nodiscard]] std::span<const Entity> bodies() const;
  /// The handles World(def) gave def.bodies, in definition order: defined_bodies()[i] is
  /// def.bodies[i]'s (a destroyed one stays listed, stale). Empty for a world built without a
  /// WorldDef.
  [[nodiscard]] std::span<const Entity> defined_bodies() const;
  /// The stability guard's findings on the definition World(def) built (near the bound, or
  /// unstable and allowed), bodies first: what a program shows as warnings. Kept by copies;
  /// not part of a snapshot.
  [[nodiscard]] std::span<const StabilityFinding> warnings() const;
  /// Destroys the body, its components and its links; throws std::invalid_argument if stale.
  void destroy(Entity e);
  /// Whether e names a live body (false for the null handle and destroyed bodies).
  [[nodiscard]] bool contains(Entity e) const;
  /// The body named `name` (the first in bodies() order when several share it), or the null
  /// entity (also for ""). O(1) for a name no other body has: a hash index the world keeps,
  /// built on the first call after a copy or restore.
  [[nodiscard]] Entity find(std::string_view name) const;
  /// Position (m) and velocity (m/s) of e, in double; throws std::invalid_argument if stale.
  [[nodiscard]] Body body(Entity e) const;
  /// Overwrites e's mass (kg), position (m) and velocity (m/s), validated as create_body; a
  /// program's edit between ticks (a teleport, a respawn). Prefer TickInput's per-body input
  /// (BodyInput) for what a player does, so recordings carry it.
  void set_body(Entity e, const Body& body);
  /// Moves e to `position` (m), its velocity and mass kept; validated as create_body (a
  /// non-finite or, in f32, unrepresentable value throws std::invalid_argument naming the
  /// body and field); throws if e is stale. An edit between ticks, as set_body.
  void set_position(Entity e, Vec2 position);
  /// Sets e's velocity (m/s): a kinematic body's motion from the next tick on, or a dynamic
  /// body's edit between ticks. Validated as create_body; a non-zero velocity for a static body
  /// throws std::invalid_argument (it never moves); throws if e is stale.
  void set_velocity(Entity e, Vec2 velocity);
  /// e's shapes (BodyDef::shapes) in the body frame; empty for a point body or a disc; throws
  /// std::invalid_argument if e is stale. Valid until the next create or destroy.
  [[nodiscard]] std::span<const ShapeDef> shapes(Entity e) const;
  /// e's centre of mass in the body frame, m ((0, 0) for a body without shapes): World::x()
  /// and y() hold the centre of mass, Body::position the origin, position = centre − R(θ)·c;
  /// throws std::invalid_argument if e is stale.
  [[nodiscard]] Vec2 local_center(Entity e) const;
  /// The program's 64-bit value of e (BodyDef::user_data); throws std::invalid_argument if e
  /// is stale.
  [[nodiscard]] std::uint64_t user_data(Entity e) const;
  /// Sets e's user data: kept with the body, copied by snapshots, never part of the state
  /// hash; throws std::invalid_argument if e is stale.
  void set_user_data(Entity e, std::uint64_t value);
  /// What mover e (BodyDef::mover) met in its last tick: floor, wall, ceiling, the body it
  /// stands on, its slid velocity (mover.hpp). Throws std::invalid_argument if e is stale or
  /// not a mover.
  [[nodiscard]] MoverState mover_state(Entity e) const;
  /// e's name ("" if none); throws std::invalid_argument if stale.
  [[nodiscard]] const std::string& name(Entity e) const;
  /// e's type (dynamic, static or kinematic); throws std::invalid_argument if stale.
  [[nodiscard]] BodyType type(Entity e) const;
  /// Whether e sleeps (ContactSettings::sleep): its island is at rest and is neither stepped
  /// nor solved until woken. False in a world without sleeping; throws if e is stale.
  [[nodiscard]] bool asleep(Entity e) const;
  /// Wakes e's island and restarts e's time at rest (an edit between ticks, as set_velocity:
  /// set_position and set_velocity wake too). Nothing else in a world without sleeping;
  /// throws if e is stale.
  void wake(Entity e);
  /// Dense index of e (valid until the next create or destroy); throws if stale.
  [[nodiscard]] std::size_t index_of(Entity e) const;
  /// Adds or replaces component C (SpringDamper, ConstantForce, Gravity, LinearDrag,
  /// Appearance, Collider) on e; throws std::invalid_argument naming the field when invalid
  /// or when e is stale.
  template <class C>
  void set(Entity e, const C& component);
  /// Removes component C from e (nothing if absent); throws std::invalid_argument if stale.
  template <class C>
  void remove(Entity e);
  /// e's component C, or nullopt (also for a stale handle).
  template <class C>
  [[nodiscard]] std::optional<C> get(Entity e) const;

  // --- links by handle --------------------------------------------------------------------
  Link create_link(const LinkDef& def);
  /// Destroys a link; throws std::invalid_argument if null or stale.
  void destroy_link(Link link);
  [[nodiscard]] bool contains(Link link) const;
  /// A live link's definition; throws std::invalid_argument if null or stale.
  [[nodiscard]] LinkDef link(Link link) const;
  [[nodiscard]] std::size_t link_count() const;

  // --- joints by handle (joint.hpp) ---------------------------------------------------------
  /// Creates a joint between two bodies with shapes (or one and the world: a null handle),
  /// its geometry taken from def in world coordinates now. Throws std::invalid_argument naming
  /// the field for a stale body, a body without shapes, a joint of a body to itself or of the
  /// world to the world, a value not finite, a negative maximum or frequency, lower > upper, a
  /// revolute limit outside [−π, π], a zero axis or length, a field its type does not use, or
  /// more joints than max_joints (joint.hpp).
  Joint create_joint(const JointDef& def);
  /// Destroys a joint (its bodies are woken); throws std::invalid_argument if null or stale.
  void destroy_joint(Joint joint);
  [[nodiscard]] bool contains(Joint joint) const;
  /// A live joint's definition as created; throws std::invalid_argument if null or stale.
  [[nodiscard]] JointDef joint(Joint joint) const;
  /// A live joint's state after the last tick (angle or translation, reaction force and
  /// torque, motor torque or force, broken); throws std::invalid_argument if null or stale.
  [[nodiscard]] JointState joint_state(Joint joint) const;
  [[nodiscard]] std::size_t joint_count() const;
  /// Every live joint's handle in creation order while none is destroyed. Valid until the next
  /// create or destroy.
  [[nodiscard]] std::span<const Joint> joints() const;
  /// The handles World(def) gave def.joints, in definition order (a destroyed one stays
  /// listed, stale).
  [[nodiscard]] std::span<const Joint> defined_joints() const;
  /// The joint named `name` (the first in joints() order), or the null joint (also for "").
  [[nodiscard]] Joint find_joint(std::string_view name) const;
  /// The joints that broke in the last tick (JointDef::break_force, break_torque), in joints()
  /// order; valid until the next step.
  [[nodiscard]] std::span<const JointBreak> joints_broken() const;

  /// A static half-plane bodies with a Collider collide with (World::add_plane).
  std::size_t add_plane(const PlaneDef& def);
  [[nodiscard]] std::span<const PlaneDef> planes() const;
  /// A static segment bodies with a Collider collide with (SegmentDef); returns its index into
  /// segments(). Throws std::invalid_argument naming segment[i] and the field for a
  /// non-finite end, coinciding ends, or restitution or friction out of range.
  std::size_t add_segment(const SegmentDef& def);
  /// The segments of a polyline (polyline_segments), joined by ghost vertices, static or
  /// carried by the kinematic `body`, each one-way (SegmentDef::one_way) when `one_way`;
  /// returns the index of its first segment. Throws as polyline_segments and add_segment do.
  std::size_t add_polyline(std::span<const Vec2> points, double restitution, double friction,
                           bool closed = false, Entity body = {}, bool one_way = false);
  [[nodiscard]] std::span<const SegmentDef> segments() const;
  /// Advances the world by one tick (WorldSettings::dt, s) with no input: step(TickInput{}).
  void step();
  /// Advances the world by one tick of `input` (its per-body forces, impulses and kinematic
  /// velocities; check_input says which entries it would ignore). Allocates nothing once warmed
  /// up. Throws StopRequested (stop_request.hpp) when a stop is requested during a long tick;
  /// the world is then neither the old state nor the new one and must be restored from a
  /// snapshot or dropped. Nothing else: a state that leaves the finite range is reported by
  /// fault(), not thrown.
  void step(const TickInput& input);
  /// Throws std::invalid_argument naming the first entry of input.bodies World::step would
  /// ignore: a stale handle, a non-finite value, a force or impulse on a body that is not
  /// dynamic, a velocity for one that is not kinematic, an angular input (torque, angular
  /// impulse, angular velocity, target angle) for a body without shapes or of the wrong type
  /// or with a non-zero value.y, or more than max_body_inputs entries; and the first entry of
  /// input.joints it would not apply (JointInput says which).
  void check_input(const TickInput& input) const;
  void set_keep_previous(bool keep);
  /// Installs the pre-solve hook (pre_solve.hpp): `fn(contact, context)` is called for every
  /// contact manifold of the shape phase once per tick, before the solve, in a fixed order;
  /// false disables that contact for the tick. nullptr (the default) removes it: a world
  /// without a hook pays one branch a tick. The hook is not state: save and restore leave the
  /// installed one in place (a snapshot neither holds nor replaces it), the state hash and the
  /// definition hash leave it out, and a copy of the World gets the same function and context.
  void set_pre_solve(PreSolveFn fn, void* context = nullptr);

  /// The runtime guard's finding: the first body whose state left the finite range (see
  /// World::fault()), or nullopt.
  [[nodiscard]] const std::optional<StateFault>& fault() const;
  [[nodiscard]] std::uint64_t tick() const;
  [[nodiscard]] double time() const;  ///< s
  [[nodiscard]] const WorldSettings& settings() const;
  [[nodiscard]] std::size_t body_count() const;
  [[nodiscard]] EnergyReport energy() const;  ///< J
  /// Mechanical energy of each body, J, in bodies() order; `out` must hold body_count()
  /// values (else std::invalid_argument). A link's potential is split equally between its two
  /// bodies.
  void body_energies(std::span<double> out) const;
  /// Which force terms some body declares (bits of ForceTermBits): a term nobody declares is
  /// not computed.
  [[nodiscard]] unsigned active_terms() const;
  /// Threads the last step used (1 or 2): 2 when its integration ran on two threads (a world
  /// with links or the dissipation account, on threads = 2, or automatic from
  /// parallel_min_bodies bodies), or when some pass of its disc contacts, shapes or joints was
  /// shared by halves with the second thread (WorldSettings::threads says from what sizes),
  /// else 1. The states are the same either way.
  [[nodiscard]] int threads_used() const;
  /// Energy dissipated by damping and drag so far, J (World::dissipated_energy()).
  [[nodiscard]] double dissipated_energy() const;
  /// Work of kinematic bodies on the others through contacts and links, J
  /// (World::external_work()).
  [[nodiscard]] double external_work() const;
  /// What the disc-disc contacts did in the last tick (World::contact_stats()).
  [[nodiscard]] const ContactStats& contact_stats() const;
  /// Where the last tick's time went in a world with disc contacts: integration, broadphase,
  /// impacts, the resting solver and events, in seconds of wall-clock time (StepProfile; all 0
  /// without disc contacts). Timings only: no state depends on them.
  [[nodiscard]] const StepProfile& profile() const;
  /// The disc-disc impacts of the last tick (World::impacts()).
  [[nodiscard]] std::span<const Impact> impacts() const;
  /// Disc pairs that began touching in the last tick (World::contacts_begun()).
  [[nodiscard]] std::span<const ContactEvent> contacts_begun() const;
  /// Disc pairs that stopped touching in the last tick (World::contacts_ended()).
  [[nodiscard]] std::span<const ContactEvent> contacts_ended() const;
  /// Discs that began overlapping a sensor (Collider::sensor) in the last tick, by (sensor,
  /// visitor) slot order, plus those that crossed one within the tick (also in
  /// sensors_ended()). A sensor sees the non-sensor discs its filter accepts
  /// (should_collide) and that are not linked to it, when at least one of the two is dynamic;
  /// raised at the tick the overlap starts. Empty without sensors; valid until the next step.
  [[nodiscard]] std::span<const SensorEvent> sensors_begun() const;
  /// Discs that stopped overlapping a sensor in the last tick (a handle may name a body
  /// destroyed since: check contains()), plus those that crossed one within the tick.
  [[nodiscard]] std::span<const SensorEvent> sensors_ended() const;
  /// Every disc overlapping a sensor after the last tick (|Δx| < r_sensor + r_visitor at the
  /// tick's end), by (sensor, visitor) slot order: what is in the bucket now.
  [[nodiscard]] std::span<const SensorEvent> sensor_overlaps() const;
  /// FNV-1a (64-bit) hash of the exact bits of every body's x, y, vx, vy in bodies() order, then,
  /// with rolling discs (ContactSettings::rolling) only, every body's θ and ω, then, with
  /// sleeping (ContactSettings::sleep) only, every body's ticks below the sleep speed and its
  /// island's number while asleep (0 awake), then, with joints only, each joint's motor speed,
  /// maxima, targets and accumulated impulses (double) and whether its motor is on and it broke,
  /// then, with movers only, each mover's MoverState (flags, normals, displacement, floor body);
  /// random()'s state is mixed in (FNV-1a over its
  /// 64-bit state) once it has been drawn from, so a world whose rules never roll dice hashes as
  /// one without random(). Equal hashes mean bit-identical states.
  [[nodiscard]] std::uint64_t state_hash() const;
  /// Bytes of heap memory a WorldSnapshot of this world holds: every array's elements, the body
  /// names' characters and the snapshot's own block (not the worker thread or the implicit
  /// solver's cache, which a copy does not take). For budgeting many snapshots (RewindBuffer).
  [[nodiscard]] std::size_t snapshot_bytes() const;

  /// Positions lerp(previous, current, alpha) in m, in bodies() order, for drawing between two
  /// ticks (alpha in [0, 1], the loop's interpolation alpha; needs set_keep_previous(true) to
  /// differ from the current state). x and y must hold body_count() values (else
  /// std::invalid_argument).
  void interpolate_positions(double alpha, std::span<float> x, std::span<float> y) const;
  /// Each live link's two bodies as places in bodies() (a[i], b[i] for the i-th link in creation
  /// order while none is destroyed), for drawing; a and b must hold link_count() values (else
  /// std::invalid_argument).
  void link_ends(std::span<std::uint32_t> a, std::span<std::uint32_t> b) const;

  // --- spatial queries (query.hpp; each without a filter is the same with QueryFilter{}): the
  // discs (Collider) at their positions after the last tick, the bodies' shapes (BodyDef::shapes)
  // at their poses, each shape on its own (QueryHit::shape, RayHit::shape: its index in
  // shapes(body)), and the planes and segments. Each runs through a grid of the discs and of the
  // shapes' boxes, built on the first query after the world changed (a step, a body created,
  // destroyed or moved, a Collider set), in O(n) with no allocation once warm; a query then visits
  // the grid cells its region covers (query_grid.hpp), at most every disc and shape once, and
  // tests a shape exactly (its rounded surface, not its box). Not safe to call on one World from
  // two threads at once (the grid is a cache). Every query throws std::invalid_argument naming
  // the argument when a coordinate is not finite (or a radius not finite and >= 0).

  /// The first shape the ray origin + s · translation, s in [0, 1] (m), enters: the hit with
  /// the least fraction, ties by handle slot (a body's shapes by index) and planes (by index) and
  /// segments (by index) last; nullopt when it enters none. The point and normal lie on the
  /// surface, exactly for circles, capsules and (rounded) polygons. A ray starting inside (or on)
  /// a disc or shape or on the solid side of a plane does not hit that shape (Box2D's rule). A
  /// zero translation hits nothing. Throws
  /// std::invalid_argument also for a ray reaching beyond max_query_reach.
  [[nodiscard]] std::optional<RayHit> cast_ray(Vec2 origin, Vec2 translation,
                                               const QueryFilter& filter) const;
  [[nodiscard]] std::optional<RayHit> cast_ray(Vec2 origin, Vec2 translation) const;
  /// Every shape the ray enters, ordered by fraction (ties by handle slot, planes and segments last
  /// by index). Writes the first min(total, out.size()) hits of that order into `out` and returns
  /// the total (call with an empty span to count). Allocates nothing once warm.
  std::size_t cast_ray_all(Vec2 origin, Vec2 translation, std::span<RayHit> out,
                           const QueryFilter& filter) const;
  std::size_t cast_ray_all(Vec2 origin, Vec2 translation, std::span<RayHit> out) const;
  /// The discs containing `point` (|point - centre| <= r), the shapes containing it (their
  /// surface included) and the planes it lies inside (n·point < offset), in handle slot order
  /// (a body's shapes by index), planes (by index) and segments (by index) last.
  /// Writes the first min(total, out.size()) and returns the total.
  std::size_t query_point(Vec2 point, std::span<QueryHit> out, const QueryFilter& filter) const;
  std::size_t query_point(Vec2 point, std::span<QueryHit> out) const;
  /// The discs overlapping the box [lower, upper] (m; the box's closest point to the centre
  /// within r), the shapes overlapping or touching it (the shape itself, not its box: GJK,
  /// distance <= 0) and the planes whose solid side it reaches, in handle slot order, planes and
  /// segments last. Writes the first min(total, out.size()) and returns the total. Throws
  /// std::invalid_argument also when lower > upper on an axis.
  std::size_t overlap_aabb(Vec2 lower, Vec2 upper, std::span<QueryHit> out,
                           const QueryFilter& filter) const;
  std::size_t overlap_aabb(Vec2 lower, Vec2 upper, std::span<QueryHit> out) const;
  /// The discs overlapping the circle (|c - center| <= r + radius, m), the shapes within
  /// `radius` of it, and the planes it reaches, in handle slot order, planes and segments last.
  /// Writes the first min(total, out.size()) and returns the total.
  std::size_t overlap_circle(Vec2 center, double radius, std::span<QueryHit> out,
                             const QueryFilter& filter) const;
  std::size_t overlap_circle(Vec2 center, double radius, std::span<QueryHit> out) const;
  /// The discs, shapes and segments overlapping or touching `shape` placed as a body's shape at
  /// body origin `position` (m) and `angle` (rad) (a disc: its centre within reach of the
  /// shape's core; a shape or segment: GJK distance <= 0), and the planes whose solid side it
  /// reaches, in handle slot order, planes and segments last. Writes the first min(total,
  /// out.size()) and returns the total. Throws std::invalid_argument also for a shape
  /// shape_problem() refuses, or an angle not finite.
  std::size_t overlap_shape(const ShapeDef& shape, Vec2 position, double angle,
                            std::span<QueryHit> out, const QueryFilter& filter) const;
  std::size_t overlap_shape(const ShapeDef& shape, Vec2 position, double angle,
                            std::span<QueryHit> out) const;

  /// The world's random generator for game rules: seeded with WorldSettings::seed when the
  /// world is made, saved and restored with snapshots (so a restore, a rewind or a replay
  /// rolls the same numbers again), and mixed into state_hash() once it has been drawn from.
  /// Draw from it only inside a tick's rules (or between ticks, as any edit), never in
  /// drawing code: a frame rate must not change what it gives.
  [[nodiscard]] Random& random();
  [[nodiscard]] const Random& random() const;

  /// Saves the complete state into `out`, reusing its storage: no allocation once `out` holds
  /// a state of the same shape (same bodies, links and components).
  void save(WorldSnapshot& out) const;
  /// Puts back a saved state: every later step gives the same bits as after the save. The
  /// snapshot may come from another World (it replaces this one's world, precision
  /// included). This world keeps its worker threads (WorldSettings::threads), so a rollback
  /// that restores every frame starts none. Throws std::invalid_argument for an empty
  /// snapshot.
  void restore(const WorldSnapshot& snapshot);

 private:
  void check_body_input(const BodyInput& in, const std::string& who) const;
  /// Reads the fields state_hash() mixes from the kernel, as state_hash() does.
  friend StateFields state_fields(const World& world);
  /// Calls f on the kernel inside (WorldKernel<float> or <double>); defined with the state
  /// (engine/core/src/world_state.hpp), for World's own sources.
  template <class F>
  decltype(auto) visit(F&& f);
  template <class F>
  decltype(auto) visit(F&& f) const;
  /// The queries' grid is out of date (a step or an edit of the discs).
  void queries_changed();
  /// Adds def's bodies, links, planes, segments and joints to this empty world (World(def)).
  void build(const WorldDef& def);
  void build_joints(const WorldDef& def);
  void check_joint_inputs(const TickInput& input) const;

  std::unique_ptr<detail::WorldState> state_;
};

/// The energy balance error (E + E_dissipated - W_external - E0)/|E0| (dimensionless; in J
/// when E0 = 0): what the integrator alone adds or loses, with the energy damping, drag and
/// contacts took out (World::dissipated_energy, kept when WorldSettings::track_dissipation
/// is on, as for every scene) put back and the work kinematic bodies did
/// (World::external_work) taken off. initial_energy = E0 in J.
[[nodiscard]] double energy_balance(const World& sim, double initial_energy);

}  // namespace fixstep
