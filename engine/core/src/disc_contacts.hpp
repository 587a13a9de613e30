// Body-vs-body contacts of discs (WorldSettings::contacts): the state and scratch a World keeps
// for them, and the two phases of a tick. Internal to the engine: not installed.
//
// A tick first integrates every body as if no disc touched another (world_step.cpp) and
// resolves contacts with planes (world_contacts.cpp). Then, for the discs:
//  1. Impacts at their time (disc_events.cpp). Each disc's start state (x0, v0) and end state
//     (x1, v1) define a motion of constant acceleration a = (v1 - v0)/dt through both end
//     positions, as for planes: x(s) = x0 + u s + ½ a s², u = v0 + δ, with the integrator's
//     velocity the model's minus δ = (x1 - x0)/dt - (v0 + v1)/2 (exact for free flight and
//     gravity). A disc that met a plane or a segment in the plane pass moves so until its first
//     plane event, and from there on that pass's motion after its last one, unless an impact
//     changes its motion first; a disc whose motion an impact changes meets the walls on its new
//     path among the impacts (disc_walls.cpp). A broadphase pairs the discs whose boxes swept over
//     the tick overlap; each pair's first contact is the first root of the quartic |d(s)|² - (r_a +
//     r_b)² while approaching (disc_toi.hpp). Impacts are resolved in time order (ties by pair
//     order) with Newton's restitution and a Coulomb-limited friction impulse on the linear
//     velocities, and the pairs of the two discs are predicted again from that time on. A disc an
//     impact sends beyond its swept box has the pairs of its new path added within the tick
//     (disc_reach.cpp), so that no contact is missed. Where fast discs cross a crowd (the boxes
//     over the whole tick overlap in more than crowded_pairs pairs a disc), the impacts run over
//     up to max_windows equal windows of the tick in turn, each paired by the boxes over it
//     (disc_windows.cpp). Past max_impacts impacts of either disc in
//     the tick, a pair with e < 1 that would end the tick overlapping is handed to the resting
//     solver, which stops it approaching (e = 0, the limit of inelastic collapse: with e < 1 three
//     or more discs can collide infinitely often in finite time, McNamara & Young, Phys. Fluids A
//     4, 496 (1992); a packed pile's first tick does). If its centres would cross by then, or it
//     would end deeper than hold_depth radii (more than the push-out can part the right way), its
//     discs are instead held where they meet for the rest of the tick, keeping their velocities for
//     the resting solver (they lose the rest of the tick's motion, as Box2D v3's b2SolveContinuous
//     drops a fast body's step after its time of impact); a disc that then meets a held one below
//     its cap bounces off it as off an immovable disc, and past its cap is held too. Every other
//     impact is resolved: a pair that would pass through, and every elastic one (e = 1 gives
//     finitely many collisions). The predictions after impacts count against max_tick_predictions
//     (limits.hpp): past it the tick stops resolving impacts and reports the cap through cap_hit().
//     An impact that would bounce back by less than one tick of the pair's relative normal
//     acceleration (e |v_n| <= |c_n| dt) is left to phase 2.
//  2. Resting contact (disc_gather.cpp, disc_rest.cpp). Pairs touching at the end of the tick, and
//  discs on
//     planes, are solved together by sequential impulses (Gauss–Seidel, warm-started from the
//     last tick's impulses) so that no pair approaches; each impulse acts as a constant
//     contact force over the tick, so it moves the positions by κ dt Δv, κ being how far the
//     integrator moves a body under a constant force per unit of velocity it gives (½ for
//     velocity Verlet, RK4 and Forest–Ruth; (n+1)/2n for semi-implicit and implicit Euler at
//     n substeps; (n-1)/2n for explicit Euler). A stack at rest is then held exactly by the
//     integrator's own step. An overlap left beyond the slop is pushed out along the normal
//     to half the slop (positions only, split by inverse mass, at most max_push_out of the
//     radius a sweep; an overlap within push_out_tolerance of the slop is left: rounding).
// With rolling discs (ContactSettings::rolling) friction, in impacts and at rest, acts on the
// slip at the contact point, (v_a - v_b)·t - ω_a r_a - ω_b r_b (t = (-n_y, n_x)), with the
// tangential mass 1 / (1/m_a + 1/m_b + r_a²/I_a + r_b²/I_b), and its impulse λ t on a turns a by
// -r_a λ / I_a and b by -r_b λ / I_b (Catto's friction with angular terms, for discs): an
// impact changes no angular momentum about any point (its arms r_a, r_b add up to the distance
// at the time of impact).
// Static discs never move; kinematic discs move at their velocity; both act as infinite mass.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "disc_caches.hpp"
#include "disc_paths.hpp"
#include "disc_records.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "gather_warm.hpp"
#include "grid_broadphase.hpp"
#include "grown_grid.hpp"
#include "impact_lane.hpp"
#include "scratch_vector.hpp"
#include "world_kernel.hpp"

namespace fixstep::detail {

struct RestSweep;  // disc_rest.cpp

template <class Real>
class DiscContacts {
 public:
  /// Replaces the disc set (after a structural change); `linked` holds the keys a << 32 | b
  /// (a < b, disc indices) of linked pairs, sorted; `filters` each disc's filter, or nothing
  /// when every disc has the default filter and none is a sensor (no pair is then looked at
  /// twice). Forgets the warm-start impulses.
  void rebuild(std::vector<Disc> discs, std::vector<std::uint64_t> linked,
               std::vector<CollisionFilter> filters, const ContactSettings& settings);
  [[nodiscard]] bool active() const { return !discs_.empty(); }
  [[nodiscard]] std::span<const Disc> discs() const { return discs_; }
  /// Per-tick constant accelerations of the discs' bodies (energy account), m/s².
  void set_accelerations(std::span<const Real> ax, std::span<const Real> ay);

  /// Saves the start-of-tick states of the discs, and their dissipated energy per unit mass
  /// (J/kg; null when the world keeps no account).
  void save_start(const Real* x, const Real* y, const Real* vx, const Real* vy,
                  const Real* dissipated);
  /// Saves the start-of-tick angular velocities (rad/s) of rolling discs (energy account).
  void save_spin_start(const Real* spin);
  /// Disc k sleeps (ContactSettings::sleep): it acts as a static disc, of infinite mass and
  /// at rest, and the broadphase pairs it with no other sleeper; or wakes, with its body's
  /// 1/m (1/kg) and, with rolling discs, 1/I (1/(kg·m²)).
  /// A disc woken within a tick (by Tick::wake) takes part in the rest of it from rest.
  void set_asleep(std::uint32_t k, bool asleep, double inv_mass, double inv_inertia) {
    Disc& d = discs_[k];
    d.dynamic = dynamic_[k] = asleep ? 0 : 1;
    d.inv_mass = asleep ? 0.0 : inv_mass;
    d.inv_inertia = asleep ? 0.0 : inv_inertia;
    if (asleep_[k] == (asleep ? 1 : 0)) return;
    asleep_[k] = asleep ? 1 : 0;
    fat_.valid = false;  // its pairs change (a sleeper pairs with no other)
    sleeper_count_ = asleep ? sleeper_count_ + 1 : sleeper_count_ - 1;
    awake_dirty_ = true;
    awake_flips_.flip(k, discs_.size());
    if (asleep) {
      sleepers_.fell_asleep(k);
    } else {
      sleepers_.woke(k);
    }
    if (!asleep && waking_) woken_.push_back(k);
  }
  /// The discs not asleep, in index order (every disc when none sleeps).
  std::span<const std::uint32_t> awake();
  /// Calls found(k) for each sleeping disc k whose box at rest (its disc padded as the
  /// broadphase pads it, at its position in x, y: m, dense body order) may overlap b (m): a
  /// superset, from a grid of the sleepers (SleeperGrid) and those that fell asleep since it
  /// was built.
  template <class Found>
  void for_each_sleeper_near(const Real* x, const Real* y, const SweptBox& b, Found&& found);
  /// Calls f(k) for each disc k the last resolve() visited, in index order: every disc, or
  /// with sleepers and few discs awake, the awake ones and the sleepers next to them
  /// (disc_live.cpp). The others' lost() and external() are 0 and their states untouched.
  template <class F>
  void each_live(F&& f) const {
    if (live_all_) {
      for (std::uint32_t k = 0; k < discs_.size(); ++k) f(k);
    } else {
      for (const std::uint32_t k : live_) f(k);
    }
  }
  /// How many discs the last resolve() visited (ContactStats::disc_visited).
  [[nodiscard]] std::size_t live_count() const { return live_all_ ? discs_.size() : live_.size(); }
  /// Each disc's swept box over the tick, as the broadphase pairs them (the motion from the
  /// start state to the end state, padded by the radius and twice the slop), grown
  /// over its path where an impact sent it beyond (disc_reach.cpp), m.
  [[nodiscard]] std::span<const SweptBox> boxes() const { return boxes_; }
  /// The last resolve()'s candidate pairs (swept boxes overlapping; linked, filtered-out and
  /// sensor pairs dropped), by disc index.
  [[nodiscard]] std::span<const DiscPair> candidate_pairs() const { return pairs_; }
  /// Whether discs k and l may collide (their filters; true without filters).
  [[nodiscard]] bool may_collide(std::uint32_t k, std::uint32_t l) const {
    return filters_.empty() || should_collide(filters_[k], filters_[l]);
  }
  /// The discs' start-of-tick positions and velocities (save_start()), m and m/s.
  [[nodiscard]] std::span<const Real> start_x() const { return x0_; }
  [[nodiscard]] std::span<const Real> start_y() const { return y0_; }
  [[nodiscard]] std::span<const Real> start_vx() const { return vx0_; }
  [[nodiscard]] std::span<const Real> start_vy() const { return vy0_; }

  struct Tick {
    Real *x, *y, *vx, *vy;   ///< the world's state arrays (dense body order)
    const Real* dissipated;  ///< J/kg per body so far (null: no account)
    std::span<const PlaneDef> planes;
    std::span<const PlaneMotion> after;  ///< plane colliders' motions after a plane impact
    std::span<const double> after_t;     ///< their times, s (< 0: none this tick)
    double dt = 0, kappa = 0.5;          ///< s; κ (see above)
    int threads = 1;
    const SegmentSet* segments = nullptr;  ///< static segments (null: none); contacts with
                                           ///< them are the plane contacts' b past the planes
    Real* spin = nullptr;  ///< angular velocities, rad/s, with rolling discs (null: none)
    /// Work the plane pass's moving segments did on each body this tick, J/kg (dense body
    /// order; null: none moves): in the account of a disc measured from the tick's start.
    const double* plane_work = nullptr;
    /// Called once the discs' motions and swept boxes are known, before the broadphase pairs
    /// them (null: not called): sleeping islands that a box reaches wake there, so that what
    /// the broadphase would pair with a sleeper is woken first (world_sleep.cpp).
    void (*wake)(void* context) = nullptr;
    void* wake_context = nullptr;
  };
  /// Resolves the tick's contacts in place. Returns per-disc energy bookkeeping through
  /// lost() (J/kg, dynamic discs) and external() (J); fills stats.
  void resolve(const Tick& tick, ContactStats& stats, StepProfile& profile);
  /// Energy the last resolve() took from each disc, J/kg (index: disc).
  [[nodiscard]] std::span<const double> lost() const { return lost_; }
  /// Work of kinematic discs on each disc in the last resolve(), J.
  [[nodiscard]] std::span<const double> external() const { return external_; }
  /// The contacts of the last resolve() (touching pairs; b >= discs().size() for a plane, as
  /// b - discs().size()), disc pairs in (a, b) order.
  [[nodiscard]] std::span<const RestContact> touching() const { return contacts_; }
  /// How many of touching()'s contacts, the first ones, are disc pairs (the rest: planes and
  /// segments).
  [[nodiscard]] std::size_t disc_pair_contacts() const { return plane_contacts_; }
  /// The dense body indices of touching()'s disc pairs (the first disc_pair_contacts()), in
  /// its order: the contact events and the sleeping islands read 8 bytes a pair here, not a
  /// whole RestContact and the discs' records.
  [[nodiscard]] std::span<const DiscPair> touching_bodies() const { return touching_bodies_; }
  /// The discs (disc indices, as touching()'s a) of touching()'s contacts with a segment that
  /// moves this tick, one per such contact.
  [[nodiscard]] std::span<const std::uint32_t> on_moving_segment() const {
    return on_moving_segment_;
  }
  /// Whether the tick's run of the second thread is open (SecondThreadRun): halves() and
  /// both_halves() then run their halves on two threads.
  [[nodiscard]] bool sharing() const { return broadphase_.second_thread().is_open(); }
  /// Runs pass(begin, end, half) over [0, n): as two halves (0 and 1) on two threads when
  /// the tick's run of the second thread is open (SecondThreadRun), else as one (half 0) here. For
  /// passes whose items are independent (one disc, one pair): the same result either way.
  template <class Pass>
  void halves(std::size_t n, Pass&& pass) {
    run_halves(sharing() ? &broadphase_.second_thread() : nullptr, n, pass);
  }
  /// halves() from `least` items; below, pass(0, n, 0) here (a pass too small to pay for the
  /// hand-off to the second thread).
  template <class Pass>
  void halves_from(std::size_t n, std::size_t least, Pass&& pass) {
    if (n < least) {
      pass(std::size_t{0}, n, 0);
      return;
    }
    halves(n, pass);
  }
  /// Runs job(0) and job(1): on two threads when the tick's run of the second thread is open,
  /// else one after the other here. For jobs that write nothing the other reads or writes.
  template <class Job>
  void both_halves(Job& job) {
    if (!sharing()) {
      job(0), job(1);
      return;
    }
    broadphase_.second_thread().both(job);
  }
  /// For the tests: the ticks whose impacts ran in two lanes, those whose lanes met and ran
  /// again in one, and those that cut the discs into lanes at all (disc_lanes.cpp), since the
  /// discs were set.
  [[nodiscard]] std::uint64_t lane_ticks() const { return lane_ticks_; }
  [[nodiscard]] std::uint64_t lanes_undone() const { return lanes_undone_; }
  [[nodiscard]] std::uint64_t lane_cuts() const { return lane_cuts_; }
  /// For the tests: the fat boxes' pairs (disc_fat.cpp) while the tick's pairs come from
  /// them, else 0.
  [[nodiscard]] std::size_t fat_pairs() const { return fat_.valid ? fat_.pairs.size() : 0; }
  /// For the tests: the resting contacts' cuts into two halves (cut_pile()) since the discs
  /// were set, before the gather or after it.
  [[nodiscard]] std::uint64_t pile_cuts() const { return pile_cuts_; }
  /// The impacts of the last resolve(), in order.
  [[nodiscard]] std::span<const DiscImpact> impacts() const { return lanes_[0].log; }
  /// The sensors' overlaps after the last resolve(), by (sensor, visitor) disc pair order.
  [[nodiscard]] std::span<const SensorOverlap> sensed() const { return sensed_; }
  /// Impacts of a disc in a tick past which its inelastic pairs that end the tick overlapping
  /// are left to the resting solver.
  static constexpr int max_impacts = 8;
  /// Depth, as a fraction of the smaller radius, past which a pair handed to the resting solver
  /// at the end of the tick has its discs held where they meet instead (see past_cap()).
  static constexpr double hold_depth = 1.5;
  /// A cap of limits.hpp that the last resolve() reached, or null: the work it stopped is
  /// named in World::fault().
  struct CapHit {
    const char* cap = nullptr;   ///< "max_candidate_pairs", "max_vetoed_pairs" or
                                 ///< "max_tick_predictions"
    std::uint64_t limit = 0;     ///< the cap's value for this world
    std::uint32_t disc = 0;      ///< the impact's first disc, or the largest swept box's
    std::uint32_t other = npos;  ///< the impact's other disc (npos: none)
    double time = 0;             ///< s after the tick's start (the impact left unresolved)
    static constexpr std::uint32_t npos = 0xffffffffu;
  };
  [[nodiscard]] const CapHit* cap_hit() const { return cap_.cap ? &cap_ : nullptr; }
  /// Heap bytes a copy holds (World::snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

  /// Contacts from which the resting solver splits them into two halves (split_contacts()),
  /// which run on two threads within the tick's run of the second thread; and from which two
  /// threads match the contacts' warm impulses by halves (match_warm()).
  static constexpr std::size_t min_split_contacts = 1024;
  /// Candidate pairs from which two threads share the first impact predictions, within the
  /// tick's run of the second thread.
  static constexpr std::size_t min_parallel_pairs = 128;
  /// Candidate pairs from which two threads gather the touching contacts (gather_contacts()):
  /// each half tests its pairs, then writes its contacts after the first half's, two hand-offs
  /// that a few hundred pairs do not pay for (a gas of 10^3 discs: about 190 pairs; see
  /// docs/perf/contact_solver_plan.md, "The gas's hand-offs at 10^3").
  static constexpr std::size_t min_parallel_gather = 512;
  /// Candidate pairs from which a tick's impacts may run in two lanes (disc_lanes.cpp), within
  /// the tick's run of the second thread. A gas of 10^3 discs has about 190 (measured in
  /// docs/perf/contact_solver_plan.md, "The impact lanes from 128 pairs").
  static constexpr std::size_t min_lane_pairs = 128;
  /// Items from which a pass that only copies each one's values (the tick's start: save_start(),
  /// the plane contacts' start) or marks (the discs the resting rows moved) shares them with
  /// the second thread: below, the hand-off costs about what the half saves.
  static constexpr std::size_t min_parallel_copies = 8192;
  /// Discs from which a tick with two threads shares its passes with the second thread,
  /// which spins between them (SecondThread::open) rather than waking for each; below, every
  /// pass runs on the stepping thread.
  static constexpr std::size_t min_parallel_discs = 256;
  /// The discs a tick steps: the awake ones (all of them when none sleeps).
  [[nodiscard]] std::size_t busy() const { return discs_.size() - sleeper_count_; }
  /// The second thread a tick on `threads` threads shares its passes with (SecondThreadRun
  /// keeps it spinning through them), or null: one thread, or fewer than min_parallel_discs
  /// busy discs (busy()).
  [[nodiscard]] SecondThread* second_thread(int threads) {
    return threads >= 2 && busy() >= min_parallel_discs ? &broadphase_.second_thread() : nullptr;
  }
  /// Passes handed to the second thread so far (SecondThread::handed()).
  [[nodiscard]] std::uint64_t handed_passes() const { return broadphase_.second_thread().handed(); }
  /// For the tests: whether a second thread was ever started (a tick shared its passes).
  [[nodiscard]] bool second_thread_started() const {
    return broadphase_.second_thread().team() != nullptr;
  }
  /// The threads the broadphase may split a call over: the tick's within its run of the second
  /// thread, else 1 (outside a run each hand-over would wake the worker by futex, which costs
  /// more than the halves save below thousands of boxes; with sleepers the broadphase may see
  /// more discs than the awake ones that open the run).
  [[nodiscard]] int pass_threads(const Tick& tick) { return sharing() ? tick.threads : 1; }
  /// A tick with sleepers visits only the live discs (each_live()) when at most this share of
  /// the discs is awake, else every disc: both give the same states.
  static constexpr std::size_t live_share = 4;
  /// Candidate pairs a disc over the whole tick past which the tick's impacts run in windows
  /// (a pile has about 3, a gas a few radii a tick up to about 10).
  static constexpr std::size_t crowded_pairs = 16;
  /// Most windows a tick's impacts run over.
  static constexpr int max_windows = 64;
  /// Radii the fastest disc moves at most in one window (unless max_windows bounds them).
  static constexpr double window_radii = 4.0;
  /// Overlap left alone, as a fraction of the smaller radius (Box2D's linear slop).
  static constexpr double slop = 0.005;
  /// True when a disc of radius r (m) centred at (x, y) (m) touches plane p within the slop:
  /// a resting contact with it.
  static bool on_plane(const PlaneDef& p, double x, double y, double r) {
    return !(p.normal.x * x + p.normal.y * y - p.offset - r > slop * r);
  }
  /// How far a disc's box reaches beyond its centre's path: its radius and twice the slop of
  /// it, m (so that pairs within the slop are candidates).
  static double box_pad(const Disc& d) { return d.radius * (1.0 + 2.0 * slop); }
  /// Largest push-out of one pair in one sweep, as a fraction of the smaller radius.
  static constexpr double max_push_out = 0.2;
  /// Overlap beyond the slop that the push-out leaves, as a fraction of the smaller radius: a
  /// pile pushed out to the slop stays within rounding of it, and without this margin those
  /// rounding-sized overlaps kept every push-out iteration busy on a pile at rest.
  static constexpr double push_out_tolerance = 1e-6;
  /// Where the push-out leaves an overlap it pushes, as a fraction of the slop: half of it, so
  /// that a pushed pair has room before it is pushed again. Pushed to the slop itself, a
  /// settling pile's pairs were pushed back and forth for some 200 ticks (every push deepens
  /// the neighbours' overlaps), the contacts' normals turned with them, and the velocity
  /// iterations ran to their bound on every one of those ticks; with the room, the 5 cm pile
  /// of 10³–10⁵ discs comes to rest (one sweep of each a tick) by tick 40
  /// (docs/perf/contact_solver_plan.md).
  static constexpr double push_target = 0.5;

 private:
  // the discs a tick visits (disc_live.cpp)
  /// Runs f(k) over live positions [begin, end) of the tick's discs (each_live()'s order).
  template <class F>
  void live_range(std::size_t begin, std::size_t end, F&& f) const {
    if (live_all_) {
      for (std::size_t k = begin; k < end; ++k) f(static_cast<std::uint32_t>(k));
    } else {
      for (std::size_t i = begin; i < end; ++i) f(live_[i]);
    }
  }
  /// Whether this tick visits the live discs only: with sleepers and few discs awake.
  [[nodiscard]] bool live_only() const {
    return sleeper_count_ != 0 && awake_list_.size() * live_share <= discs_.size();
  }
  /// Starts the tick's live list: the awake discs (save_start() saved them).
  void begin_live();
  /// Disc k, not yet live, joins the tick: its start state is its state now (a sleeper's, or a
  /// disc woken this tick: at rest where it slept), its motion and box built.
  void add_live(const Tick& tick, std::uint32_t k);
  /// The discs woken by Tick::wake, then the sleepers whose boxes overlap a dynamic live
  /// disc's: what the broadphase would pair with them.
  void add_woken_and_near(const Tick& tick);
  /// Calls found(k) for each sleeper k, not live, whose box may overlap b (a superset).
  template <class Found>
  void sleepers_near(const Tick& tick, const SweptBox& b, Found&& found);
  /// The live list in index order (after add_live()).
  void sort_live();
  /// The grid of the sleepers where they sleep (x, y: the bodies' positions, m).
  void build_sleeper_grid(const Real* x, const Real* y);
  /// The live discs' boxes and dynamic flags in live order (the broadphase's input in
  /// live_only() ticks); pairs it finds are mapped back by live_[i].
  void gather_live_boxes(std::span<const SweptBox> boxes);
  // phase 1 (disc_events.cpp)
  void build_motions(const Tick& tick);
  /// Discs [begin, end)'s motions and boxes; those the plane pass bounced go onto `bounced`.
  void build_motions(const Tick& tick, std::size_t begin, std::size_t end,
                     ScratchVector<std::uint32_t>& bounced);
  /// The swept box of a disc the plane pass bounced (p, its state at time t, s), on its free
  /// motion `free` until its first plane event and on p's motion from then on, padded by `pad`
  /// (m).
  static void plane_box(const PlaneMotion& p, double t, const DiscMotion& free, double pad,
                        double dt, SweptBox& b);
  /// Disc k, which the plane pass bounced, takes that pass's motion after its last plane event
  /// (its first plane event came before any disc impact changed its free motion).
  void switch_to_plane_motion(const Tick& tick, std::uint32_t k);
  /// The candidate pairs of boxes_ into pairs_ (and their CSR lists): false past max_pairs
  /// (past max_candidate_pairs the cap is recorded in cap_ and stats; below it, a try).
  /// whole_tick: boxes_ are the whole tick's (not a window's), and the pairs may be recycled
  /// from the fat boxes (disc_fat.cpp).
  bool find_candidates(const Tick& tick, ContactStats& stats, std::size_t max_pairs,
                       bool whole_tick);
  /// Each live disc's list of its pairs_ (offset_, degree_, incident_), in pair order; by
  /// halves of the pairs on two threads from min_parallel_copies pairs.
  void incident_lists();
  // candidate pairs recycled from fat boxes (disc_fat.cpp)
  /// pairs_ from the fat boxes' pairs, rebuilt when a box left its fat box: 1 found, 0 past
  /// max_pairs, -1 not used (the fat pairs past cap, or resting after a rebuild that lasted
  /// one tick): the caller runs the broadphase on the boxes.
  int recycled_pairs(int threads, std::size_t max_pairs, std::size_t cap);
  /// The broadphase's grid of the fat boxes again (after a copy, whose broadphase has none).
  void rebuild_fat_grid(int threads);
  /// Disc j's box as the broadphase paired it (before reach() grew it), m.
  [[nodiscard]] const SweptBox& paired_box(const ImpactLane& q, std::uint32_t j) const {
    return grown_of_[j] == GrownBox::none ? boxes_[j] : q.grown[grown_of_[j]].first;
  }
  // windows of the tick (disc_windows.cpp)
  /// How many windows the tick's disc impacts run over: 1 when the swept boxes over the whole
  /// tick overlap in at most crowded_pairs pairs a disc or the discs move too little for windows
  /// to part them (pairs_ then found), else motion_windows(); 0 past max_candidate_pairs.
  int tick_windows(const Tick& tick, ContactStats& stats);
  /// Windows that keep the fastest disc's motion in each within window_radii of its radius,
  /// 1 to max_windows.
  [[nodiscard]] int motion_windows() const;
  /// Each disc's box over [t0, t1] (s) on its motion now (a disc the plane pass bounced, still on
  /// its free motion: that until its first plane event, then the plane pass's motion), padded
  /// as the tick's boxes are.
  void window_boxes(const Tick& tick, double t0, double t1);
  /// Drops from pairs_ the linked pairs and the pairs filters reject, and moves the sensor
  /// pairs (one sensor, one not) to sensor_pairs_ (disc_sensors.cpp).
  void sort_out_pairs();
  /// Fills sensed_ from sensor_pairs_ at the tick's end state (disc_sensors.cpp).
  void detect_sensors(const Tick& tick);
  /// Phase 1 over `windows` equal windows of the tick in turn (each with its own pairs when more
  /// than one), then each changed disc's end state.
  void run_events(const Tick& tick, ContactStats& stats, int windows);
  [[nodiscard]] std::uint32_t largest_box() const;
  /// What becomes of a pair's impact due at `now` (s): resolved (both discs below
  /// max_impacts, e = 1, or the pair would pass through), left to the resting solver (it ends
  /// the tick overlapping), or its discs held where they meet (it would end the tick with its
  /// centres crossed, or deeper than hold_depth, or a disc of it that met a wall in the tick
  /// would end it clear of every wall, or one is held already).
  enum class PastCap { impact, rest, hold };
  [[nodiscard]] PastCap past_cap(const Tick& tick, std::uint32_t pair, double now);
  /// True when disc k, on its motion, ends the tick touching a plane or a segment (within the
  /// slop, as the resting solver gathers its wall contacts), m.
  [[nodiscard]] bool ends_on_a_wall(const Tick& tick, std::uint32_t k);
  /// Pushes pair's next impact after `now` (s) onto q's event queue, if it has one this tick.
  void predict(ImpactLane& q, std::uint32_t pair, double now, double dt);
  /// The pair's next impact after `now` into out; false when it has none this tick.
  bool next_event(std::uint32_t pair, double now, double dt, DiscEvent& out) const;
  /// The event queue filled with every pair's first impact (two threads share the pairs within
  /// the tick's run of the second thread when there are min_parallel_pairs or more).
  void first_events(const Tick& tick, double from);
  /// Resolves q's events up to horizon_ in time order; false once q.budget.cap stopped it
  /// (cap_ and stats record it), or, in one of two lanes, where it met the other (q.met).
  bool run_window(ImpactLane& q, const Tick& tick, ContactStats& stats);
  /// The cap reached at `now` (s) before the impact of a and b (b = npos: a's wall): cap_ and
  /// stats record it, or, in one of two lanes, the lanes meet. False.
  bool over_budget(ImpactLane& q, ContactStats& stats, std::uint32_t a, std::uint32_t b,
                   double now);
  /// The tick's impacts in lane 0 over `windows` windows.
  void run_lane(const Tick& tick, ContactStats& stats, int windows);
  // the impacts in two lanes (disc_lanes.cpp)
  /// The tick's impacts in two lanes on two threads; false where they did not run or met (the
  /// motions then as at the tick's start, for run_lane()).
  bool run_lanes(const Tick& tick, ContactStats& stats);
  [[nodiscard]] bool lanes_may_run(const Tick& tick);
  /// lane_of_ for every disc; false when a lane would hold a quarter of the pairs or less.
  bool assign_lanes();
  /// Disc k's centre at the tick's start on `axis` (0: x, 1: y), m.
  [[nodiscard]] double centre(std::uint32_t k, int axis) const;
  /// f(k) for each disc k the plane pass bounced this tick (bounced_, as build_motions() listed
  /// them).
  template <class F>
  void each_bounced(F&& f) const {
    for (const auto& list : bounced_) {
      for (const std::uint32_t k : list) f(k);
    }
  }
  /// Disc k's switch, at its first plane event, to the motion the plane pass bounced it onto.
  [[nodiscard]] DiscEvent switch_of(const Tick& tick, std::uint32_t k) const {
    return DiscEvent{tick.after[discs_[k].plane_slot].first, switch_event | k, stamp_[k], 0};
  }
  /// Disc k's lane in a split tick: its group's (lane_of_), or, in no pair, its own side.
  [[nodiscard]] std::uint8_t lane(std::uint32_t k) const {
    return degree_[k] != 0 ? lane_of_[k] : (centre(k, lane_axis_) >= lane_cut_ ? 1 : 0);
  }
  void start_lanes(const Tick& tick);
  /// q's first events: its pairs' and its bounced discs' (as first_events()).
  void first_lane_events(ImpactLane& q, const Tick& tick);
  /// Whether either lane stopped where it met the other (read while they run).
  [[nodiscard]] bool lanes_met();
  /// q stops: it met the other lane, and the other stops at its next event. False.
  bool meet_other_lane(ImpactLane& q);
  /// After both ran: their bands against the other's grown boxes, and the one lane's count of
  /// predictions bounded against the cap; lanes_[0].met where either fails.
  void check_lanes();
  /// An upper bound of what one lane would have counted against max_tick_predictions.
  [[nodiscard]] std::uint64_t one_lane_count() const;
  /// Both lanes' impact logs into lane 0's, by time; false at a tie between them.
  bool merge_lane_logs();
  void merge_lanes(ContactStats& stats);
  /// Back to the motions at the tick's start after lanes that met.
  void undo_lanes(const Tick& tick);
  /// A tick the lanes did not pay for (they met, or one lane would hold nearly every pair):
  /// after four in a row the lanes rest for 16 ticks, doubling up to 64.
  void rest_lanes();
  /// The lanes' held discs, extra pairs and grown boxes forgotten.
  void forget_lanes();
  void end_lanes();
  void impact(ImpactLane& q, std::uint32_t pair, double now, double dt);
  // within a tick: pairs for a disc an impact sends beyond its box (disc_reach.cpp)
  /// Forgets the last tick's extra pairs and grown boxes; the pairs found so far are the base.
  void start_reach(ImpactLane& q);
  /// Disc k's motion from `now` (s) to the tick's end (dt, s): if it leaves k's box, the box
  /// grows over it and the discs that piece may meet become new pairs, predicted from now.
  /// Returns the work done, in units of a box test (a prediction counts 16).
  /// Within a live_only() tick, the sleepers that piece reaches join the tick.
  std::uint64_t reach(ImpactLane& q, const Tick& tick, std::uint32_t k, double now, double dt);
  /// Whether a pair of discs k, j may collide at all: not both immovable, not kept apart by
  /// their filters, neither a sensor, not linked.
  [[nodiscard]] bool may_pair(std::uint32_t k, std::uint32_t j) const;
  /// Puts pairs_ back in (a, b) order once extra pairs were added.
  void finish_reach();
  /// q's next partner mark for reach().
  std::uint32_t next_mark(ImpactLane& q);
  /// Pair p as q's next extra pair, linked to both discs; its index, or ExtraPair::none where
  /// a lane's slots ran out (the lanes meet).
  std::uint32_t add_extra_pair(ImpactLane& q, DiscPair p);
  /// Holds the dynamic discs of a pair past the cap that would end the tick overlapping where
  /// they are at `now` (s) for the rest of the tick, keeping their velocities for the resting
  /// solver; how many it held (0 when a partner is kinematic, or both are held already or were
  /// released by a kinematic disc in the tick).
  std::size_t hold_pair(ImpactLane& q, std::uint32_t pair, double now);
  /// Puts held disc k back on its motion from where it was held (a kinematic disc meets it).
  void release(std::uint32_t k);
  // walls within the impacts (disc_walls.cpp)
  /// Disc k's first impact with a plane or a segment after `now` (s) on its motion, into out
  /// (a wall event, see DiscEvent); false when it has none this tick. `looked` counts the walls
  /// tested.
  bool next_wall_event(const Tick& tick, std::uint32_t k, double now, double dt, DiscEvent& out,
                       std::uint64_t& looked);
  /// Pushes disc k's next wall event after `now` (s) onto the event queue, if it has one: a
  /// disc the plane pass met (Disc::plane_slot), not held.
  void predict_wall(ImpactLane& q, const Tick& tick, std::uint32_t k, double now, double dt,
                    std::uint64_t& looked);
  /// Wall `wall` (DiscEvent::stamp_b) as the plane disc k meets at `now` (s), moving at u (m/s;
  /// a segment's local plane at its closest feature); false when the ghost-vertex rule gives
  /// that feature to a neighbour.
  bool wall_plane(const Tick& tick, std::uint32_t k, std::uint32_t wall, double now,
                  PlaneDef& plane, Vec2& u) const;
  enum class WallOutcome { none, impact, held };
  /// Disc k's impact with wall `wall` at `now` (s), resolved as the plane pass resolves it, or,
  /// past max_impacts, the disc held where it meets an inelastic wall it would end the tick in.
  WallOutcome wall_impact(ImpactLane& q, const Tick& tick, std::uint32_t k, std::uint32_t wall,
                          double now);
  /// Disc k's pairs' and extra pairs' next events after `now` (s); adds the work to `again`.
  void predict_pairs(ImpactLane& q, std::uint32_t k, double now, double dt, std::uint64_t& again);
  /// After disc k's motion changed at `now` (s): predict_pairs(), the pairs of its path beyond
  /// its box, and its walls' next event; adds the work to `again`.
  void predict_after(ImpactLane& q, const Tick& tick, std::uint32_t k, double now,
                     std::uint64_t& again);
  /// The broadphase's pairs of `boxes` into out, without the linked and filtered-out pairs;
  /// false past max_candidate_pairs (or max_vetoed_pairs dropped).
  bool pairs_of(std::span<const SweptBox> boxes, std::vector<DiscPair>& out, int threads,
                std::size_t cap);
  /// pairs_of() over boxes with their dynamic flags as given (a live_only() tick's: live
  /// positions, which the veto maps back).
  bool pairs_of_boxes(std::span<const SweptBox> boxes, std::span<const std::uint8_t> dynamic,
                      std::vector<DiscPair>& out, int threads, std::size_t cap);
  // phase 2 (disc_gather.cpp, then disc_rest.cpp)
  void gather_contacts(const Tick& tick);
  /// Whether candidate pair p touches at the tick's end as a resting contact (within the slop,
  /// and not an impact of the next tick), and if so its contact into *out (when not null); in
  /// a large world (gather_warm.hpp) with the last tick's impulses as its warm start (warm()).
  /// warm_at: where in warm_ the last pair asked looked (warm_from()).
  bool pair_contact(const Tick& tick, const DiscPair& p, RestContact* out,
                    const WarmImpulse*& warm_at) const;
  /// Pair p's impulses of the last tick's resting solver, or null when it had no normal
  /// impulse, looked up in warm_'s disc pairs from `at` on (a walk for pairs in key order),
  /// which it moves to p.
  [[nodiscard]] const WarmImpulse* warm(const DiscPair& p, const WarmImpulse*& at) const;
  /// warm()'s normal impulse (N·s), or 0.
  [[nodiscard]] double last_impulse(const DiscPair& p, const WarmImpulse*& at) const {
    const WarmImpulse* const w = warm(p, at);
    return w != nullptr ? w->lambda_n : 0.0;
  }
  /// Where in warm_'s disc pairs pair i's key is, or would be.
  [[nodiscard]] const WarmImpulse* warm_from(std::size_t i) const;
  /// Disc k's resting contact with a plane or segment b (b past the discs) along its normal
  /// (nx, ny), friction μ: its key, radii, masses and, with rolling discs, its turn.
  [[nodiscard]] RestContact wall_contact(std::uint32_t k, std::uint32_t b, double nx, double ny,
                                         double friction) const;
  /// Appends dynamic disc k's contacts with the planes (within the slop) to out, in plane order.
  void plane_contacts_of(const Tick& tick, std::uint32_t k, std::vector<RestContact>& out) const;
  static constexpr std::size_t wall_block = 64;  ///< discs plane_contacts_in tests at once
  void plane_contacts_in(const Tick& tick, std::size_t begin, std::size_t end,
                         std::vector<RestContact>& out) const;
  /// Splits contacts_ into two halves of the discs and the contacts across the cut: order_
  /// lists them part by part (key order within a part), part_start_[p] where part p begins
  /// (disc_halves.cpp). Below min_split_contacts everything is part 0.
  void split_contacts(ContactStats& stats);
  /// The cut between the halves: the axis along which the live dynamic discs spread the most
  /// and their median coordinate along it (cut_along_y_, median_); false when one is NaN.
  bool cut_pile();
  /// Makes the cut before the gather (cut_state_) in a large world (warm_gathered_), so that
  /// gather_contacts() finds each pair's part (part_) while the contact is in the cache.
  void cut_before_gather();
  /// A disc's side of the cut (side_): below the median, not below it, or not moved by the
  /// solver (static, kinematic).
  static constexpr std::uint8_t side_low = 0, side_high = 1, side_none = 2;
  /// The part of a contact between discs on sides a and b (b side_none for a plane or a
  /// segment): the half of the discs it moves, or 2 when they are in both halves.
  static std::uint32_t part_of(std::uint8_t a, std::uint8_t b) {
    static constexpr std::uint32_t parts[3][3] = {{0, 2, 0}, {2, 1, 1}, {0, 1, 1}};
    return parts[a][b];
  }
  /// cut_state_: no cut made yet this tick, the cut made (side_), or no cut (a NaN).
  static constexpr std::uint8_t cut_none = 0, cut_made = 1, cut_failed = 2;
  /// Runs range(begin, end, thread) over order_'s parts: the two halves, on two threads within
  /// solve_resting() when it shares them, then the contacts across the cut on this thread.
  template <class Range>
  void parts_pass(Range& range) {
    const auto& p = part_start_;
    if (team_on_) {
      auto halves = [&](int half) { range(p[half], p[half + 1], half); };
      broadphase_.second_thread().both(halves);
    } else {
      range(p[0], p[1], 0), range(p[1], p[2], 0);
    }
    range(p[2], p[3], 0);  // across the cut
  }
  /// Warm start, velocity iterations and push-out, on two threads when the contacts were
  /// split, within the tick's run of the second thread.
  void solve_resting(const Tick& tick, ContactStats& stats);
  /// Each contact's impulses from last tick's by key (warm_, each run of contacts_ against the
  /// same run of warm_), 0 for a new contact or one that carried no normal impulse.
  void match_warm();
  // velocity iterations on rows (disc_rows.cpp)
  /// rows_ from contacts_ in order_'s order, with the solver velocities of their discs, and
  /// each row's warm start: last tick's impulses (the contact's λ_n, λ_t) applied to its discs'
  /// velocities as the row is made, in row order within each part.
  void build_rows(const Tick& tick);
  /// Each moving disc's slot (sv_, sw_) set to its velocity as the tick left it, before any
  /// row's warm start adds to it, and every live disc's mark (slot_moved_) cleared: the passes
  /// after the sweeps find the discs they moved by disc (scatter_rows(), solve_resting()).
  void set_slots();
  /// Row i of rows_ and push_rows_ (and of roll_rows_ with rolling discs) from contact c, its
  /// two bodies at the solver's slots a and b.
  void fill_row(std::uint32_t i, const RestContact& c, std::uint32_t a, std::uint32_t b);
  /// Writes the velocities back and each contact's impulses to warm_ (for the next tick), and
  /// moves each disc an impulse changed by κ dt times its velocity's change (kdt = κ dt, s):
  /// the contact forces over the tick.
  void scatter_rows(double kdt);
  void solve_velocities(ContactStats& stats);
  /// What a sweep's rows need beyond impulses on velocities (row_kind_): the work of moving
  /// kinematic partners, the turn of rolling discs. Worlds without them pay for neither.
  static constexpr int kinematic_rows = 1, rolling_rows = 2;
  /// Calls f(std::integral_constant<int, row_kind_>{}): one sweep's loop for each kind.
  template <class F>
  void with_row_kind(F&& f);
  /// Row i's (r = rows_[i]) normal and friction impulses in a velocity iteration, on the
  /// solver velocities sv (sv_.data()), marking moved (row_moved_[i]); out gathers the
  /// iteration's largest change and largest normal impulse.
  template <int Kind>
  void solve_row(std::uint32_t i, SolveRow& r, SolveVelocity* sv, std::uint8_t& moved,
                 RestSweep& out);
  /// Applies the impulse λ_n n + λ_t t (N·s) to row i's (r) body a and its opposite to b.
  template <int Kind>
  void push_row(std::uint32_t i, const SolveRow& r, SolveVelocity& va, SolveVelocity& vb, double ln,
                double lt);
  void push_out(const Tick& tick, ContactStats& stats);
  /// The depth of push row i's (r) overlap now (m) and its normal, at the positions ex, ey
  /// (ex_, ey_).
  double overlap_of(const Tick& tick, std::uint32_t i, const PushRow& r, const double* ex,
                    const double* ey, double& nx, double& ny) const;
  /// What storing the positions as Real can add to push row r's overlap, m: 0 in f64 (the
  /// solver's own precision); in f32 each coordinate rounds to the nearest float at the tick's
  /// end, which moves the pair's distance by up to 2 ε max|x| (ε = FLT_EPSILON), so that an
  /// overlap pushed out to the slop is not pushed again every tick for its rounding.
  [[nodiscard]] double storage_rounding(const PushRow& r) const {
    if constexpr (std::is_same_v<Real, double>) {
      return 0.0;
    } else {
      double most = std::max(std::abs(ex_[r.a]), std::abs(ey_[r.a]));
      if (r.b < discs_.size()) most = std::max({most, std::abs(ex_[r.b]), std::abs(ey_[r.b])});
      return 2.0 * double(std::numeric_limits<float>::epsilon()) * most;
    }
  }
  // segments (disc_segments.cpp)
  /// Appends disc k's resting contacts with the segments near its end position, in segment
  /// order (key k << 32 | n + planes + segment), as gather_contacts() does for planes.
  void gather_segment_contacts(const Tick& tick, std::uint32_t k);
  /// True when disc k at (x, y) (m), at the integrator's velocity (vx, vy) (m/s) at the tick's
  /// end, rests on segment i: within the slop of its closest feature (into t), on a side where
  /// it acts, and not closing faster than a tick of its acceleration (then it is the next
  /// tick's impact).
  bool rests_on_segment(const Tick& tick, std::uint32_t k, std::uint32_t i, double x, double y,
                        double vx, double vy, SegmentTouch& t) const;
  /// overlap_of() for a segment contact: the depth (m) and normal at the closest feature now.
  double segment_overlap_of(const Tick& tick, const RestContact& c, double& nx, double& ny) const;
  /// Whether disc k is a kinematic disc that moves this tick (its contacts' partner's work is
  /// external, and its rows give it a slot of its own).
  [[nodiscard]] bool moving_kinematic(std::uint32_t k) const {
    return !discs_[k].dynamic && (motion_[k].ux != 0.0 || motion_[k].uy != 0.0);
  }
  /// The velocity (m/s) of contact c's wall b this tick: a segment's (its carrier's), 0 for a
  /// plane.
  [[nodiscard]] Vec2 wall_velocity(const Tick& tick, const RestContact& c) const {
    const std::size_t walls = discs_.size() + tick.planes.size();
    return c.b >= walls ? tick.segments->velocity(std::uint32_t(c.b - walls)) : Vec2{};
  }
  /// Contact c's rolling turn: each disc's radius as its arm and radius / inertia as its turn
  /// (a plane's or a segment's b: 0 and 0).
  [[nodiscard]] RollRow roll_row(const RestContact& c) const {
    const Disc& a = discs_[c.a];
    RollRow t{a.radius, 0.0, a.radius * a.inv_inertia, 0.0};
    if (c.b < discs_.size())
      t.arm_b = discs_[c.b].radius, t.turn_b = t.arm_b * discs_[c.b].inv_inertia;
    return t;
  }
  /// Turns row i's rolling discs by the tangential impulse lt (N·s along t = (-n_y, n_x) on a).
  void turn(std::uint32_t i, double lt) {
    const RollRow& t = roll_rows_[i];
    sw_[rows_[i].a] -= t.turn_a * lt, sw_[rows_[i].b] -= t.turn_b * lt;
  }
  /// The contact point's tangential velocity of row i's rolling discs' turn: -(ω_a r_a + ω_b r_b).
  [[nodiscard]] double turn_slip(std::uint32_t i) const {
    const RollRow& t = roll_rows_[i];
    return sw_[rows_[i].a] * t.arm_a + sw_[rows_[i].b] * t.arm_b;
  }
  void finish(const Tick& tick);
  /// Disc k's end state written back, and what the tick took from it (lost_).
  void finish(const Tick& tick, std::uint32_t k);

  std::vector<Disc> discs_;
  std::vector<std::uint64_t> linked_;
  std::vector<CollisionFilter> filters_;  ///< per disc; empty: all default, no sensor
  ContactSettings settings_;
  double min_radius_ = 0;
  // per tick (sized once; no allocation once warm). A ScratchVector is written in full by
  // every tick before it is read (save_start(), build_motions(), gather_contacts(),
  // split_contacts(), build_rows()): a snapshot copies its size only (scratch_vector.hpp).
  ScratchVector<Real> x0_, y0_, vx0_, vy0_;
  ScratchVector<DiscMotion> motion_;
  ScratchVector<DiscOffset> model_offset_;  ///< by disc, beside motion_
  /// The discs the plane pass bounced this tick, by build_motions()'s halves: the first
  /// events' switches (first_events(), first_lane_events()) without a pass over every disc.
  std::array<ScratchVector<std::uint32_t>, 2> bounced_;
  ScratchVector<SweptBox> boxes_;
  std::vector<std::uint8_t> dynamic_;
  // The candidate pairs and their CSR lists by disc: found anew by every tick before the
  // impacts (find_candidates()), read within it.
  ScratchVector<DiscPair> pairs_, sensor_pairs_;
  std::vector<SensorOverlap> sensed_;
  ScratchVector<std::uint32_t> offset_, incident_;
  ScratchVector<std::uint32_t> stamp_, impacts_;
  ScratchVector<std::uint32_t> cursor_;  ///< find_candidates()'s fill cursors
  /// On two threads, the second half of the pairs' degrees and fill cursors (incident_lists()),
  /// and of the recycled pairs (recycled_pairs()).
  ScratchVector<std::uint32_t> degree_half_, cursor_half_;
  ScratchVector<DiscPair> fat_half_;
  ScratchVector<std::uint8_t> changed_;
  ScratchVector<std::uint8_t> walled_;  ///< per disc: met a plane or a segment in the tick
  std::vector<HeldMotion> held_;        ///< per disc: held for the rest of the tick (hold_pair())
  // reach()'s: extra pairs, each disc's list of them (head per disc), the discs whose boxes
  // grew in the tick (and where in that list, per disc), and how many pairs the broadphase
  // found.
  std::vector<std::uint32_t> extra_head_, grown_of_;  ///< per disc: list head; index in grown
  std::vector<DiscPair> extra_sorted_;                ///< finish_reach()'s scratch
  std::vector<std::uint32_t> partner_mark_;           ///< per disc: reach()'s mark when k's partner
  std::vector<std::uint32_t> wall_found_;             ///< next_wall_event()'s segments near a path
  double max_radius_ = 0;
  std::size_t base_pairs_ = 0;
  double horizon_ = 0;  ///< s: the end of the window the impacts run in (the tick's by default)
  std::array<ScratchVector<RestContact>, 2> plane_half_;  ///< gather_contacts()'s on two threads
  ScratchVector<std::uint8_t> touch_;  ///< gather_contacts()'s on two threads: pair i touches
  ScratchVector<DiscEvent> events_;    ///< first_events()'s second half
  /// The tick's impacts: lane 0 alone, or both (disc_lanes.cpp) and then merged into lane 0.
  std::array<ImpactLane, 2> lanes_;
  std::vector<std::uint8_t> lane_of_;                ///< per disc: its lane in a split tick
  std::vector<std::uint32_t> lane_parent_;           ///< assign_lanes()'s union-find
  std::vector<DiscImpact> lane_log_;                 ///< merge_lane_logs()'s scratch
  LanesMet lanes_met_;                               ///< set where a lane stopped
  std::uint64_t lane_ticks_ = 0, lanes_undone_ = 0;  ///< lane_ticks(), lanes_undone()
  std::uint64_t lane_cuts_ = 0;                      ///< lane_cuts()
  std::uint64_t pile_cuts_ = 0;                      ///< pile_cuts()
  int lane_axis_ = 0;                                ///< the cut's axis (0: x, 1: y)
  double lane_cut_ = 0;                              ///< where it cuts, m
  std::uint32_t lane_misses_in_a_row_ = 0;           ///< ticks in a row without lanes
  std::uint32_t lane_rest_ = 0;                      ///< ticks left before lanes are tried again
  /// Disc pairs in key order, then planes in key order: gathered anew by every tick, read
  /// within it (touching(): the contact events, the sleeping islands).
  ScratchVector<RestContact> contacts_;
  ScratchVector<DiscPair> touching_bodies_;  ///< touching_bodies()
  /// on_moving_segment(): a vector a snapshot copies, since the sleeping islands read it after
  /// the tick (a few entries, only with moving segments).
  std::vector<std::uint32_t> on_moving_segment_;
  bool warm_gathered_ = false;          ///< the disc pairs' warm start made as they were gathered
  std::uint32_t plane_contacts_ = 0;    ///< where contacts_'s plane contacts begin
  ScratchVector<std::uint32_t> order_;  ///< see split_contacts()
  std::array<std::uint32_t, 4> part_start_{};
  ScratchVector<double> cut_;         ///< cut_pile()'s
  ScratchVector<std::uint8_t> side_;  ///< per disc: side_low, side_high or side_none
  /// Per contact of contacts_: its part (split_contacts()). (Not bytes: a byte stored may alias
  /// anything, and the gather's loop would load its arrays again after each.)
  ScratchVector<std::uint32_t> part_;
  std::uint8_t cut_state_ = cut_none;
  bool cut_along_y_ = false;  ///< cut_pile()'s axis: y, else x
  double median_ = 0.0;       ///< cut_pile()'s median coordinate along it, m
  bool team_on_ = false;      ///< set by solve_resting(): its parts' halves on two threads
  /// The last solved tick's impulses, one per contact of contacts_ as it was then, in its
  /// order: the disc pairs [0, warm_pairs_) and the planes and segments after, each run in key
  /// order. Written in place by scatter_rows(), so that no pass after the solve gathers them
  /// (an entry with λ_n = 0 carries nothing: match_warm() and last_impulse() skip it).
  std::vector<WarmImpulse> warm_;
  std::uint32_t warm_pairs_ = 0;
  // the velocity iterations' own state (disc_rows.cpp; sized once, no allocation once warm)
  ScratchVector<SolveRow> rows_;
  ScratchVector<PushRow> push_rows_;
  ScratchVector<std::uint8_t> row_moved_;  ///< 1 once an impulse of row i moved its discs
  /// Solver velocities by slot: the first three velocity 0, one per part of order_ (never
  /// written by two threads), then disc k's at 3 + k, then a moving kinematic partner's, one
  /// a row (see disc_rows.cpp).
  ScratchVector<SolveVelocity> sv_;
  /// Per slot, for this tick's rows: 0, or 1 once an impulse changed it, 2 once scatter_rows()
  /// moved its disc by that (and for a disc's slot nonzero once the push-out moved the disc).
  /// build_rows() clears every live disc's; the others keep an earlier tick's marks, never read.
  ScratchVector<std::uint8_t> slot_moved_;
  bool kinematic_contacts_ = false;   ///< a contact of this tick has a kinematic partner
  ScratchVector<RollRow> roll_rows_;  ///< with rolling discs (empty otherwise)
  ScratchVector<double> sw_;          ///< angular velocities by slot with rolling discs, rad/s
  int row_kind_ = 0;                  ///< kinematic_rows | rolling_rows, as the rows need
  ScratchVector<double> ex_, ey_, evx_, evy_;  ///< end states in double, m and m/s
  /// Rolling discs (settings_.rolling; empty otherwise): ω in double during the tick and at
  /// its start, rad/s.
  ScratchVector<double> ew_, ew0_;
  bool rolling_ = false;
  // Per disc: the energy per unit mass the tick's contacts took (lost_, J/kg, from the energy
  // ½|v|² - a·x at the tick's start or after its free step: finish()), the work done on it by
  // kinematic and static partners (external_, J), and its dissipated account at the start
  // (d_begin_, J/kg).
  ScratchVector<double> lost_, external_, d_begin_;
  GridBroadphase broadphase_;
  std::vector<std::uint32_t> segments_near_;  ///< gather_segment_contacts()'s scratch
  // Sleeping discs (set_asleep(); disc_live.cpp). A tick with sleepers and few discs awake
  // visits the live discs only (live_only()): live_ in index order, flagged in in_live_ (both
  // kept, so that the next tick clears the flags it set).
  std::vector<std::uint8_t> asleep_;  ///< per disc
  std::size_t sleeper_count_ = 0;
  std::vector<std::uint32_t> awake_list_;  ///< awake(), while !awake_dirty_
  bool awake_dirty_ = true;
  AwakeFlips awake_flips_;   ///< by which awake() updates awake_list_
  bool live_all_ = true;     ///< the tick visits every disc
  bool saved_live_ = false;  ///< save_start() saved the awake discs only (live_only())
  std::vector<std::uint32_t> live_;
  std::vector<std::uint8_t> in_live_;
  bool live_sorted_ = true;
  bool waking_ = false;               ///< within Tick::wake: set_asleep() lists the woken
  std::vector<std::uint32_t> woken_;  ///< discs woken within the tick's Tick::wake
  SleeperGrid sleepers_;
  ScratchVector<SweptBox> live_boxes_;
  ScratchVector<std::uint8_t> live_dynamic_;
  ScratchVector<std::uint32_t> degree_;  ///< per disc: its candidate pairs (find_candidates())
  FatBoxes fat_;
  FatGridHeld fat_grid_;
  CapHit cap_;
};

}  // namespace fixstep::detail
