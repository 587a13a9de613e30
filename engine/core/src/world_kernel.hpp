// The world's kernel in one precision (Real = float or double): entities, their components, and
// the fixed-step integration of their bodies. Internal: a program holds a fixstep::World
// (world.hpp), which chooses the precision at creation and holds one of these inside.
//
// Layout (the EnTT idea, kept minimal): every component type lives in its own sparse set keyed
// by entity slot, so adding or removing a component never touches the others. Body state is
// stored structure-of-arrays (x, y, vx, vy) in the set's dense order, which is the order the
// integrator walks. Since every fixstep force acts on one body, the components fold into one
// per-body force field a(x, v) = -K s(x - anchor) - γ v + c, kept as arrays in the world's
// precision and rebuilt only when components are added or removed, never per tick. A tick is
// one fused pass over the bodies that reads only the arrays of the parts some body declares:
// a force nobody declares costs nothing. active_terms() says which terms are declared.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "awake_runs.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/pre_solve.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/world_settings.hpp"
#include "joint_record.hpp"
#include "mover_slide.hpp"
#include "owner_ptrs.hpp"
#include "scratch_vector.hpp"
#include "segment_set.hpp"
#include "sparse_set.hpp"
#include "thread_choice.hpp"

/// The small phases of a tick (world_tick.cpp): named functions in the files they belong to,
/// inlined into WorldKernel::step (kernel_instances.cpp compiles them in one unit), so that a
/// tick of a few bodies pays no call for a phase it does not need.
#if defined(__GNUC__) || defined(__clang__)
#define FIXSTEP_TICK_PHASE [[gnu::always_inline]] inline
#else
#define FIXSTEP_TICK_PHASE inline
#endif

namespace fixstep {

namespace plane_contact {
struct V2;  // plane_contact.hpp
}  // namespace plane_contact

namespace detail {

/// `v` rounded to Real, as a double: a body with shapes keeps its angle and angular velocity
/// in double, rounded to the world's precision. Through a volatile Real: GCC 12 on x86-64
/// (-O2 and -O3) merges two adjacent `double(static_cast<float>(x))` stores into one vector
/// store and drops the rounding (aarch64's GCC 12 keeps it), so an f32 world with shapes
/// stepped to other bits on x86-64 than on aarch64 from its second tick (boxes.toml).
template <class Real>
[[nodiscard]] inline double rounded_to(double v) {
  const volatile Real r = static_cast<Real>(v);
  return double(r);
}

/// The second thread of a world with links (world_coupled.cpp).
class Workers;
struct WorkersDeleter {
  void operator()(Workers* w) const;
};
/// Implicit Euler's sparse solver for a world with links (world_implicit.cpp, Eigen).
template <class Real>
class ImplicitSolver;
template <class Real>
struct ImplicitSolverDeleter {
  void operator()(ImplicitSolver<Real>* s) const;
};
/// A collider's motion after its last plane impact in a tick (world_contacts.cpp), from which
/// the disc-disc contacts continue (its time, s into the tick, is kept apart: ContactScratch's
/// after_t): position, model velocity and acceleration at that time, and the integrator's
/// velocity offset; the time of its first plane event (s), before which it moves on its free
/// motion, of acceleration free_a and offset free_d from its start state, and (a rolling disc)
/// spin free_w (rad/s): the spin before the plane pass's friction turned it.
struct PlaneMotion {
  double x = 0, y = 0, ux = 0, uy = 0, ax = 0, ay = 0, dx = 0, dy = 0;
  double first = 0, free_ax = 0, free_ay = 0, free_dx = 0, free_dy = 0, free_w = 0;
};
/// One body's way through a tick's planes and segments (world_contacts.cpp).
struct PlaneWay;
/// What resolve_contacts counts over the bodies of a tick.
struct PlaneTally {
  std::uint64_t again = 0;  ///< plane tests after a body's max_impacts-th event (limits.hpp)
  std::size_t capped = 0;   ///< ContactStats::capped of the planes
  bool out_of_range = false;
  /// The second half of the bodies on two threads (world_plane_blocks.cpp): a body that would
  /// count against the cap or add to the world's external work is left whole (`deferred`
  /// set) for this thread to redo after the first half, in order, as one thread would.
  bool defer = false, deferred = false;
};
/// Disc-disc contacts of a world with WorldSettings::contacts (disc_contacts.hpp).
template <class Real>
class DiscContacts;
/// Contacts of bodies with shapes (shape_world.hpp).
class ShapeWorld;
/// The uniform grid of discs that World's queries and the sleeping islands' wake test use
/// (query_grid.hpp).
class QueryGrid;
struct QueryGridDeleter {
  void operator()(QueryGrid* grid) const;
};
/// A world of point bodies stepped at a fixed dt in precision Real (float or double).
///
/// Copies are complete, independent states (a snapshot): bodies, components, links, tick,
/// energy accounts and the runtime guard's fault; a copy steps to the same bits as the
/// original. Copy-assigning between worlds of equal size reuses storage (no allocation).
///
/// Errors: creation and setters throw std::invalid_argument naming the body and field when a
/// value is non-finite (also after narrowing to Real) or out of range; using a stale or null
/// Entity throws std::invalid_argument. step() never throws; it allocates only on the first
/// step after a structural change (rebuilding the force-term lists) and the first time a step
/// length is seen (damping-flow factors), and nothing per tick after that.
template <class Real>
class WorldKernel {
 public:
  using real_type = Real;

  /// Throws std::invalid_argument if settings.dt is not finite and > 0.
  explicit WorldKernel(const WorldSettings& settings);

  // --- entities -------------------------------------------------------------------------
  /// Creates an entity with a Body and the optional components set in def.
  Entity create_body(const BodyDef& def);
  /// Reserves room for `bodies` bodies (avoids regrowth when creating many).
  void reserve(std::size_t bodies);
  /// Destroys the entity, all its components and every link attached to it; its handle (and
  /// copies, and the links' handles) become stale.
  void destroy(Entity e);
  [[nodiscard]] bool contains(Entity e) const { return bodies_.contains(e); }
  [[nodiscard]] std::size_t body_count() const { return bodies_.dense.size(); }
  /// Dense index of e's body (the index into x(), y(), ...); throws if e is stale.
  [[nodiscard]] std::size_t index_of(Entity e) const;
  /// The first body in dense order named `name`, or the null entity (also for ""). O(1) for a
  /// name no other body has (O(k) for k bodies of one name): a hash index built on the first
  /// call after a copy and kept up to date by create_body and destroy.
  [[nodiscard]] Entity find(std::string_view name) const;

  // --- links: spring-dampers between bodies (cold path; see LinkSpring for the force) ------
  /// Creates a link. Throws std::invalid_argument when a body is null or stale, both ends are
  /// the same body, a parameter is non-finite (also after narrowing to Real) or negative, or
  /// a rest-length link's bodies are at the same point (its direction is undefined).
  Link create_link(const LinkDef& def);
  /// Destroys a link; throws std::invalid_argument if the handle is null or stale.
  void destroy_link(Link link);
  [[nodiscard]] bool contains(Link link) const;
  [[nodiscard]] std::size_t link_count() const { return links_.dense.size(); }
  /// The definition of a live link; throws std::invalid_argument if it is null or stale.
  [[nodiscard]] LinkDef link(Link link) const;
  /// The handle of the link at dense index i < link_count() (creation order while no link is
  /// destroyed).
  [[nodiscard]] Link link_at(std::size_t i) const {
    return Link{links_.dense[i].index1, links_.dense[i].generation};
  }
  /// Dense body indices of both ends of the link at dense index i (for drawing).
  [[nodiscard]] std::pair<std::size_t, std::size_t> link_bodies(std::size_t i) const;

  // --- components (cold path; each change rebuilds the force-term lists before next step) --
  /// Adds or replaces component C on e. C is one of SpringDamper, ConstantForce, Gravity,
  /// LinearDrag, Appearance, Collider.
  template <class C>
  void set(Entity e, const C& component);
  /// Removes component C from e (no-op if absent).
  template <class C>
  void remove(Entity e);
  /// The component C of e, or nullptr.
  template <class C>
  [[nodiscard]] const C* get(Entity e) const;

  /// The type of e's body (dynamic, static or kinematic); throws if e is stale.
  [[nodiscard]] BodyType type(Entity e) const { return types_[index_of(e)]; }
  /// The type of the body at dense index i < body_count().
  [[nodiscard]] BodyType type_at(std::size_t i) const { return types_[i]; }

  /// Body state of e converted to double.
  [[nodiscard]] Body body(Entity e) const;
  /// Overwrites mass, position and velocity of e (validated like create_body).
  void set_body(Entity e, const Body& body);
  /// Moves e to `position` (m) with its velocity and mass kept, validated as create_body.
  void set_position(Entity e, Vec2 position);
  /// Sets e's velocity (m/s), validated as create_body: a kinematic body's next motion, or a
  /// dynamic body's edit between ticks. Throws std::invalid_argument for a non-zero velocity
  /// of a static body (it never moves).
  void set_velocity(Entity e, Vec2 velocity);
  /// The program's 64-bit value of e (BodyDef::user_data); throws if e is stale.
  [[nodiscard]] std::span<const ShapeDef> shapes(Entity e) const;  // (world_shapes.cpp)
  [[nodiscard]] Vec2 local_center(Entity e) const;
  [[nodiscard]] bool has_shapes() const { return !shape_sets_.data.empty(); }
  /// What mover e met in its last tick (world_movers.cpp); throws if e is stale or no mover.
  [[nodiscard]] MoverState mover_state(Entity e) const;

  // --- joints (world_joints.cpp, world_joint_checks.cpp; joint.hpp) -------------------------
  /// Creates a joint from def (checked: check_joint), its geometry fixed in its bodies' frames
  /// now; `who` names it in errors.
  Joint create_joint(const JointDef& def, const std::string& who);
  /// Throws std::invalid_argument if the joint is null or stale.
  void destroy_joint(Joint joint);
  [[nodiscard]] bool contains(Joint joint) const {
    return joints_.contains(Entity{joint.index1, joint.generation});
  }
  [[nodiscard]] const JointDef& joint(Joint joint) const {
    return joint_records_[joint_index(joint)].def;
  }
  [[nodiscard]] JointState joint_state(Joint joint) const;
  [[nodiscard]] std::size_t joint_count() const { return joint_records_.size(); }
  [[nodiscard]] std::span<const Joint> joint_handles() const { return joint_handles_; }
  [[nodiscard]] Joint find_joint(std::string_view name) const;
  [[nodiscard]] std::span<const JointBreak> joints_broken() const { return joints_broken_; }
  /// Throws std::invalid_argument naming `who` when World::step would not apply `in`.
  void check_joint_input(const JointInput& in, const std::string& who) const;
  /// The shape contacts (null without shapes): for tests that read the solver's rows or set
  /// its switches (ShapeWorld::skip_idle_rows).
  [[nodiscard]] const ShapeWorld* shape_world() const { return shape_world_.get(); }
  [[nodiscard]] ShapeWorld* shape_world() { return shape_world_.get(); }
  /// The discs' contacts (null in a world without them), for the tests.
  [[nodiscard]] const DiscContacts<Real>* disc_contacts() const { return discs_.get(); }
  [[nodiscard]] std::uint64_t user_data(Entity e) const { return user_data_[index_of(e)]; }
  /// Sets e's user data (part of copies and snapshots, never of the state hash).
  void set_user_data(Entity e, std::uint64_t value) { user_data_[index_of(e)] = value; }

  // --- planes: static half-planes bodies with a Collider collide with (world_contacts.cpp) --
  /// Adds the half-plane n·x >= offset of free space with n = def.normal/|def.normal|; returns
  /// its index into planes(). Throws std::invalid_argument naming the field when the normal is
  /// zero or not finite, or offset, restitution (in [0, 1]) or friction (>= 0) is out of range
  /// or not finite. Planes cannot be removed.
  std::size_t add_plane(const PlaneDef& def);
  /// The planes in order of creation, normals normalised.
  [[nodiscard]] std::span<const PlaneDef> planes() const { return planes_; }
  /// Adds a static segment (SegmentDef) and returns its index into segments(). Throws
  /// std::invalid_argument naming segment[i] and the field when an end or ghost vertex is not
  /// finite, the ends coincide, or restitution (in [0, 1]) or friction (>= 0) is out of range
  /// (world_segments.cpp). Segments cannot be removed.
  std::size_t add_segment(const SegmentDef& def);
  [[nodiscard]] std::span<const SegmentDef> segments() const { return segments_.defs(); }
  [[nodiscard]] const SegmentSet& segment_set() const { return segments_; }

  // --- stepping ---------------------------------------------------------------------------
  /// Advances every body by one tick of settings().dt with the chosen integrator.
  ///
  /// Without links (and without track_dissipation), one fused pass over the bodies: each
  /// body's whole tick (every substep, every stage) runs in registers and its state is loaded
  /// and stored once. The pass reads only the coefficient arrays of force parts some body
  /// declares; bytes_per_body_step() gives the resulting memory traffic. With links, each
  /// force evaluation is a pass over the links (their forces) and a pass over the bodies
  /// (each gathers its links' forces in a fixed order), on one or two threads (see
  /// WorldSettings::threads); implicit Euler solves the linear system of the whole network
  /// (world_implicit.cpp). Both paths give bit-identical states where both apply.
  ///
  /// When input.drag_body names a body, the pointer's drag spring (input.hpp: drag_frequency,
  /// drag_damping_ratio) first changes that body's velocity, implicitly over the tick; its
  /// work is not in the energy account (an external force, like push). A non-finite pointer
  /// leaves the velocity as it was.
  void step(const TickInput& input = {});
  /// The pre-solve hook the shape phase calls (World::set_pre_solve; World::step sets it before
  /// each tick, so a restored or copied kernel's is never stale). Not state.
  void set_pre_solve(PreSolveFn fn, void* context) {
    pre_solve_ = fn, pre_solve_context_ = context;
  }
  /// Bytes one tick moves between memory and the core per body (STREAM's convention: each
  /// array element read or written counts once, write-allocate traffic is not counted):
  /// x, y, vx, vy read and written, plus each coefficient array the kernel reads, plus
  /// x and y copied to previous_x()/previous_y() when set_keep_previous is on. Rebuilds the
  /// force field first if components changed.
  [[nodiscard]] std::size_t bytes_per_body_step();
  /// The runtime guard: the first body whose state left the finite range in a step (NaN,
  /// infinity or a magnitude beyond max_state_magnitude), or nullopt. Checked inside the fused
  /// pass on values already in registers (a compare per component; no extra memory traffic).
  /// step() keeps stepping after a fault; callers stop (fixstep run/render exit non-zero, the
  /// window pauses) and explain it with explain_fault() (stability.hpp).
  [[nodiscard]] const std::optional<StateFault>& fault() const { return fault_; }
  /// Number of ticks taken since creation.
  [[nodiscard]] std::uint64_t tick() const { return tick_; }
  /// Simulated time tick()·dt, s.
  [[nodiscard]] double time() const { return static_cast<double>(tick_) * settings_.dt; }
  [[nodiscard]] const WorldSettings& settings() const { return settings_; }
  void set_integrator(Integrator integrator) { settings_.integrator = integrator; }
  /// When on, step() first copies positions to previous_x()/previous_y() so a renderer can
  /// interpolate between the last two ticks. Off by default (costs a copy per tick).
  void set_keep_previous(bool keep);

  /// Accelerations a(x, v) at the current state, m/s², links included; ax and ay must hold
  /// body_count() (else std::invalid_argument).
  void accelerations(std::span<Real> ax, std::span<Real> ay, const TickInput& input = {});
  /// Which force terms some body declares (bits of ForceTermBits).
  [[nodiscard]] unsigned active_terms() const;
  /// Threads the last step used (1 or 2): 2 when its integration ran on two, or when a pass of
  /// its disc or shape phases was handed to the second thread.
  [[nodiscard]] int threads_used() const { return threads_used_; }
  /// The thread count the disc phases were given in the last tick that ran them (1 or 2;
  /// below DiscContacts::min_parallel_discs busy discs they run on one either way).
  [[nodiscard]] int disc_phase_count() const { return disc_count_; }

  // --- state (dense body order) -----------------------------------------------------------
  [[nodiscard]] std::span<const Real> x() const { return x_; }
  [[nodiscard]] std::span<const Real> y() const { return y_; }
  [[nodiscard]] std::span<const Real> vx() const { return vx_; }
  [[nodiscard]] std::span<const Real> vy() const { return vy_; }
  [[nodiscard]] std::span<const Real> previous_x() const { return prev_x_; }
  [[nodiscard]] std::span<const Real> previous_y() const { return prev_y_; }
  [[nodiscard]] std::span<const Entity> entities() const { return bodies_.dense; }
  /// Angles θ (rad, in [-π, π]) and angular velocities ω (rad/s) of rolling discs; empty in
  /// a world without ContactSettings::rolling.
  [[nodiscard]] std::span<const Real> angle() const { return angle_; }
  [[nodiscard]] std::span<const Real> angular_velocity() const { return spin_; }
  /// Each body's ticks below the sleep speed and its island's number while asleep (0 awake),
  /// as state_hash() mixes them; empty in a world without ContactSettings::sleep.
  [[nodiscard]] std::span<const std::uint32_t> still_ticks() const { return still_ticks_; }
  [[nodiscard]] std::span<const std::uint32_t> islands() const { return asleep_; }
  [[nodiscard]] const std::string& name(std::size_t index) const { return names_[index]; }
  /// Whether the body at dense index i sleeps (ContactSettings::sleep): false in a world
  /// without sleeping.
  [[nodiscard]] bool asleep(std::size_t index) const {
    return !asleep_.empty() && asleep_[index] != 0;
  }
  /// Wakes the island of the body at dense index i (nothing when it is awake).
  void wake(std::size_t index);

  // --- measurements -----------------------------------------------------------------------
  /// Total mechanical energy by kind, J (see EnergyReport for the potentials).
  [[nodiscard]] EnergyReport energy() const;
  /// Mechanical energy of each body, J; out must hold body_count() values. A link's potential
  /// is split equally between its two bodies.
  void body_energies(std::span<double> out) const;
  /// Energy taken out by damping (anchored springs and links) and drag since creation, J,
  /// when settings().track_dissipation is on (0 otherwise). Each integrator integrates the
  /// dissipated power Σ b|u|² + c|v|² with its own stages (Euler methods: one rectangle per
  /// step; RK4: its weights 1/6, 1/3, 1/3, 1/6; implicit Euler: the end of the step), or
  /// takes the kinetic energy its damping flow removes (velocity Verlet, Forest–Ruth), so
  /// the energy balance (E + E_dissipated - E0)/|E0| shrinks at the integrator's order.
  [[nodiscard]] double dissipated_energy() const;
  /// Work done on the dynamic bodies from outside the world's energy account, J, since
  /// creation: by kinematic bodies through contacts (their impulses' work on the bodies they
  /// push) and through links (the power -F·v of each link force F on a kinematic end moving
  /// at v, integrated with the integrator's own stages, as dissipated_energy() is). The energy
  /// balance is E + E_dissipated - W_external - E0 (energy_balance()). Velocity Verlet and
  /// Forest–Ruth count here only a link's spring: their damping flow takes a damped link's
  /// whole effect on kinetic energy into dissipated_energy(), which then holds the damper's
  /// dissipation minus the kinematic end's work through it (the balance is unchanged).
  [[nodiscard]] double external_work() const { return external_work_; }
  /// Disc-disc contacts of the last tick (WorldSettings::contacts): what the broadphase and the
  /// solver did. Zero without contacts.
  [[nodiscard]] const ContactStats& contact_stats() const { return contact_stats_; }
  /// How many times the plane passes (planes and segments) polled a stop request, over the
  /// world's life: every 1024 colliders, and every plane_poll_tests segment tests.
  [[nodiscard]] std::uint64_t plane_polls() const { return plane_polls_; }
  /// Segment tests of a plane pass between two stop polls (a disc may test every segment).
  static constexpr std::uint64_t plane_poll_tests = 1 << 16;
  /// Where the last tick's time went, with disc contacts (StepProfile); zero without.
  [[nodiscard]] const StepProfile& profile() const { return profile_; }
  /// The disc-disc impacts of the last tick in the order they were resolved (empty without
  /// contacts): what a game's rules read to score a hit. Valid until the next step.
  [[nodiscard]] std::span<const Impact> impacts() const;
  /// Pairs of discs touching after the last tick that were not before it, in handle order,
  /// plus pairs that struck and parted within the tick (also in contacts_ended()). Empty
  /// without contacts. Valid until the next step.
  [[nodiscard]] std::span<const ContactEvent> contacts_begun() const { return begun_; }
  /// Pairs of discs touching before the last tick that are not after it (a handle may name a
  /// body destroyed since: check contains()), plus pairs that struck and parted within it.
  [[nodiscard]] std::span<const ContactEvent> contacts_ended() const { return ended_; }
  /// Discs that began overlapping a sensor in the last tick, by (sensor, visitor) slot order,
  /// plus those that crossed it within the tick (also in sensors_ended()). Empty without
  /// sensors. Valid until the next step.
  [[nodiscard]] std::span<const SensorEvent> sensors_begun() const { return sensor_begun_; }
  /// Discs that stopped overlapping a sensor in the last tick (a handle may name a body
  /// destroyed since), plus those that crossed it within the tick.
  [[nodiscard]] std::span<const SensorEvent> sensors_ended() const { return sensor_ended_; }
  /// Every disc overlapping a sensor after the last tick, by (sensor, visitor) slot order.
  [[nodiscard]] std::span<const SensorEvent> sensor_overlaps() const { return sensed_; }
  /// FNV-1a (64-bit) hash of the exact bits of every body's x, y, vx, vy in dense order, then,
  /// with rolling discs (ContactSettings::rolling) only, every body's θ and ω, then, with
  /// sleeping (ContactSettings::sleep) only, every body's ticks below the sleep speed and its
  /// island's number while asleep (0 awake): equal hashes mean bit-identical states.
  [[nodiscard]] std::uint64_t state_hash() const;
  /// Bytes of heap memory a copy of this world (a WorldSnapshot) holds: every array's elements
  /// and the body names' characters (not the worker threads or the implicit solver's cache,
  /// which a copy does not take). For budgeting many copies (RewindBuffer); about 0.5 kB per
  /// body of a cloth-like grid with its links.
  [[nodiscard]] std::size_t snapshot_bytes() const;

 private:
  template <class C>
  Store<C>& store();
  template <class C>
  const Store<C>& store() const;
  void validate(const Body& body, const std::string& who) const;
  // stepping (world_step.cpp)
  void apply_drag(const TickInput& input);
  const Real* damping_decay(double tau);
  struct LinkFlow;
  const LinkFlow& link_flow(double tau);  // (world_coupled.cpp)
  static void validate_component(const SpringDamper& c, const std::string& who);
  static void validate_component(const ConstantForce& c, const std::string& who);
  static void validate_component(const Gravity& c, const std::string& who);
  static void validate_component(const LinearDrag& c, const std::string& who);
  static void validate_component(const Appearance& c, const std::string& who);
  static void validate_component(const Collider& c, const std::string& who);
  [[nodiscard]] std::string describe(Entity e) const;
  void require(Entity e) const;
  void rebuild_terms();
  void record_fault();
  /// Records a fault when a body's or link's dissipated energy is no longer finite (with
  /// track_dissipation; world_step.cpp).
  void check_energy_account();
  void record_cap_fault(std::size_t body, const char* cap, std::uint64_t limit,
                        const std::string& with);
  template <class Add>
  void for_each_energy(Add&& add) const;

  WorldSettings settings_;
  std::uint64_t tick_ = 0;
  bool keep_previous_ = false;
  bool terms_dirty_ = true;
  std::optional<StateFault> fault_;

  // entity slots
  std::vector<std::uint32_t> generations_;
  std::vector<std::uint32_t> free_slots_;
  std::vector<std::uint32_t> link_generations_;
  std::vector<std::uint32_t> link_free_slots_;

  // bodies: SoA in dense order
  SparseSet bodies_;
  std::vector<Real> x_, y_, vx_, vy_, prev_x_, prev_y_;
  std::vector<double> mass_;
  std::vector<BodyType> types_;
  std::vector<std::string> names_;
  std::vector<std::uint64_t> user_data_;  ///< BodyDef::user_data, in dense order
  double external_work_ = 0.0;            ///< J (external_work())
  ContactStats contact_stats_;
  StepProfile profile_;  ///< profile(): timings only, never read by the physics

  // components (authoritative, double)
  Store<SpringDamper> springs_;
  Store<ConstantForce> constant_forces_;
  Store<Gravity> gravities_;
  Store<LinearDrag> drags_;
  Store<Appearance> appearances_;
  // links (authoritative, double), dense; keyed by Link handles stored as Entity-shaped keys
  SparseSet links_;
  std::vector<LinkDef> link_defs_;
  // dissipated energy per unit mass per body (J/kg) and per link (J), when tracked
  std::vector<Real> dissipated_body_;
  std::vector<Real> dissipated_link_;
  double dissipated_gone_ = 0.0;  ///< J, of destroyed bodies and links
  int threads_used_ = 1;
  /// Passes handed to the second threads of the disc and shape phases so far (world_tick.cpp).
  [[nodiscard]] std::uint64_t handed_passes() const;

  // The force field per body, in dense order, rebuilt from the components when terms_dirty_:
  //   a(x, v) = -K s(d) - γ v + c + push,   d = x - anchor,
  // with K = k/m, s(d) = d for rest length 0 and (|d| - L) d/|d| otherwise, γ = (b + c_drag)/m,
  // c = F/m + g. The step kernels read only the arrays of the parts some body declares (the
  // flags): a scene without springs never touches stiffness or anchors, one without damping
  // never reads γ.
  struct Coefficients {
    std::vector<Real> stiffness, anchor_x, anchor_y, rest, gamma, accel_x, accel_y;
    bool spring = false;       ///< some body has a spring (stiffness, anchor_x, anchor_y are read)
    bool rest_length = false;  ///< some spring has L > 0 (rest is read; |d| needs a sqrt)
    bool damping = false;      ///< some body has γ > 0 (gamma or the damping-flow decay)
    bool accel = false;        ///< some body has c != 0 (accel_x, accel_y are read)
    bool gamma_uniform = false;  ///< every body has the same γ, gamma[0] (the fused sweep's)
  } coeff_;
  // Exact damping flow D(τ) factors e^{-γτ} per body (1 where γ = 0), cached per τ: a Verlet
  // tick needs one τ, Forest–Ruth two.
  struct DampingFlow {
    double tau = -1.0;
    std::vector<Real> decay;
  };
  std::vector<DampingFlow> flows_;

  // The link network, rebuilt with the coefficients: both ends (dense body indices) and the
  // spring of each link in Real, 1/m per body, and each body's incident links in CSR form
  // (incident[offset[j] .. offset[j+1]) = 2·link + (0 if the body is end a, 1 if end b)), in
  // link order, so every body sums its link forces in the same order on any thread.
  struct Network {
    std::vector<std::uint32_t> a, b;
    std::vector<Real> k, damping, rest, inv_mass;
    std::vector<std::uint32_t> offset, incident;
    // With damped links, the links grouped by colour: no two links of a colour share a body
    // (greedy edge colouring in link order), so the exact damping flows of a colour's links
    // commute and run in parallel (link_damping.hpp). by_color[color_offset[c] ..
    // color_offset[c+1]) are colour c's links in link order.
    std::vector<std::uint32_t> color_offset, by_color;
    std::vector<std::uint32_t> color_a, color_b;  ///< a, b, k, rest in colour order
    std::vector<Real> color_k, color_rest;
    std::vector<std::uint32_t> driven;  ///< links with a static or kinematic end, in link order
    bool rest_length = false;           ///< some link has L > 0
    bool all_rest_length = false;       ///< every link has L > 0 (none has L = 0)
    bool damped = false;                ///< some link has b > 0
  } net_;
  // Each link's exact damping flow over τ (link_damping.hpp), in colour order (by_color),
  // cached per τ like flows_:
  // Δv_a = ca·p, Δv_b = -cb·p for the relative velocity p along the link (the kinetic energy
  // it removes is counted per body by the kicks around the sweeps: strang_network.hpp).
  struct LinkFlow {
    double tau = -1.0;
    std::vector<Real> ca, cb;  ///< per link in colour order (link_damping.hpp)
  };
  std::vector<LinkFlow> link_flows_;
  std::vector<Real> unit_x_,
      unit_y_;  ///< each link's direction at the last force pass (colour order)
  // The Strang chain's last link sums (d_[0], d_[1]) and directions were computed at these
  // positions: the next tick's first force pass is skipped when the positions are still these,
  // bit for bit (first same as last across ticks; strang_network.hpp). Not state: a pure
  // function of the positions and the network, so reusing it changes no bit.
  std::vector<Real> fsal_x_, fsal_y_;
  bool fsal_valid_ = false;
  // Scratch of the multi-pass path, sized at rebuild (never per tick): link forces, stage
  // states and accumulators (see world_coupled.cpp).
  std::vector<Real> fx_, fy_, power_body_, power_link_;
  // Stage states and derivatives, one vector per stage of a four-stage integrator.
  std::array<std::vector<Real>, 4> s_, d_;
  /// Bodies by name for find(): FNV-1a of the name -> the bodies with that hash (unnamed bodies
  /// are not indexed). A cache: a copy rebuilds it on its first find().
  struct NameIndex {
    std::unordered_map<std::uint64_t, std::vector<Entity>> by_hash;
  };
  void index_name(Entity e, const std::string& name) const;
  void unindex_name(Entity e, const std::string& name) const;
  mutable CachePtr<NameIndex, std::default_delete<NameIndex>> name_index_;
  KeptPtr<Workers, WorkersDeleter> workers_;
  CachePtr<ImplicitSolver<Real>, ImplicitSolverDeleter<Real>> implicit_;
  // (world_coupled.cpp)
  void step_multipass(const TickInput& input);
  template <class Pass>
  void parallel(std::size_t n, Pass&& pass, std::size_t min_range);
  void rebuild_network();
  void validate_link(const LinkDef& def, const std::string& who) const;
  // (world_implicit.cpp)
  bool step_implicit_network(Real h, const Real push[2]);
  void integrate(const TickInput& input);  // one tick of the integrator (world_step.cpp)
  /// What a tick runs besides the integration (world_tick.cpp: plan_tick).
  struct TickPlan {
    bool planes = false;        ///< contacts with planes (world_contacts.cpp)
    bool immovable = false;     ///< static, kinematic or sleeping bodies put back after the step
    bool quiet = false;         ///< every disc sleeps: the disc phases are skipped
    bool shapes_still = false;  ///< sleepers, and nothing with shapes moves: no shape phase
    bool discs = false;         ///< the disc phases run (world_discs.cpp, world_events.cpp, ...)
    bool own_worker = false;    ///< the integration has a worker thread of its own (links)
  };
  /// The tick's plan; where its disc phases run, their thread count (disc_count_) chosen.
  [[nodiscard]] FIXSTEP_TICK_PHASE TickPlan plan_tick();
  /// The tick's input at its start: islands woken, impulses, kinematic velocities, carried
  /// segments placed, the pointer's drag (world_input.cpp).
  FIXSTEP_TICK_PHASE void apply_input(const TickInput& input);
  /// The integration with the tick's per-body forces and push, the contacts' and the
  /// immovable bodies' start states saved before it and put back after (world_input.cpp).
  FIXSTEP_TICK_PHASE void integrate_with_input(const TickInput& input, bool immovable, bool discs);
  FIXSTEP_TICK_PHASE void keep_previous_positions();  ///< previous_x/y (world_step.cpp)
  /// WorldSettings::flush_denormals, every flush_denormals_every ticks (world_step.cpp).
  FIXSTEP_TICK_PHASE void flush_state_subnormals();

  // Contacts with static half-planes (world_contacts.cpp). The scratch holds, for each body
  // with a Collider, its dense index, radius and start-of-tick state (SoA), sized in
  // rebuild_terms(), so a tick allocates nothing. Inactive (no planes or no colliders): step()
  // runs none of it.
  Store<Collider> colliders_;
  std::vector<PlaneDef> planes_;
  struct ContactScratch {
    std::vector<std::uint32_t> body;
    std::vector<double> radius;
    // Written for every collider by each tick with planes before it reads them
    // (save_contact_start, resolve_body_contacts): a snapshot copies their sizes only.
    ScratchVector<Real> x0, y0, vx0, vy0;
    /// Per collider, this tick: the time of its motion in `after` (s into the tick), < 0 when
    /// no plane or segment acted on it and `after` is not written. Dense, apart from `after`,
    /// since every tick writes it for every collider and the disc passes read it for every disc.
    ScratchVector<double> after_t;
    ScratchVector<PlaneMotion> after;  ///< per collider, this tick, where after_t >= 0
    /// This tick's colliders not clear of every plane, by halves (find_near_planes).
    std::array<ScratchVector<std::uint32_t>, 2> near;
    bool active = false;
  } contact_;
  void rebuild_contacts();
  void save_contact_start();
  std::size_t resolve_contacts();  // returns ContactStats::capped of the planes
  // Its steps for one body (world_contacts.cpp).
  void resolve_body_contacts(std::size_t k, PlaneTally& tally);
  static constexpr std::size_t near_split = 256;  ///< near bodies from which two threads share
  void find_near_planes();
  void resolve_near_planes(PlaneTally& tally);
  void near_block_of(std::size_t begin, std::size_t m, std::vector<std::uint32_t>& near);
  void push_out_of_surfaces(PlaneWay& w, double r, double rel);
  void follow_plane_impacts(PlaneWay& w, std::uint32_t j, double r, PlaneTally& tally);
  bool keep_bouncing(const PlaneWay& w, std::uint32_t j, const PlaneDef& hit, double first,
                     std::uint64_t tests, std::uint32_t segment, PlaneTally& tally);
  bool touch_at_tick_end(PlaneWay& w, plane_contact::V2 x1, plane_contact::V2 u1,
                         plane_contact::V2 offset, double r);
  void store_plane_way(std::size_t k, std::uint32_t j, PlaneWay& w, PlaneTally& tally);
  // Static segments (world_segments.cpp): the plane pass meets them as local planes.
  SegmentSet segments_;
  std::vector<std::uint32_t> segment_found_;  ///< a query's scratch
  /// Segments tested in this tick's plane pass, and the count at its last stop poll: the pass
  /// polls a stop request every plane_poll_tests tests (a disc may test every segment).
  std::uint64_t segment_tests_ = 0, polled_tests_ = 0;
  std::uint64_t plane_polls_ = 0;  ///< stop polls of the plane passes so far (plane_polls())
  /// Polls a stop request when plane_poll_tests segments were tested since the last poll.
  void poll_segment_work() {
    if (segment_tests_ - polled_tests_ < plane_poll_tests) return;
    polled_tests_ = segment_tests_, ++plane_polls_;
    throw_if_stop_requested();
  }
  /// Work of the moving segments on each body in this tick's plane pass, J/kg (dense order;
  /// empty while no segment moves): the resting solver's account of a disc takes it.
  std::vector<double> plane_work_;
  /// The deepest segment contact of a disc (x, y, m; radius r) at `time` (s into the tick)
  /// overlapping it by more than tol (m), as its local plane there (friction and restitution
  /// the segment's) and the segment's velocity u (m/s; 0 static); false: none. `start` is the
  /// disc's centre at the tick's start (m), for one-way segments (segment_acts).
  bool segment_overlap(double x, double y, double r, double tol, double time, Vec2 start,
                       PlaneDef& plane, Vec2& u);
  /// The first segment impact of a disc moving as m from `time` (s into the tick) over
  /// [0, horizon] (s), or infinity; plane gets the contact's local plane at that moment, u
  /// the segment's velocity, index the segment; `looked` the segments tested; `start` the
  /// disc's centre at the tick's start (m), for one-way segments (segment_acts).
  double first_segment_hit(const SegmentMotion& m, double time, double r, double horizon,
                           double rel, double vtol, Vec2 start, PlaneDef& plane, Vec2& u,
                           std::uint32_t& index, std::uint64_t& looked);
  /// Puts every segment a kinematic body carries where its body is, at its velocity.
  void place_segments();

  // Kinematic bodies, and static ones unless the free step skips them (AwakeRuns::on), by
  // dense index, and their start-of-tick states: after the integrator, a static body is put
  // back and a kinematic one moved on at its velocity, so nothing (forces, links, push) moves
  // them otherwise. Empty in a world of dynamic bodies.
  struct Immovable {
    std::vector<std::uint32_t> body;
    std::vector<Real> x0, y0, vx0, vy0;
    std::vector<Real> d0;  ///< sleepers' dissipated J/kg (ContactSettings::sleep, tracked)
  } immovable_;
  // Bodies with shapes (world_shapes.cpp; BodyDef::shapes), keyed by entity: their shapes,
  // centre of mass in the body frame (m), inertia about it (kg·m²; dynamic bodies), and their
  // angle θ (rad, in [-π, π]) and angular velocity ω (rad/s), each rounded to Real after every
  // tick. The shape world (their contacts) is null in a world without shapes.
  struct ShapeSet {
    std::vector<ShapeDef> defs;
    Vec2 center{};
    double inertia = 0.0;
    double angle = 0.0, spin = 0.0;
    double torque = 0.0;  ///< N·m: this tick's torque input (0 between ticks)
  };
  Store<ShapeSet> shape_sets_;
  ClonePtr<ShapeWorld> shape_world_;
  /// An automatic world's thread count for its shape phase, by trial (not state: the phase's
  /// bits are the same on either count).
  ThreadChoice shape_threads_;
  PreSolveFn pre_solve_ = nullptr;  ///< set_pre_solve: not state
  void* pre_solve_context_ = nullptr;
  // Character movers (world_movers.cpp; BodyDef::mover), keyed by entity: the definition, what
  // the last tick met (state: hashed, copied by snapshots) and where this tick leaves the body
  // (m); the obstacles near the one being moved and the slide's contacts (scratch).
  struct MoverRecord {
    MoverDef def;
    MoverState state;
    Vec2 target{};
  };
  Store<MoverRecord> movers_;
  ScratchVector<MoverObstacle> mover_obstacles_;
  ScratchVector<std::uint32_t> mover_segments_;
  MoverSlide mover_slide_;
  void check_mover(const BodyDef& def, const std::string& who) const;
  void move_movers();
  void move_mover(MoverRecord& m, Entity e);
  void place_movers();
  void finish_movers();
  [[nodiscard]] MoverGeometry mover_geometry(const MoverRecord& m, Entity e) const;
  void gather_mover_obstacles(std::size_t self, const Aabb& box, const CollisionFilter& filter,
                              const MoverGeometry& g, Vec2 start);
  void push_by_mover(const MoverContact& c, Vec2 velocity, double limit);
  void mover_outcome(MoverRecord& m, Vec2 v, Vec2 attempt, std::span<const MoverContact> cs);
  // Joints (world_joints.cpp), dense, keyed by Joint handles stored as Entity-shaped keys: each
  // one's record (definition, geometry, input, accumulated impulses: state) and handle; the
  // pairs of shape-world bodies they keep from colliding (rebuilt with the shapes); the
  // joints that broke in the last tick.
  SparseSet joints_;
  std::vector<std::uint32_t> joint_generations_, joint_free_slots_;
  std::vector<JointRecord> joint_records_;
  std::vector<Joint> joint_handles_;
  std::vector<std::uint64_t> joint_unpaired_;
  /// By shape-world body a: the first of joint_unpaired_'s pairs whose lower end is a or
  /// after (one entry more than the bodies: the last is their count).
  std::vector<std::uint32_t> joint_unpaired_start_;
  std::vector<JointBreak> joints_broken_;
  [[nodiscard]] std::size_t joint_index(Joint joint) const;
  [[nodiscard]] std::pair<Vec2, double> joint_end_pose(Entity e) const;
  [[nodiscard]] Vec2 local_center_or_zero(Entity e) const;
  void check_joint(const JointDef& def, const std::string& who) const;
  void check_joint_body(Entity e, const std::string& who, const char* field) const;
  void check_joint_ranges(const JointDef& def, const std::string& who) const;
  void wake_joint_bodies(const JointDef& def);
  void destroy_joints_of(Entity e);
  void rebuild_joints();
  void apply_joint_input(const JointInput& in);
  void break_joints();
  void check_shapes(const BodyDef& def, const std::string& who) const;
  void add_shapes(Entity e, const BodyDef& def, const std::string& who);
  void remove_shapes(Entity e);
  void apply_angular_input(const BodyInput& in, std::size_t j);
  void rebuild_shapes();
  void save_shape_start();
  void resolve_shapes();
  /// The shape phase's thread count this tick (shape_threads_: by trial in an automatic world).
  int shape_phase_threads();
  /// Makes the shape world's resting lists stale (shape_rest.hpp): whenever a static body or a
  /// sleeper may change (an edit, a body falling asleep or waking, a rebuild).
  void unsettle_shapes();
  /// Calls f(i) for each body of the shape world a tick gives its state: every one when the
  /// resting lists are stale, else the live ones (ShapeWorld::live).
  template <class F>
  void for_shape_bodies(F&& f);
  /// Calls f(record, index) for each joint of the last shape phase, not broken, in index
  /// order: every one when the resting lists are stale, else those with a live end
  /// (ShapeWorld::live_joints).
  template <class F>
  void for_shape_joints(F&& f);
  void shape_energies(std::vector<double>& out) const;
  void account_shape_contacts();
  // Disc-disc contacts (world_discs.cpp, disc_*.cpp); null without WorldSettings::contacts.
  ClonePtr<DiscContacts<Real>> discs_;
  void rebuild_discs();
  // Rolling discs (world_rolling.cpp; ContactSettings::rolling): θ (rad) and ω (rad/s) per
  // body in dense order, and 1/I (1/(kg·m²); 0 for a body that does not turn: no collider,
  // static or kinematic). All three are empty in a world without rolling.
  std::vector<Real> angle_, spin_;
  std::vector<double> inv_inertia_;
  bool rolling_ = false;
  /// A disc's moment of inertia about its centre, kg·m²: Collider::inertia, else ½ m r².
  static double inertia_of(double mass, const Collider& c) {
    return c.inertia ? *c.inertia : 0.5 * mass * c.radius * c.radius;
  }
  /// inv_inertia_ from the colliders (after a structural change).
  void rebuild_inertia();
  /// θ += ω dt for every body, wrapped into (-π, π] (semi-implicit: the tick's end ω).
  void integrate_angles();
  /// Saves the immovable bodies' start states, and the discs' when `discs` (their phases run).
  void save_tick_start(bool discs);
  void restore_immovable();
  void resolve_discs();
  /// Chooses the threads the disc phases may use this tick, into disc_count_:
  /// WorldSettings::threads (threads_for), and with 0 (automatic) from
  /// DiscContacts::min_parallel_discs awake discs by trial (disc_threads_: thread_choice.hpp),
  /// below on one (world_discs.cpp). Call once a tick, in a tick whose disc phases run, before
  /// resolve_discs() (which times the trial's ticks).
  void choose_disc_threads();
  int disc_count_ = 1;  ///< choose_disc_threads()'s count: this tick's, or the last that had one
  /// An automatic world's thread count for its disc phases, by trial (not state: the phases'
  /// bits are the same on either count).
  ThreadChoice disc_threads_;
  // Sleeping islands (world_sleep.cpp; ContactSettings::sleep). Per body in dense order: the
  // ticks it has stayed below the sleep speed (saturating) and its island's number while
  // asleep (0: awake); empty in a world without sleeping. A sleeping body is in the
  // immovable list (put back after the free step, as a static body) and a disc of infinite
  // mass to the disc phases until woken. Numbers come from next_island_, in the order the
  // islands fell asleep, so they are the same on every run.
  std::vector<std::uint32_t> still_ticks_, asleep_;
  std::uint32_t next_island_ = 1;
  std::uint32_t sleep_ticks_ = 0;               ///< ticks below the speed before an island sleeps
  std::size_t sleepers_ = 0;                    ///< bodies asleep
  std::size_t disc_sleepers_ = 0;               ///< discs among them
  std::size_t shape_sleepers_ = 0;              ///< bodies of shaped_dynamic_ among them
  bool sleep_ = false;                          ///< ContactSettings::sleep
  bool immovable_dirty_ = false;                ///< the immovable list misses a change of sleepers
  std::vector<std::int32_t> disc_of_;           ///< body -> disc index, or -1 (rebuild_discs)
  std::vector<std::uint32_t> kinematic_discs_;  ///< their bodies (rebuild_discs)
  std::size_t dynamic_discs_ = 0;               ///< dynamic discs (rebuild_discs)
  /// By body: 1 for a dynamic body with shapes (the shape world's bodies that are not discs),
  /// their count, and the shape world's kinematic bodies, discs among them (its indices), so
  /// that a world whose bodies with shapes all sleep is known without a pass over them
  /// (count_shaped_bodies; empty without sleeping).
  std::vector<std::uint8_t> shaped_dynamic_;
  std::size_t dynamic_shaped_ = 0;
  std::vector<std::uint32_t> kinematic_shaped_;
  /// Whether every disc sleeps or is static, or is kinematic and still: the disc phases have
  /// nothing to do.
  [[nodiscard]] bool discs_at_rest() const;
  /// Per sleeper, the next body of its island, round a ring through them all (update_sleep),
  /// so that waking an island visits its bodies only.
  std::vector<std::uint32_t> island_next_;
  /// Scratch of one tick: the union-find of the awake bodies (island_union.hpp), a body's
  /// entry read only when it is awake, and island_blocked_[j] == blocked_stamp_ for a body
  /// that keeps its island awake this time (a new stamp each time: no pass to clear them).
  std::vector<std::uint32_t> island_parent_, island_blocked_;
  std::uint32_t blocked_stamp_ = 0;
  /// Scratch of one tick: bodies whose islands wake (wake_labelled), and the bodies of a
  /// change (those woken, or those falling asleep).
  std::vector<std::uint32_t> wake_bodies_, flip_scratch_;
  std::size_t sleeper_contacts_ = 0;  ///< this tick's contacts with sleepers (ContactStats)
  std::size_t woken_ = 0;             ///< islands woken this tick (ContactStats)

  /// The awake bodies' runs (awake_runs.hpp), built with the immovable list.
  AwakeRuns awake_;
  /// update_awake_runs' scratch: the bodies flipped that woke and that slept, their
  /// colliders' slots, and the runs made.
  struct RunScratch {
    std::vector<std::uint32_t> woke, slept, woke_slots, slept_slots;
    std::vector<IndexRun> runs;
  } run_scratch_;
  /// Bodies the last free step and plane pass visited (ContactStats::free_stepped,
  /// plane_tested).
  std::size_t stepped_ = 0, plane_visited_ = 0;
  /// Whether the free step is the fused sweep, which can skip the sleepers (world_step.cpp).
  [[nodiscard]] bool fused_step() const { return net_.a.empty() && !settings_.track_dissipation; }
  /// Refuses (std::invalid_argument) sleep settings out of range; returns sleep_ticks_.
  static std::uint32_t sleep_ticks(const ContactSettings& c, double dt);
  /// Resizes the sleep state after a structural change: every island awake.
  void reset_sleep();
  /// The immovable list: kinematic bodies, and static ones and sleepers unless the free step
  /// skips them (AwakeRuns::on), and the awake runs.
  void rebuild_immovable();
  /// awake_ from asleep_ and the types (on: the passes skip the sleepers and the static bodies;
  /// off: the runs stay empty).
  void rebuild_awake_runs(bool on);
  /// Wakes the islands of bodies with input this tick (before the free step).
  void wake_for_input(const TickInput& input);
  /// Wakes the islands that an awake disc's motion over the tick may reach (after the free
  /// step, before the sleepers are put back: a woken body keeps its free step).
  void wake_near_movers();
  /// Wakes the islands a segment carried by a moving kinematic body may reach in the tick
  /// (before the free step).
  void wake_by_segments();
  /// Wakes the islands of the bodies in wake_bodies_ (then clears it), each round its ring:
  /// the cost of the bodies woken, in increasing order.
  void wake_labelled();
  /// Puts the body at dense index i in wake_bodies_ (false when it is awake).
  bool mark_awake(std::size_t index);
  /// Notes that body j fell asleep or woke (AwakeRuns::flipped).
  void flip_sleep(std::uint32_t j);
  /// Calls f(j) for every awake body j that is not static, in increasing order, and for some
  /// static ones: from the awake runs and the bodies flipped since, or else every body.
  template <class F>
  void for_each_awake_body(F&& f);
  /// The awake runs updated from the bodies flipped since they were built (rebuild_immovable).
  void update_awake_runs();
  /// After the tick: contacts with sleepers wake them; islands at rest fall asleep. `discs`:
  /// the disc phases ran this tick (their contacts are the tick's).
  void update_sleep(const TickInput& input, bool discs);
  // Bodies with shapes in the islands (world_shape_sleep.cpp).
  /// Each shaped body's `asleep` flag and masses in the shape world from asleep_.
  void mark_shape_sleepers();
  /// ShapeTick::wake: the islands of the sleepers the shape broadphase paired with a mover.
  static void wake_shape_sleepers(void* kernel);
  /// Still ticks of the awake dynamic bodies with shapes (speed, and rim speed ω · extent);
  /// true when one is ready to sleep.
  bool count_still_shapes(double speed2);
  /// The shape contacts' and pairs' part of join_islands.
  void join_shape_islands();
  /// Whether no body with shapes moves: every dynamic one asleep, every kinematic one still.
  [[nodiscard]] bool shapes_at_rest() const;
  /// Makes shaped_dynamic_, dynamic_shaped_ and kinematic_shaped_ (after rebuild_shapes, with
  /// every island awake).
  void count_shaped_bodies();
  /// Joins the tick's awake islands (island_parent_); island_blocked_[root] for an island that
  /// may not sleep.
  void join_islands();
  void fall_asleep(std::size_t j, std::uint32_t label);
  /// The next island number (never 0, which means awake).
  std::uint32_t take_island_number();
  /// The end of a tick whose every disc sleeps or is static: the disc phases are skipped, and
  /// the events say nothing began or ended.
  void quiet_discs();
  /// The sleeping islands after a tick (update_sleep when the disc phases ran) and their
  /// counts in contact_stats_.
  FIXSTEP_TICK_PHASE void finish_sleep(const TickInput& input, bool discs);
  /// A tick without disc phases: the last tick's pairs and sensor overlaps end
  /// (world_events.cpp).
  FIXSTEP_TICK_PHASE void end_disc_events();
  // Contact events (world_events.cpp): the touching pairs after the last tick, as handle pairs
  // sorted by slot; part of a snapshot, so events after a restore are the same. The pairs
  // before it and the hits are the tick's own (touching_before_ is swapped with touching_ as
  // the tick begins, hits_ cleared): a snapshot copies their sizes only.
  std::vector<ContactEvent> touching_;  // normal_speed unused
  /// The touching pairs whose bodies both sleep, sorted by slot, apart from touching_ (with
  /// it, the pairs touching after the last tick); stale once an island woke.
  std::vector<ContactEvent> asleep_touching_;
  bool asleep_pairs_stale_ = false;
  void set_asleep_pairs_apart();
  ScratchVector<ContactEvent> touching_before_, hits_;
  std::vector<ContactEvent> begun_, ended_;
  /// The second half's begun and ended pairs on two threads, appended to begun_ and ended_.
  ScratchVector<ContactEvent> begun_half_, ended_half_;
  std::vector<Impact> impacts_;            ///< the last tick's, by handle
  void update_contact_events(bool discs);  // discs: the disc phases ran this tick
  void add_disc_touching();
  void add_shape_touching();
  void diff_contact_events(bool touching_sorted);  // touching_ known sorted by slots
  /// Pairs of touching_ from which diff_contact_events goes by halves on the discs' second
  /// thread (when its run is open).
  static constexpr std::size_t events_split = 4096;
  void diff_touching(std::size_t now_begin, std::size_t now_end, std::size_t before_begin,
                     std::size_t before_end, std::vector<ContactEvent>& begun,
                     std::vector<ContactEvent>& ended) const;
  // Sensor events (world_sensors.cpp), kept like the contact events: part of a snapshot
  // (sensed_before_, swapped with sensed_ as the tick begins, only by its size).
  std::vector<SensorEvent> sensed_, sensor_crossed_;
  ScratchVector<SensorEvent> sensed_before_;
  std::vector<SensorEvent> sensor_begun_, sensor_ended_;
  void update_sensor_events(bool discs);
  /// Throws std::invalid_argument naming `who` when c is a sensor and the world has no disc
  /// contacts (WorldSettings::contacts), where no sensor would ever see anything.
  void check_sensor(const Collider& c, const std::string& who) const;
  // Per-body input (world_input.cpp): impulses and velocities at the tick's start; forces
  // added to the constant accelerations for the tick and taken off after it, exactly.
  struct SavedAccel {
    std::uint32_t body;
    Real ax, ay;    ///< coeff_.accel_x/y before
    double cx, cy;  ///< the implicit solver's, before
  };
  std::vector<SavedAccel> saved_accel_;
  bool saved_accel_flag_ = false;
  // Push in a network with static or kinematic bodies: folded into the dynamic bodies'
  // accelerations for the tick (restored after it), so no immovable end moves inside a tick.
  std::vector<Real> push_saved_;
  std::vector<double> push_saved_implicit_;
  bool push_saved_flag_ = false;
  void fold_push(Vec2 push);
  void unfold_push();
  void apply_body_inputs(const TickInput& input);
  bool add_input_forces(const TickInput& input);
  void remove_input_forces();
  ImplicitSolver<Real>& implicit_solver();  // built on first use (world_implicit.cpp)
  /// The implicit solver's constant accelerations cx, cy (m/s², body_count() each).
  std::pair<double*, double*> implicit_accelerations();
};

// --- component access (templates, so defined here) ---------------------------------------

template <class Real>
template <class C>
Store<C>& WorldKernel<Real>::store() {
  if constexpr (std::is_same_v<C, SpringDamper>)
    return springs_;
  else if constexpr (std::is_same_v<C, ConstantForce>)
    return constant_forces_;
  else if constexpr (std::is_same_v<C, Gravity>)
    return gravities_;
  else if constexpr (std::is_same_v<C, LinearDrag>)
    return drags_;
  else if constexpr (std::is_same_v<C, Collider>)
    return colliders_;
  else {
    static_assert(std::is_same_v<C, Appearance>, "not a fixstep component");
    return appearances_;
  }
}

template <class Real>
template <class C>
const Store<C>& WorldKernel<Real>::store() const {
  return const_cast<WorldKernel*>(this)->store<C>();
}

template <class Real>
template <class C>
void WorldKernel<Real>::set(Entity e, const C& component) {
  require(e);
  validate_component(component, describe(e));
  if constexpr (std::is_same_v<C, Collider>) check_sensor(component, describe(e));
  auto& s = store<C>();
  if (s.set.contains(e)) {
    s.data[s.set.index(e)] = component;
  } else {
    s.set.insert(e);
    s.data.push_back(component);
  }
  if constexpr (!std::is_same_v<C, Appearance>) terms_dirty_ = true;  // drawing only
}

template <class Real>
template <class C>
void WorldKernel<Real>::remove(Entity e) {
  require(e);
  auto& s = store<C>();
  if (!s.set.contains(e)) return;
  const std::size_t i = s.set.erase(e);
  s.data[i] = s.data.back();
  s.data.pop_back();
  if constexpr (!std::is_same_v<C, Appearance>) terms_dirty_ = true;  // drawing only
}

template <class Real>
template <class C>
const C* WorldKernel<Real>::get(Entity e) const {
  const auto& s = store<C>();
  return s.set.contains(e) ? &s.data[s.set.index(e)] : nullptr;
}

extern template class WorldKernel<float>;
extern template class WorldKernel<double>;

}  // namespace detail
}  // namespace fixstep
