// The records of disc-disc contacts (disc_contacts.hpp): a disc of the contact set, its motion
// within a tick, an impact waiting in the event queue, a resting contact and the rows the
// resting solver and the push-out make of it, the impulses kept for warm starting, a sensor's
// overlap and an impact as logged. Plain data; internal to the engine: not installed.
#pragma once

#include <algorithm>
#include <cstdint>

namespace fixstep::detail {

/// One disc of the contact set, in the World's dense body order at rebuild time.
struct Disc {
  std::uint32_t body = 0;           ///< dense body index
  double radius = 0;                ///< m
  double restitution = 0;           ///< e in [0, 1]
  double friction = 0;              ///< μ >= 0
  double inv_mass = 0;              ///< 1/kg; 0 for static and kinematic discs
  std::uint8_t dynamic = 0;         ///< 1 for dynamic discs
  std::uint8_t sensor = 0;          ///< 1 for a sensor (Collider::sensor): no contact, sensed
  double accel_x = 0, accel_y = 0;  ///< constant acceleration (gravity + F/m), m/s² (energy)
  std::int32_t plane_slot = -1;     ///< its index among the plane colliders (Tick::after), or -1
  double inv_inertia = 0;           ///< 1/(kg·m²) with rolling discs; 0: it does not turn
};

/// A disc's motion within the tick: position X and model velocity U at time t, acceleration a;
/// and the disc's radius beside them. One cache line: an impact's prediction reads the two
/// discs' motions and radii in the order of the impacts' times, which no memory order follows.
struct alignas(64) DiscMotion {
  double t = 0, x = 0, y = 0, ux = 0, uy = 0, ax = 0, ay = 0;
  double radius = 0;  ///< m (Disc::radius)
  [[nodiscard]] double px(double s) const {
    return x + ux * (s - t) + 0.5 * ax * (s - t) * (s - t);
  }
  [[nodiscard]] double py(double s) const {
    return y + uy * (s - t) + 0.5 * ay * (s - t) * (s - t);
  }
  /// Moves the state on along the motion to time `now` (s), which becomes t.
  void advance(double now) {
    const double s = now - t;
    x += s * (ux + 0.5 * s * ax), y += s * (uy + 0.5 * s * ay);
    ux += s * ax, uy += s * ay, t = now;
  }
};

static_assert(sizeof(DiscMotion) == 64);

/// The offset δ of a disc's model velocity U from the integrator's velocity v (U = v + δ, so
/// that the model's path ends the tick where the integrator put the disc), m/s.
struct DiscOffset {
  double x = 0, y = 0;
};

/// The range [lo, hi] of a + u s + ½ c s² over s in [0, h], widened by `pad`, m.
inline void motion_extent(double a, double u, double c, double h, double pad, double& lo,
                          double& hi) {
  const double end = a + h * (u + 0.5 * c * h);
  lo = std::min(a, end), hi = std::max(a, end);
  if (c != 0.0) {
    const double s = -u / c;
    if (s > 0.0 && s < h) {
      const double turn = a + s * (u + 0.5 * c * s);
      lo = std::min(lo, turn), hi = std::max(hi, turn);
    }
  }
  lo -= pad, hi += pad;
}

/// A pair found within a tick for a disc an impact sent beyond its box (disc_reach.cpp): one
/// link of that disc's list of such pairs.
struct ExtraPair {
  static constexpr std::uint32_t none = 0xffffffffu;
  std::uint32_t pair = 0, disc = 0, next = none;  ///< pair index; the disc; its next link
};

/// A disc held where it is for the rest of a tick: its motion's velocity (m/s) and acceleration
/// (m/s²) when it was held; on = 0 when not held.
struct HeldMotion {
  double ux = 0, uy = 0, ax = 0, ay = 0;
  std::uint8_t on = 0;
  /// 1 once a kinematic disc released it in the tick: it is not held again in that tick (the
  /// kinematic disc would release it again at the same instant, without end).
  std::uint8_t released = 0;
};

/// An impact waiting in the event queue: time, pair index and the two discs' versions.
/// A wall event (disc_walls.cpp) has pair = wall_event | disc, stamp_a the disc's version and
/// stamp_b the wall: a plane's index, or the plane count plus a segment's; a switch event
/// pair = switch_event | disc.
struct DiscEvent {
  double time = 0;
  std::uint32_t pair = 0, stamp_a = 0, stamp_b = 0;
};

/// The bit of DiscEvent::pair that marks a disc's event with a wall.
inline constexpr std::uint32_t wall_event = 0x80000000u;
/// The bit of DiscEvent::pair that marks the first plane event of a disc the plane pass bounced
/// (stamp_a its version): from there it moves on the plane pass's motion.
inline constexpr std::uint32_t switch_event = 0x40000000u;

/// Earlier event first; ties by pair index, a disc's wall events after every pair's (a fixed
/// order, so runs agree bit for bit). The event queue's heap order.
inline bool later_event(const DiscEvent& l, const DiscEvent& r) {
  return l.time > r.time || (l.time == r.time && l.pair > r.pair);
}

/// A contact of the resting solver: disc a against disc b, or against plane p (b = disc count
/// + p) or a segment (past the planes). The gather writes one per touching pair and
/// build_rows() reads it back, so it holds only what its rows cannot make from its other fields
/// (80 bytes): the effective masses are 1 / (1/m_a + 1/m_b) (build_rows()), whether a partner
/// is a moving kinematic disc is its disc's (moving_kinematic()), and a moving segment's
/// velocity is the segment's for the tick.
struct RestContact {
  std::uint32_t a = 0, b = 0;
  /// The normal n (unit, from b to a), μ; the impulses the solve starts from (N·s: last tick's,
  /// matched by key), its own are kept in DiscContacts::warm_.
  double nx = 0, ny = 0, friction = 0, lambda_n = 0, lambda_t = 0;
  double inv_a = 0, inv_b = 0;  ///< 1/kg of a and b (0: static, kinematic or a plane)
  /// The radii r_a + r_b (r_a for a plane or a segment) and the smaller radius, m.
  double radii = 0, r_min = 0;
  /// a << 32 | b: the contacts' order, and the warm start's match.
  [[nodiscard]] std::uint64_t key() const { return (std::uint64_t(a) << 32) | b; }
};

/// A resting contact as the velocity iterations see it (disc_rows.cpp), in order_'s order:
/// its two bodies as slots of the solver's own velocity array (a slot of velocity 0 for a
/// static body or a plane), and what an impulse needs, from RestContact.
/// A sweep streams every row (72 bytes): at 10^5 discs the rows of a settling pile fill most of
/// the last-level cache, so a row holds only what the sweep reads (the tangent's mass of rolling
/// discs is RollRow's; without rolling it is `mass`).
struct SolveRow {
  std::uint32_t a = 0, b = 0;  ///< slots of DiscContacts' solver velocities
  double nx = 0, ny = 0, mass = 0, friction = 0, lambda_n = 0, lambda_t = 0;
  /// Each body's inverse mass (1/kg; 0: the slot is not moved): an impulse changes its velocity
  /// by the impulse's components times (1/m) n, the same products in every sweep.
  double inv_a = 0, inv_b = 0;
};

/// A resting contact as the push-out sees it (disc_rows.cpp), in order_'s order: its discs (b
/// past the discs for a plane or a segment), r_a + r_b (r_a past the discs) and the smaller
/// radius (m), and the shares w_a = (1/m_a) / (1/m_a + 1/m_b) and w_b of a push that each
/// disc takes (0: it is not moved).
struct PushRow {
  std::uint32_t a = 0, b = 0;
  double radii = 0, r_min = 0, w_a = 0, w_b = 0;
};

/// A rolling row's turn (disc_rows.cpp): the radii r_a, r_b from the centres to the contact
/// point (m; 0 for a plane) and r/I of each disc (rad/s per N·s; 0: it does not turn).
struct RollRow {
  double arm_a = 0, arm_b = 0, turn_a = 0, turn_b = 0;
  /// The mass along the tangent at the contact point, kg: 1 / (1/m_a + 1/m_b + r_a²/I_a +
  /// r_b²/I_b).
  double mass_t = 0;
};

/// A velocity in the solver's own array, m/s.
struct SolveVelocity {
  double x = 0, y = 0;
};

/// Last tick's resting impulses, for warm starting (part of a snapshot).
struct WarmImpulse {
  std::uint64_t key = 0;
  double lambda_n = 0, lambda_t = 0;
};

/// The first impulse of [first, last), in key order, whose key is not below `key`.
inline const WarmImpulse* first_warm_from(const WarmImpulse* first, const WarmImpulse* last,
                                          std::uint64_t key) {
  return std::lower_bound(first, last, key,
                          [](const WarmImpulse& h, std::uint64_t k) { return h.key < k; });
}

/// A disc overlapping a sensor after a tick, or crossing it within the tick (begun and ended
/// in it), by dense body index.
struct SensorOverlap {
  std::uint32_t sensor = 0, visitor = 0;
  std::uint8_t crossed = 0;  ///< 1: it met the sensor only within the tick
};

/// An impact as the contact solver logs it: the two bodies by dense index (body_a < body_b),
/// its time (s after the tick's start) and closing speed (m/s). World::impacts() names them
/// by handle.
struct DiscImpact {
  std::uint32_t body_a = 0, body_b = 0;
  double time = 0.0, normal_speed = 0.0;
};

}  // namespace fixstep::detail
