// What a tick reports: the mechanical energy, contact statistics, impacts and contact events,
// and the runtime guard's state fault.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// Mechanical energy, J. Potentials: spring ½k(|x-anchor|-L)² (anchored) and ½k(|x_a-x_b|-L)²
/// (links), gravity -m g·x, constant force -F·x (both zero at the origin). Damping and drag
/// are dissipative and have no potential: see World::dissipated_energy().
struct EnergyReport {
  double kinetic = 0.0;         ///< ½ m |v|², J
  double spring = 0.0;          ///< anchored springs and links, J
  double gravity = 0.0;         ///< J
  double constant_force = 0.0;  ///< J
  [[nodiscard]] double total() const { return kinetic + spring + gravity + constant_force; }
};

/// What the disc-disc contacts did in one tick (World::contact_stats()).
struct ContactStats {
  std::size_t candidate_pairs = 0;  ///< pairs of discs whose swept boxes overlap (broadphase)
  std::size_t impacts = 0;          ///< impacts resolved at their time within the tick
  /// Discs held where they met another or a wall for the rest of the tick: past their 8th impact
  /// of the tick, in a pair whose centres would cross by its end or that would end it deeper than
  /// 1.5 times the smaller radius, or against an inelastic wall they would end it inside
  /// (docs/ROBUSTNESS.md, "No physics dropped by a cap"); the resting solver then stops them
  /// approaching.
  std::size_t held = 0;
  /// Impacts of discs with planes and segments resolved among the disc impacts: a disc whose
  /// motion an impact changed meets the walls on its new path (the plane pass met those of its
  /// free motion before).
  std::size_t wall_impacts = 0;
  std::size_t touching = 0;  ///< pairs in contact at the end of the tick (resting solver)
  double max_overlap = 0.0;  ///< deepest overlap r_a + r_b - |x_a - x_b| left, m (>= 0)
  /// Contact work a cap stopped in the last tick (limits.hpp: max_candidate_pairs,
  /// max_tick_predictions): 0, or 1 when the tick reached one; World::fault() then
  /// names it.
  std::size_t capped = 0;
  /// Iterations the resting solver ran over the touching pairs in the last tick: velocity
  /// iterations (impulses; at most ContactSettings::velocity_iterations) and position
  /// iterations (push-out; at most ContactSettings::position_iterations). 0 when no pair
  /// touched. Fewer than the setting when the solver finished early (below).
  int velocity_sweeps = 0;
  int position_sweeps = 0;
  /// Whether the velocity iterations finished early: the last one changed no accumulated
  /// impulse by more than 1e-9 of the largest. False is normal in a deep pile: the rest is
  /// carried into the next tick by warm starting. True when no pair touched.
  bool velocity_converged = true;
  /// Whether no pair is left deeper than the solver's slop (0.5 % of the smaller radius, plus
  /// 10^-6 of it for rounding) after the position iterations. False is normal while a pile settles:
  /// the next tick's push-out goes on (max_overlap says how deep). True when no pair touched.
  bool positions_settled = true;
  /// Touching pairs across the cut that splits a large pile in two halves for the resting
  /// solver (the halves are solved at once on two threads; these after them, on one).
  std::size_t across = 0;
  /// Bodies asleep after the tick (ContactSettings::sleep; 0 without sleeping).
  std::size_t sleeping = 0;
  /// Islands woken in the tick: by an awake disc's motion coming near, a contact, input or an
  /// edit (ContactSettings::sleep).
  std::size_t woken = 0;
  /// Impacts and resting contacts of an awake disc with a sleeping one in the tick, in which the
  /// sleeper acted as a static disc (it then wakes at the tick's end). An island wakes before
  /// the broadphase pairs any of its discs with an awake one, so this is 0 unless an impact sent
  /// an awake disc beyond the box it was paired by and on into a sleeper within the tick.
  std::size_t sleeper_contacts = 0;
  /// Bodies the last tick's free step (the integrator) stepped: every body, except that in a
  /// world without links the static bodies are skipped (they never move), and with sleeping
  /// islands the sleepers too, so a world asleep steps none.
  std::size_t free_stepped = 0;
  /// Bodies the last tick's pass over the planes and segments looked at: every dynamic
  /// collider (0 in a world without planes or segments), the sleepers skipped as above.
  std::size_t plane_tested = 0;
  /// Bodies with shapes (and discs that meet them) the last tick's shape phase visited: 0 in
  /// a tick in which every dynamic body with shapes sleeps, no kinematic one moves and the
  /// disc phases do not run, so that a world asleep passes over none of them; in a world of
  /// 128 shapes or more, the awake dynamic and the kinematic ones, but in a tick after a body
  /// fell asleep or woke, or an edit, which visits every one; in a smaller world every one.
  std::size_t shape_visited = 0;
  /// Joints (not broken) the last tick's shape phase solved: every one, but in a world of 128
  /// shapes or more, where a tick visits the moving bodies alone (shape_visited), only those
  /// with an end among them; a joint whose two ends are asleep or static is left as its last
  /// tick left it (its impulses kept for the warm start when its island wakes). 0 in a tick
  /// without a shape phase.
  std::size_t joint_visited = 0;
  /// Discs the last tick's disc phases visited (their motions, the broadphase, the end of
  /// the tick): every disc, or in a world with sleeping islands and at most a quarter of its
  /// discs awake, the awake ones and the sleepers their swept boxes reach (0 when every disc
  /// sleeps and no phase ran).
  std::size_t disc_visited = 0;
  /// Windows (equal sub-intervals) of the tick the discs were paired over, each by its boxes
  /// over that window: 1, or up to 64 when the boxes over the whole tick overlapped in more than
  /// 16 pairs a disc (fast discs through a crowd; candidate_pairs is then the most of one
  /// window); 0 without disc contacts, or when the pairs over the whole tick reached
  /// max_candidate_pairs before any window.
  std::size_t windows = 0;
  /// Manifold points of bodies with shapes (BodyDef::shapes) this tick, with planes, segments,
  /// discs and one another; 0 in a world without shapes.
  std::size_t shape_points = 0;
  /// The deepest overlap of two shapes (or a shape and a plane, segment or disc) left after the
  /// tick's solve, m (the solver pushes out what lies beyond a 5 mm slop over ticks).
  double deepest_shape_overlap = 0.0;
  /// Velocity sweeps of the shapes' and joints' solver in the last tick, at most
  /// ContactSettings::velocity_iterations: fewer once a sweep has converged (its joints moved
  /// no body's velocity by more than 1e-9 m/s or rad/s, and its contacts changed no point's
  /// normal or tangent velocity by more than 1e-5 m/s or rad/s); 0 without shapes and joints,
  /// or when nothing touched.
  int shape_velocity_sweeps = 0;
};

/// Where the last tick's time went in a world with disc contacts (World::profile()): seconds of
/// wall-clock time (std::chrono::steady_clock) per phase, as Box2D's b2Profile reports them.
/// For finding the costly phase only: no state depends on it, and it differs from run to run.
/// A world without disc contacts measures nothing (every field 0), so its ticks pay no clock.
/// The phases add up to `step`, less the few reads of the clock between them.
struct StepProfile {
  double step = 0.0;        ///< s, the whole tick
  double integrate = 0.0;   ///< s, input, forces, springs, links and the integrator's free step
  double broadphase = 0.0;  ///< s, the discs' motions in the tick and their candidate pairs
  double impacts = 0.0;     ///< s, impacts found and resolved at their time within the tick
  double resting = 0.0;     ///< s, the resting solver: gather, warm start, sweeps, push-out
  double events = 0.0;      ///< s, the state written back, sensors, contact and sensor events
};

/// A disc-disc impact resolved at its time within the last tick (World::impacts()), in the
/// order they were resolved.
struct Impact {
  Entity a{}, b{};            ///< the two bodies, a before b in World::bodies() order
  double time = 0.0;          ///< s after the tick's start
  double normal_speed = 0.0;  ///< closing speed along the line of centres, m/s (> 0)
};

/// A pair of discs that began or stopped touching in the last tick (World::contacts_begun(),
/// World::contacts_ended()): what a game's rules read to start a sound, score a hit or end a
/// grab. Touching is the resting solver's test (centres within r_a + r_b plus its slop). Each
/// list is in slot order: by a.slot(), then b.slot().
struct ContactEvent {
  Entity a{}, b{};  ///< the two bodies, a.slot() < b.slot()
  /// Begun: the closing speed of the impact that began it, m/s (the largest, if several), or 0
  /// when the discs came to touch without one (settling into contact). Ended: 0.
  double normal_speed = 0.0;
  friend constexpr bool operator==(const ContactEvent&, const ContactEvent&) = default;
};

/// A disc that began or stopped overlapping a sensor in the last tick (World::sensors_begun(),
/// World::sensors_ended()), or overlaps one now (World::sensor_overlaps()): the ball in the
/// bucket. Overlapping is |x_sensor - x_visitor| < r_sensor + r_visitor.
struct SensorEvent {
  Entity sensor{};   ///< the body whose Collider is a sensor
  Entity visitor{};  ///< the disc it sees (never a sensor)
  friend constexpr bool operator==(const SensorEvent&, const SensorEvent&) = default;
};

/// Largest magnitude a body's x, y (m) or vx, vy (m/s) may reach. Beyond it, or at NaN or
/// infinity, World::step records a StateFault: 10¹² m is about 7 astronomical units, far outside
/// any scene a game steps, and still 26 orders of magnitude below float's overflow.
inline constexpr double max_state_magnitude = 1e12;

/// Why World::step stopped being trustworthy: the first body whose state left the finite range
/// |value| <= max_state_magnitude, or a contact cap (limits.hpp) that kept a tick's contacts
/// from being resolved in full (field "contacts", cap set).
struct StateFault {
  Entity body{};           ///< the body (its handle when the fault was recorded)
  std::string name;        ///< the body's name
  std::uint64_t tick = 0;  ///< the tick that produced the value (World::tick() after it)
  double time = 0.0;       ///< simulated time after that tick, s
  std::string field;       ///< "x", "y" (m) or "vx", "vy" (m/s); "contacts" for a cap
  double value = 0.0;      ///< the offending value (NaN, ±inf or |value| > the limit); the cap
  /// The cap reached ("max_candidate_pairs", "max_tick_predictions"); empty for a
  /// state out of range.
  std::string cap;
  /// With cap: the other party of the impact left unresolved ("body[7] \"peg\"", "plane[2]"),
  /// or, for max_candidate_pairs, what made the pairs (the body is the disc with the largest
  /// swept box).
  std::string with;
};

}  // namespace fixstep
