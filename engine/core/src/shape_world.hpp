// Contacts of bodies with shapes (BodyDef::shapes): the kernel's shaped bodies, their
// broadphase, manifolds, continuous collision against what does not move, and the contact
// solver. Internal; WorldKernel owns one when a body has shapes (world_shapes.cpp).
//
// A tick, after the integrator has moved every body freely (world_tick.cpp):
//  1. each shaped body's angle moves on at its angular velocity, θ1 = θ0 + dt ω (a torque
//     input as a constant angular acceleration, world_shapes.cpp);
//  2. the broadphase (shape_broadphase.cpp: each shape's box at the tick's start, grown by the
//     speculative margin, 4 slops plus the distance its body's free motion can cover in the
//     tick, paired by the hierarchical grid of grid_broadphase.hpp, or below min_grid_shapes by
//     a sort and sweep on x) and the manifolds at the tick's start poses of each candidate pair, of
//     each shape with the planes and segments, and with the discs (bodies with a Collider):
//     speculative contacts (Catto 2013), points that may not yet touch; a pair of sharp
//     polygons whose relative pose has moved less than recycle_distance since its manifold was
//     made keeps that manifold, carried with the bodies (contact recycling, kept_manifold.hpp);
//  3. sequential impulses (Catto, GDC 2005: accumulated impulses clamped at zero, Coulomb
//     friction bounded by μ λ_n, a manifold's two normal impulses solved together, warm
//     starting from the last tick's impulses matched by feature ids) on the free end
//     velocities, the manifolds in colours of which no two move one body (shape_sweep.cpp),
//     with velocity targets: a gap s > 0 may close at s/dt, a touching point stops
//     approaching, one that meets faster than the restitution threshold bounces back (Newton's
//     law); the impulses move velocities only, and once they are done each body moves by dt
//     times its velocity change (as semi-implicit Euler's x1 = x0 + dt v1 would); each sweep
//     first solves the joints' rows (joint_solver.hpp), the point rows of the revolute joints
//     that form a forest all at once (joint_tree.hpp), and a sweep that moves nothing (no
//     contact, joints alone) ends the sweeps;
//  4. continuous collision for a body whose motion over the tick is more than half its
//     thinnest extent: moved back to its first touch of anything that does not move (planes,
//     segments, static bodies) it has no speculative point with, found by conservative
//     advancement (shape_distance.cpp), keeping its velocity: bounded, not exact — the rest of
//     that tick's motion is lost, and no shape passes through a static one;
//  5. the joints' error of the tick's motion removed (shape_joints.cpp), then the overlap left
//     beyond the slop pushed out on positions only (non-linear Gauss-Seidel, Box2D v2.4's
//     position solver, which adds no kinetic energy) with the joints' errors, until a sweep
//     moves nothing.
// Everything runs in one order (a colour's manifolds four at a time in the lanes of a vector,
// each lane as one alone; with two threads a large world's broadphase, manifolds and colours
// by halves, joined in that order): the same bits on any thread count, SIMD level and
// platform.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/pre_solve.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/step_results.hpp"
#include "grid_broadphase.hpp"
#include "joint_halves.hpp"
#include "joint_keep_search.hpp"
#include "joint_limit_rows.hpp"
#include "joint_limit_shifts.hpp"
#include "joint_point_rows.hpp"
#include "joint_tree.hpp"
#include "kept_manifold.hpp"
#include "one_way.hpp"
#include "rot_batch.hpp"
#include "second_thread.hpp"
#include "shape_fat_pairs.hpp"
#include "shape_geom.hpp"
#include "shape_lanes.hpp"
#include "shape_records.hpp"
#include "shape_rest.hpp"
#include "sweep_conjugate.hpp"

namespace fixstep::detail {

class JointSolver;

class ShapeWorld {
 public:
  /// Shapes from which the grid pairs them; below, sweep_few (its levels and tables cost a
  /// 20-box tower more than its whole sweep; from a 210-box pyramid on the two are even).
  static constexpr std::size_t min_grid_shapes = 128;
  /// A plane with a unit normal: n·x = offset (m) on its surface.
  struct UnitPlane {
    Vec2 n{};
    double offset = 0.0;
  };
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  /// Separation below which a point is pushed out (m): Box2D's linear slop.
  static constexpr double slop = 0.005;
  /// Passes of the impact pass a tick (ShapeWorld::impact_pass): a chain of bounces one body
  /// passes on to the next within a tick is followed this many links deep.
  static constexpr int max_impact_passes = 8;
  /// The shapes from which the broadphase and the manifolds are made by halves on two
  /// threads (ShapeTick::threads).
  static constexpr std::size_t min_split_shapes = 1024;
  /// The joints (broken ones too) from which a tick with two threads sweeps them by halves
  /// (joint_halves.hpp), where they make two.
  static constexpr std::size_t min_split_joints = 256;
  /// The manifolds of a colour from which its sweep is split over two threads: below, the
  /// hand-over costs about what the half saves.
  static constexpr std::uint32_t min_split_manifolds = 256;
  /// What a push-out sweep reads of a manifold point: its ShapeRow's bodies, normal, lever
  /// arms and separation, and its velocity row's normal mass, packed so that a sweep streams
  /// a fraction of the bytes of the two rows.
  struct PushRow {
    std::uint32_t a = 0, b = 0;
    Vec2 n{}, ra{}, rb{};
    double separation = 0.0, normal_mass = 0.0;
    /// The evaluation at which the row last found nothing to push, 0 when it pushed (or was
    /// not yet evaluated): while neither body has moved since, a sweep skips it.
    std::uint64_t idle = 0;
  };
  /// The push-out's rows by halves: each live movable body on one side of a line across the
  /// wider extent of their start positions, at their mean; a row whose movable bodies lie on
  /// one side goes to that half, the rest to the cut. From min_split_rows rows, when
  /// both halves have rows and the cut holds a quarter of them or fewer, each sweep pushes
  /// half 0's rows and half 1's (each in row order: on two threads at once, or one after the
  /// other), then the cut's: the same bits on one thread and two. Else the rows in row order.
  struct PushSplit {
    static constexpr std::uint8_t any = 3, no_side = 2;
    std::vector<std::uint8_t> side;     ///< per body: 0, 1, or no_side (not live this tick)
    std::vector<std::uint8_t> part;     ///< per row: 0, 1 (its half) or 2 (the cut)
    std::vector<PushRow> rows;          ///< the tick's: half 0's, half 1's, the cut's
    std::array<std::size_t, 2> ends{};  ///< where half 0's and half 1's end in rows
    /// The evaluations of rows counted over every sweep of every tick (row j of a sweep is its
    /// first + j), and per body the one that last moved it (PushRow::idle).
    std::uint64_t clock = 0;
    std::vector<std::uint64_t> moved_at;
    /// Whether idle rows are skipped (the same bits either way), and the evaluations skipped
    /// so far in half 0, half 1 and the cut (all in half 0 where not split).
    bool skip_idle = true;
    std::array<std::uint64_t, 3> skipped{};
    bool on = false;
  };
  /// The manifold points from which the push-out is split (PushSplit) and, with two
  /// threads, the rows are made by halves.
  static constexpr std::size_t min_split_rows = 2048;

  std::vector<ShapedBody> bodies_;
  std::vector<ShapeEntry> shapes_;
  std::vector<ShapeState> state_;
  std::vector<ShapeWarm> warm_;  ///< sorted by pair: last tick's impulses (state)
  /// Last tick's manifolds of pairs of sharp polygons (sharp()), in candidate order, each as it
  /// was made (state, which a snapshot copies): contact recycling (kept_manifold.hpp). The
  /// shapes' indices key them, so the kernel clears them whenever it rebuilds the shapes.
  std::vector<KeptManifold> kept_;
  /// How far a pair's bodies may move relative to one another before its manifold is made
  /// again (m): one slop, where Box2D v3.2 allows ten. A kept point's separation follows its
  /// two bodies, and one clipped on a tilted edge can differ from a fresh one's by up to the
  /// motion times the tilt's tangent: within the slop, the error a shape world accepts.
  static constexpr double recycle_distance = slop;
  /// Scratch of the energy account (world_shapes.cpp): each body's energy before and after the
  /// solve and the kinematic work on it (J).
  std::vector<double> energy_, energy_after_, work_;
  /// Each body's energy at the tick's start (before the free step, J) and its damping account
  /// then (J/kg), and whether the solve touched it (a contact row or a joint).
  std::vector<double> energy_start_, dissipated_start_;
  std::vector<std::uint8_t> touched_;

  /// One tick over `bodies_` with `state_` filled (start and free end); leaves the result in
  /// state_.
  ShapeTally solve(const ShapeTick& tick);
  /// The last tick's manifold points with their impulses (N·s).
  [[nodiscard]] std::span<const ShapeRow> rows() const { return rows_; }
  /// A sensor shape's body and a body it overlaps at the tick's end (bodies_ indices), in
  /// the broadphase's order; each pair once.
  struct Sensed {
    std::uint32_t sensor = 0, visitor = 0;
    friend bool operator==(const Sensed&, const Sensed&) = default;
  };
  [[nodiscard]] std::span<const Sensed> sensed() const { return sensed_; }
  /// The broadphase's pairs of shapes (shapes_ indices, a < b) whose boxes overlap, sorted.
  struct Candidate {
    std::uint32_t a, b;
  };
  [[nodiscard]] std::span<const Candidate> candidates() const { return candidates_; }
  /// Passes handed to the shape world's own second thread so far (SecondThread::handed();
  /// with disc contacts the shape phase hands its passes to the discs' instead).
  [[nodiscard]] std::uint64_t handed_passes() const { return second_.handed(); }
  /// Whether the last tick's broadphase and manifolds were made by halves on two threads.
  [[nodiscard]] bool halved() const { return halved_; }
  /// The colours of the last tick's velocity sweeps solved by halves on two threads (a colour
  /// once per sweep).
  [[nodiscard]] std::uint64_t split_colors() const { return split_colors_; }
  /// For the tests: the joints' passes run by halves on two threads (joint_halves.hpp) so far.
  [[nodiscard]] std::uint64_t halved_joint_passes() const { return halved_joint_passes_; }
  /// For the tests: the ticks whose shapes' pairs came from fat boxes made in an earlier tick
  /// (shape_fat_pairs.cpp; a copy counts from 0, an assigned world keeps its own count).
  [[nodiscard]] std::uint64_t fat_pair_ticks() const { return fat_.kept_ticks; }
  /// For the tests: of those, the ticks that refitted the fat boxes of some places.
  [[nodiscard]] std::uint64_t fat_refit_ticks() const { return fat_.refit_ticks; }
  /// For the tests: the refits stopped at the bound on their work so far.
  [[nodiscard]] std::uint64_t fat_refit_work_stops() const { return fat_.work_stops; }
  /// For the tests: the forest's steps that keep taken back so far, each halving and each
  /// step dropped after the last halving (joint_keep_search.hpp).
  [[nodiscard]] std::uint64_t kept_step_cuts() const { return keep_search_.cuts_made; }
  /// Whether the last tick swept its joints' rows packed (joint_limit_rows.hpp).
  [[nodiscard]] bool limit_rows_packed() const { return packed_limits_; }
  /// The last tick's push-out split.
  [[nodiscard]] const PushSplit& push_split() const { return push_split_; }
  /// Whether the push-out skips rows that would push nothing (PushRow::idle): on unless
  /// turned off to compare.
  void skip_idle_rows(bool on) { push_split_.skip_idle = on; }
  /// For the tests: the push-out's sweeps run by halves on two threads so far.
  [[nodiscard]] std::uint64_t split_pushes() const { return split_pushes_; }
  /// Stop requests polled by the sweeps so far: each velocity and position sweep polls once.
  [[nodiscard]] std::uint64_t stop_polls() const { return stop_polls_; }
  /// Heap bytes a copy holds (World::snapshot_bytes): every array's elements (shape_memory.cpp).
  [[nodiscard]] std::size_t bytes() const;
  /// The sleepers (bodies_ indices) the broadphase paired with a moving body this tick.
  [[nodiscard]] std::span<const std::uint32_t> woken() const { return wake_; }
  /// Makes the resting lists stale (shape_rest.hpp): the kernel's call whenever a body that
  /// the ticks leave alone may change (it falls asleep or wakes, an edit, a rebuild).
  void unsettle() { rest_.stale = true, rest_.whole = true; }
  /// Unsettles for kernel body `body` alone, which fell asleep, woke or had its position or
  /// velocity set (its own state alone changed): the next lists are made again from such
  /// bodies (ShapeRest::flipped, rebuild_flipped), unless something makes them stale whole.
  void unsettle_body(std::uint32_t body);
  /// Unsettles and forgets what each resting body's state was made into (ShapeRest::Key): the
  /// kernel's call when it rebuilds the bodies and shapes, whose indices may then name others.
  void reshape() { rest_.stale = true, rest_.forget(); }
  /// Whether the next tick makes the resting lists again: the kernel then gives every body its
  /// state, else the live ones.
  [[nodiscard]] bool rest_stale() const { return rest_.stale; }
  /// Whether stale lists are made from every body: the kernel then gives every body its state;
  /// else the live ones and the flipped ones (visit_few, ascending, each once; flipped).
  [[nodiscard]] bool rest_whole() const { return rest_.whole; }
  std::span<const std::uint32_t> visit_few();
  [[nodiscard]] std::span<const std::uint32_t> flipped() const { return rest_.flipped; }
  /// The bodies a tick visits (bodies_ indices, ascending; shape_rest.hpp), as the last tick
  /// left them: valid while !rest_stale().
  [[nodiscard]] std::span<const std::uint32_t> live() const { return rest_.live; }
  /// The joints a tick visits (ShapeTick::joints indices, ascending; those with a live end),
  /// as the last tick left them: valid while !rest_stale().
  [[nodiscard]] std::span<const std::uint32_t> live_joints() const { return rest_.live_joints; }
  /// The bodies the last tick visited: every one when it made the resting lists again, else
  /// the live ones.
  [[nodiscard]] std::size_t visited() const { return visited_; }
  /// The joints (not broken) the last tick's joint passes visited: those with a live end.
  [[nodiscard]] std::size_t joints_visited() const { return joints_visited_; }

 private:
  ShapeRest rest_;
  std::size_t visited_ = 0, joints_visited_ = 0;
  /// Makes the resting lists and the resting shapes' grid from state_ (every body's filled),
  /// and each resting body's rotations, margin, velocity and box.
  void rebuild_rest(double dt);
  void rebuild_whole(double dt);
  void rebuild_flipped(double dt);
  bool settle_body(std::uint32_t i, double dt);
  void rebuild_live_joints();
  /// Shape k's box at the tick's start grown by its body's margin_, its activity and its tag.
  void box_shape(std::uint32_t k);
  /// The pairs of the live shapes among themselves and with the resting ones into pairs_
  /// (false: a work limit reached, named in `tally`).
  bool pair_live(ShapeTally& tally, SecondThread* thread);
  /// never_pair of two live shapes by their places in rest_.live_shapes.
  static bool never_pair_live(const void* context, std::uint32_t a, std::uint32_t b);
  /// The pairs among the live shapes (`live`: places in live_shapes, into rest_.pairs) or
  /// among every shape (into pairs_), not vetoed, from the fat boxes, and the pairs vetoed into
  /// `vetoed`, as the grid would find them: false where the fat boxes do not hold (and are not
  /// made again) or a limit is passed (the grid or the sweep then finds the pairs).
  bool recycle_pairs(bool live, std::uint64_t most_pairs, std::uint64_t most_vetoed,
                     std::uint64_t& vetoed, std::vector<DiscPair>& out, SecondThread* thread);
  /// What recycle_pairs reads of the places it pairs: their boxes, activity, shapes and veto
  /// (shape_fat_pairs.cpp).
  struct FatPlaces;
  [[nodiscard]] FatPlaces fat_places(bool live) const;
  /// The fat boxes of `at` and their pairs made again (false: among few shapes, a body moves
  /// more than its fat margin in a tick; or the pairs pass `most_pairs`).
  bool make_fat_pairs(const FatPlaces& at, std::uint64_t most_pairs, SecondThread* thread);
  /// The fat boxes of the places in fat_.moved made again from `at` and their pairs found
  /// again (false: too many refitted since the fat boxes were made, a box not finite, or the
  /// pairs pass `most_pairs`; the fat boxes are then made again whole).
  bool refit_fat_pairs(const FatPlaces& at, std::uint64_t most_pairs);
  /// Place k's fat box: its box grown by FatBoxes::margin of its body's extent and reaching
  /// ShapeFatPairs::ahead_ticks of its body's motion ahead (a static body's: its box).
  [[nodiscard]] SweptBox fat_box(const FatPlaces& at, std::size_t k) const;
  ShapeFatPairs fat_;
  /// Fills `tally` with the broadphase's work limit `cap` reached.
  void name_cap(ShapeTally& tally, bool by_veto) const;
  std::vector<std::uint32_t> wake_;
  /// Awake and dynamic: what the solver moves.
  [[nodiscard]] bool awake(const ShapedBody& b) const {
    return b.type == BodyType::dynamic && !b.asleep;
  }
  /// Whether an impulse moves the body: a pass leaves the others' state as it is (a resting
  /// body's, shape_rest.hpp, from one tick to the next).
  [[nodiscard]] static bool movable(const ShapedBody& b) {
    return b.inv_mass > 0.0 || b.inv_inertia > 0.0;
  }
  /// Awake and dynamic, or kinematic and moving (turning or not): what wakes a sleeper.
  [[nodiscard]] bool moving(std::uint32_t body) const;
  /// Each shape's box at the tick's start, grown by its body's speculative margin (m).
  std::vector<SweptBox> boxes_;
  std::vector<std::uint8_t> dynamic_;  ///< per shape: its body is dynamic
  std::vector<DiscPair> pairs_;        ///< the grid's pairs, (a, b) order
  GridBroadphase grid_;
  std::vector<std::uint32_t> order_;  ///< sweep_few's: the shapes by their boxes' lower x
  std::vector<DiscPair> swept_;       ///< sweep_few's pairs as found
  std::vector<std::uint32_t> first_;  ///< order_pairs' scratch
  void sweep_few();
  /// What the broadphase's filter reads of a shape and its body this tick.
  struct PairTag {
    static constexpr std::uint32_t sensor = 1, disc = 2, awake = 4, asleep = 8, moving = 16;
    CollisionFilter filter;
    std::uint32_t owner = 0;
    std::uint32_t flags = 0;
  };
  std::vector<PairTag> tags_;
  /// Whether shape `mover`'s body wakes shape `sleeper`'s (asleep, the other moving).
  static bool wakes(const PairTag& mover, const PairTag& sleeper) {
    return (sleeper.flags & PairTag::asleep) != 0 && (mover.flags & PairTag::moving) != 0;
  }
  static bool never_pair(const void* context, std::uint32_t a, std::uint32_t b);
  [[nodiscard]] std::uint32_t largest_box() const;
  std::vector<Candidate> candidates_;
  std::vector<UnitPlane> unit_planes_;        ///< this tick's planes, their normals made unit
  std::vector<Candidate> sensor_candidates_;  ///< a: the sensor shape
  std::vector<Sensed> sensed_;
  std::vector<ShapeRow> rows_;
  std::vector<ShapeSolveRow> solve_;  ///< rows_' velocity rows, in the same order
  /// Each body's velocity through the velocity solve (prepare_rows copies it in; the solve's
  /// impulses move it alone, and follow_velocities moves the poses by its change and copies
  /// it out): a sweep reads 24 bytes a body.
  std::vector<ShapeMotion> velocity_;
  std::vector<double> turned_at_;  ///< solve_positions' scratch
  /// The pair keys (as ShapeRow::pair) of the manifolds a one-way rule or the pre-solve hook
  /// disabled this tick, sorted: continuous collision leaves them alone as it does a row's.
  std::vector<std::uint64_t> disabled_;
  /// For the continuous check, made at the tick's first fast body: the rows' pair keys sorted
  /// (what a fast body already has a row with).
  std::vector<std::uint64_t> row_keys_;
  std::vector<std::uint32_t> near_segments_;  ///< near_segments' answer
  std::vector<std::uint32_t> near_statics_;   ///< static_shapes_near's answer
  std::vector<ShapeWarm> next_warm_;
  std::vector<double> margin_;                     ///< each body's speculative margin this tick, m
  double dt_ = 0.0;                                ///< this tick's dt (s), set as solve() begins
  std::span<JointRecord> joints_;                  ///< this tick's (ShapeTick::joints)
  JointBodies joint_bodies_;                       ///< the live joints' bodies, numbered
  JointTree tree_;                                 ///< the joints' direct solve
  std::span<const std::uint64_t> unpaired_;        ///< this tick's (ShapeTick::unpaired)
  std::span<const std::uint32_t> unpaired_start_;  ///< (ShapeTick::unpaired_start)

  [[nodiscard]] Pose pose(std::uint32_t body) const;
  [[nodiscard]] Pose start_pose(std::uint32_t body) const;
  [[nodiscard]] double margin(std::uint32_t body, double dt) const;
  void continuous(const ShapeTick& tick, ShapeTally& tally);
  double first_static_touch(std::uint32_t body, const ShapeTick& tick);
  [[nodiscard]] bool has_row(std::uint64_t pair) const;
  /// The indices of the tick's segments whose boxes may meet `box`, ascending.
  std::span<const std::uint32_t> near_segments(const ShapeTick& tick, const Aabb& box);
  /// The static bodies' shapes whose boxes may meet `box`, in body order, then shape order.
  std::span<const std::uint32_t> static_shapes_near(const Aabb& box);
  /// Pairs the shapes (false: a work limit reached, named in `tally`); by halves of the
  /// boxes on `thread` when given (the same candidates, in the same order).
  bool broadphase(double dt, ShapeTally& tally, SecondThread* thread);
  /// The manifolds of the candidates, the planes and the segments into rows_; the
  /// candidates' by halves on `thread` when given.
  void collect(const ShapeTick& tick, SecondThread* thread);
  /// The manifolds of an awake body's shape k with the planes and segments into rows_.
  void collect_surfaces(const ShapeTick& tick, std::uint32_t k);
  void collect_pairs(const ShapeTick& tick, std::size_t begin, std::size_t end,
                     std::vector<ShapeRow>& rows, std::vector<std::uint64_t>& disabled,
                     std::vector<KeptManifold>& kept);
  std::vector<ShapeRow> half_rows_;
  std::vector<std::uint64_t> half_disabled_;
  std::vector<KeptManifold> next_kept_, half_kept_;
  /// Whether a pair's manifold may be kept (contact recycling) for this shape: a polygon
  /// without rounding, not one-way. A round shape's normal passes through its core, which a
  /// kept normal no longer does once the pair has moved (a disc, which does not turn, would
  /// then take a torque it cannot: the elastic gas's angular momentum drifted by 4e-6 of
  /// itself); a one-way shape's rule is read from each tick's manifold.
  [[nodiscard]] static bool sharp(const ShapeEntry& e) {
    return e.convex.count >= 3 && e.convex.radius == 0.0 && !e.one_way;
  }
  /// A candidate's shapes as one key, a << 32 | b: KeptManifold::pair, in candidate order.
  [[nodiscard]] static std::uint64_t index_pair(const Candidate& c) {
    return std::uint64_t{c.a} << 32 | c.b;
  }
  bool halved_ = false;
  /// Whether manifold m between shapes_[a] and shapes_[b] (a may be `none`: a plane or
  /// segment, `surface` its index) acts this tick: the one-way rule of each one-way shape
  /// (one_way.hpp; `segment_up` the up of a one-way segment A, else null) and then the
  /// pre-solve hook (shape_one_way.cpp).
  [[nodiscard]] bool contact_acts(const ShapeTick& tick, const Manifold& m, std::uint32_t a,
                                  std::uint32_t b, int plane, int segment,
                                  const Vec2* segment_up) const;
  /// Whether continuous collision stops a fast body at its first touch of a one-way shape or
  /// segment of world up `up` (m: their manifold at the touch): the touch's normal leans up.
  [[nodiscard]] static bool one_way_touch(const Manifold& m, Vec2 up) {
    return m.count > 0 && dot(m.normal, up) > one_way_min_dot;
  }
  /// Returns the change of the two bodies' relative turning rate it made (rad/s).
  double solve_rolling(ShapeRow& r, double normal_impulse);
  void turn(const ShapeRow& r, double l);  ///< an angular impulse l on B, −l on A
  void add_manifold(std::vector<ShapeRow>& rows, const Manifold& m, std::uint32_t a,
                    std::uint32_t b, double friction, double restitution, double rolling,
                    std::uint64_t pair);
  /// The velocity rows from the manifold points (each row's own by halves on `thread` from
  /// min_split_rows), the impact pass, then the warm start.
  void prepare_rows(const ShapeTick& tick, SecondThread* thread);
  /// The velocities of a row's two bodies (A's zero for a plane or segment), as a sweep
  /// carries them through a manifold's rows; store() writes them back.
  struct Motion2 {
    ShapeMotion a, b;
  };
  [[nodiscard]] Motion2 load(const ShapeSolveRow& h) const {
    Motion2 m;
    if (h.a != none) m.a = velocity_[h.a];
    m.b = velocity_[h.b];
    return m;
  }
  /// Writes back the bodies an impulse moves (not a static, kinematic or asleep one, whose
  /// velocity it leaves as it was: two threads may read one such body in one colour).
  void store(const ShapeSolveRow& h, const Motion2& m) {
    if (h.a != none && (h.ma > 0.0 || h.ia > 0.0)) velocity_[h.a] = m.a;
    if (h.mb > 0.0 || h.ib > 0.0) velocity_[h.b] = m.b;
  }
  // apply, normal_velocity, tangent_velocity and make_solve_row are defined in
  // shape_solver.cpp, the one file that calls them, and inlined into its loops.
  /// Impulses pn along n and pt along t (N·s) on B, their opposite on A: velocities only.
  inline void apply(const ShapeSolveRow& h, double pn, double pt);
  /// B's velocity relative to A's at the row's point, along n and along t (m/s).
  [[nodiscard]] inline double normal_velocity(const ShapeSolveRow& h) const;
  [[nodiscard]] inline double tangent_velocity(const ShapeSolveRow& h) const;
  /// Makes `h` the row of `r` for the velocity solve, every field (its target and flags left
  /// zero for prepare_rows and prepare_blocks).
  inline void make_solve_row(const ShapeRow& r, ShapeSolveRow& h) const;
  /// After the velocity solve: each pose moved by dt times its body's velocity change in it
  /// (semi-implicit Euler's x1 = x0 + dt v1, once, for every impulse of the solve), and the
  /// velocities written back to state_.
  void follow_velocities();
  /// The velocity sweeps (shape_sweep.cpp): the joints' rows, then the contacts' colour by
  /// colour, each colour's blocks and one-point manifolds four at a time (shape_lanes.hpp) and
  /// the rest one at a time; the colours that split (ColorRun::splits) by halves on `second`
  /// when given. The sweeps end at tick.velocity_iterations, or at the first that has
  /// converged: its joints moved nothing and no contact row changed its own velocity by more
  /// than velocity_sweep_tolerance. Returns the sweeps run.
  int solve_velocities(const ShapeTick& tick, SecondThread* second);
  /// m/s (rad/s for a turning rate): the largest change of a contact row's velocity in a sweep
  /// that has converged (the joints' rows and forest keep direct_velocity_tolerance). A
  /// hundredth of a millimetre a second: a tick of 1/60 s moves a point 0.2 µm by it, well
  /// within the push-out's 5 mm slop, where 1e-9 m/s ran every sweep of a stack still
  /// settling (docs/perf/contact_solver_plan.md, "Where the sweeps end").
  static constexpr double velocity_sweep_tolerance = 1e-5;
  /// A manifold: its first row in solve_ and its rows (1 or 2).
  struct Unit {
    std::uint32_t start = 0, rows = 1;
  };
  /// A manifold and its colour: no two manifolds of one colour move the same body.
  struct ColoredUnit {
    Unit unit;
    std::uint32_t color = 0;
    std::uint8_t kind = 0;  ///< its place in the colour (shape_colors.cpp): block, point, unit
  };
  /// Whether row i + 1 is the second point of row i's manifold (the same pair and bodies).
  [[nodiscard]] bool pairs_next(std::size_t i) const {
    return i + 1 < rows_.size() && rows_[i + 1].pair == rows_[i].pair &&
           rows_[i + 1].a == rows_[i].a && rows_[i + 1].b == rows_[i].b;
  }
  /// The end of each colour that has manifolds in block_lanes_, point_lanes_ and units_.
  struct ColorRun {
    std::uint32_t blocks_end = 0, points_end = 0, units_end = 0;
    /// Whether two threads may solve it by halves: min_split_manifolds or more, and not the
    /// overflow colour (whose manifolds may move one body).
    bool splits = false;
  };
  std::vector<std::uint64_t> body_colors_;  ///< the colours each body's manifolds took
  std::vector<ColoredUnit> colored_;
  std::vector<std::uint32_t> by_color_;               ///< colored_ sorted by colour
  std::vector<shape_lanes::BlockLanes> block_lanes_;  ///< each colour's blocks, four a group
  std::vector<shape_lanes::PointLanes> point_lanes_;  ///< and its one-point manifolds
  std::vector<Unit> units_;                           ///< and the rest, one at a time
  std::vector<ColorRun> color_runs_;
  /// Each colour's manifolds by kind (block lanes, point lanes, units), counted as coloured.
  std::vector<std::array<std::uint32_t, 3>> color_kinds_;
  /// A colour that has manifolds: its manifolds in by_color_ [first, end), where its groups and
  /// units start, its units but a lone block or point, and whether it has one of each.
  struct ColorPlace {
    std::uint32_t first = 0, end = 0;
    ColorRun start;
    std::uint32_t units = 0;
    bool lone_block = false, lone_point = false;
  };
  std::vector<ColorPlace> color_places_;
  SecondThread second_;  ///< the shape world's own, when the discs' is not running
  std::uint64_t split_colors_ = 0;
  /// One sweep of the colour from `from` to `run` (ColorRun ends), on `thread` by halves when
  /// given. Returns the largest change of a row's own velocity its impulse made (m/s, rad/s).
  double sweep_color(const ColorRun& from, const ColorRun& run, SimdLevel level,
                     SecondThread* thread);
  void color_manifolds();
  /// color_places_ and color_runs_ from color_kinds_.
  void place_colors();
  /// The colours' groups and units, by halves of the colours on `thread` when given.
  void pack_lanes(SecondThread* thread);
  void pack_color(std::size_t k, std::uint32_t zero);
  /// The lanes' impulses back into solve_, then solve_'s into rows_: by halves on `thread`
  /// when given.
  void unpack_lanes(SecondThread* thread);
  /// One manifold's rows; returns the largest change of a row's own velocity (m/s, rad/s).
  double solve_unit(Unit u);
  /// The velocity sweeps' conjugate steps (sweep_conjugate.hpp, shape_conjugate.cpp).
  SweepConjugate conjugate_;
  /// Each lane's and unit's impulses and each live body's velocity, as the warm start left
  /// them, as the first sweep's start.
  void start_conjugate(SecondThread* thread);
  /// The step after a sweep whose largest change of a row's own velocity was `change` (m/s,
  /// rad/s), the tick's first when `first`; by halves on `thread` when given.
  void step_conjugate(double change, bool first, SecondThread* thread);
  template <SweepConjugate::Mode M>
  void step_conjugate_as(double beta, SecondThread* thread);
  /// The slot of velocity_ past the bodies', always zero, that lanes read for a plane's or
  /// segment's A and for a padding lane.
  [[nodiscard]] std::uint32_t zero_slot() const {
    return static_cast<std::uint32_t>(state_.size());
  }
  /// f(k) for each live body k, by halves of the live list on `thread` when given: f may touch
  /// only body k's own state.
  template <class F>
  void each_live(SecondThread* thread, F&& f) {
    const std::span<const std::uint32_t> live = rest_.live;
    run_halves(thread, live.size(), [&](std::size_t begin, std::size_t end, int /*half*/) {
      for (std::size_t j = begin; j < end; ++j) f(live[j]);
    });
  }
  /// store(k, rot_of(angle(k))) for every live body k, by halves as each_live, the rotations
  /// made in batches (rot_batch.hpp: the same bits).
  template <class Angle, class Store>
  void rot_each_live(SecondThread* thread, Angle&& angle, Store&& store) {
    const std::span<const std::uint32_t> live = rest_.live;
    run_halves(thread, live.size(), [&](std::size_t begin, std::size_t end, int /*half*/) {
      rot_of_each(live.subspan(begin, end - begin), angle, store);
    });
  }
  /// The joints' warm start, velocity sweep, position sweep and account (joint_solver.hpp).
  void prepare_joints();
  /// Each returns whether its sweep moved anything (the velocity sweep's own rows: a body's
  /// velocity by more than velocity_sweep_tolerance).
  bool solve_joint_velocities();
  bool solve_joint_positions(bool keep);
  /// The joints by halves (joint_halves.hpp): from min_split_joints joints, when the tick has
  /// a second thread (joint_thread_) and the joints make two halves, each joint pass runs
  /// job(0) and job(1) on the two threads; else job(JointTree::whole) here. A part's passes
  /// see its joints (for_joints, in joint order) and its members of the forest.
  template <class Job>
  void run_joint_parts(Job& job) {
    if (joints_halved_) {
      joint_thread_->both(job);
      ++halved_joint_passes_;
    } else {
      job(JointTree::whole);
    }
  }
  template <class F>
  void for_joints(int part, F&& f) {
    if (part == JointTree::whole) {
      for (const std::uint32_t i : rest_.live_joints) {
        if (!joints_[i].broken) f(joints_[i]);
      }
      return;
    }
    for (const std::uint32_t i : halves_.joints(part)) f(joints_[i]);
  }
  JointHalves halves_;
  bool joints_halved_ = false;
  SecondThread* joint_thread_ = nullptr;
  std::uint64_t halved_joint_passes_ = 0;
  bool joint_rows_ = false;  ///< some joint has velocity rows of its own this tick
  /// Every joint's velocity rows this tick are packed limit rows (joint_limit_rows.hpp), made
  /// by prepare_joints for this tick alone (they point into the tick's joints).
  bool packed_limits_ = false;
  JointLimitRows limit_rows_;
  /// The same worlds' limit corrections on positions, packed with them (joint_limit_shifts.hpp).
  JointLimitShifts limit_shifts_;
  /// The forest's point rows, packed by prepare_joints for this tick alone (joint_point_rows.hpp).
  JointPointRows point_rows_;
  bool indirect_ = false;       ///< some joint is not all in the forest
  bool direct_limits_ = false;  ///< some joint of the forest has a limit
  bool rest_factored_ = false;  ///< the forest factored for this tick's sweeps on positions
  std::vector<Rot> turned_;     ///< solve_tree_positions' scratch: each forest body's rotation
  /// solve_tree_positions' scratch: each member's arms at the poses now (m).
  std::vector<std::array<Vec2, 2>> fresh_arms_;
  /// Whether each member's bodies turned more than fast_joint_turn by the sweeps that keep.
  std::vector<std::uint8_t> fast_;
  /// Whether each tree of the forest has an error over its tolerance in the last measure
  /// (velocity or position): a tree within it is left as it is, each tree by itself (a
  /// settled island stops sweeping while a moving one goes on).
  std::vector<std::uint8_t> tree_active_;
  void clear_active(int part);
  void kick(JointSolver& solver, std::size_t k, Vec2 p);
  /// The sweeps that keep as a line search (joint_keep_search.hpp), in a tick where no joint
  /// outside the forest holds a forest body (searches_, set by prepare_joints): such a
  /// joint's rows correct its bodies in the same sweeps, and a step taken back would undo
  /// that, so one turns the search off for the whole world.
  JointKeepSearch keep_search_;
  bool searches_ = false;
  [[nodiscard]] bool in_forest(std::uint32_t body) const;  ///< a body index or JointRecord::none
  void give_kept_step(int part);
  bool cut_kept_step();
  /// After the sweeps that keep: the step still waiting given (its error was not measured).
  void end_keeping();
  /// The largest point error the forest's last step on positions in this phase started from
  /// (m; no_step: none to check), and the phase: keeping or not.
  static constexpr double no_step = std::numeric_limits<double>::infinity();
  double step_error_ = no_step;
  bool step_keeps_ = false;
  /// What measure_tree_errors found: the largest point error (m), the largest limit
  /// correction (rad), whether a member's angle row came or went, and whether any has one.
  struct TreeErrors {
    double error = 0.0, past_limit = 0.0;
    bool rows_changed = false, any_row = false;
  };
  TreeErrors measure_tree_errors(bool keep, const JointSolver& solver, int part);
  /// The forest's step on positions from the errors measured (solve_tree_positions' step).
  bool step_tree_positions(bool keep, const TreeErrors& now);
  void poll_stop();  ///< throw_if_stop_requested, counted in stop_polls_
  std::uint64_t stop_polls_ = 0;
  void account_joints();
  /// Whether a joint keeps the shapes of these two bodies from colliding.
  [[nodiscard]] bool unpaired(std::uint32_t a, std::uint32_t b) const;
  bool impact_pass(const ShapeTick& tick);
  bool bounce(std::size_t i, const ShapeTick& tick);
  bool bounce_block(std::size_t i, const ShapeTick& tick);
  /// The two-point manifolds' blocks of rows [begin, end), which start and end between two
  /// manifolds.
  void prepare_blocks(std::size_t begin, std::size_t end);
  /// The push-out (shape_push_out.cpp): sweeps over the rows until one moves nothing, on
  /// `second` by halves where push_split_ is on.
  void solve_positions(const ShapeTick& tick, SecondThread* second, ShapeTally& tally);
  struct Pusher;  ///< one row's push (shape_push_out.cpp)
  PushSplit push_split_;
  std::uint64_t split_pushes_ = 0;
  void split_push_out(SecondThread* thread);
  /// push_split_.rows from rows_ and solve_: in row order, or by halves where split.
  void make_push_rows(SecondThread* thread);
  /// push_split_.rows[from, to) (of `part`: a half or the cut) pushed in that order, row j as
  /// evaluation first + j; whether any pushed.
  bool push_rows(std::size_t from, std::size_t to, std::uint64_t first, int part);
  /// One sweep of the push-out (by halves on `thread` when given); whether any row pushed.
  bool push_sweep(SecondThread* thread);
  /// Each live body's turn since the start made again where its angle changed (by halves of
  /// the live list on `thread` when given).
  void update_turns(SecondThread* thread);
  void keep_impulses();
  void detect_sensors();
};

}  // namespace fixstep::detail
