// A disc's motion against a plane within a tick, and what its contacts do to it: the time of
// impact, the push-out of a body that starts inside, the impact (restitution, Coulomb friction,
// coming to rest and sliding), rolling discs' friction at the contact point, and planes that
// move (a kinematic body's segments). The model is described in world_contacts.cpp, the plane
// pass that uses them. Internal: included by world_contacts.cpp only.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "fixstep/core/components.hpp"

namespace fixstep::plane_contact {

/// Events (bounces and comings to rest) resolved per body and tick before only bounces are.
constexpr int max_impacts = 8;

struct V2 {
  double x = 0, y = 0;
};
inline V2 operator+(V2 a, V2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline V2 operator-(V2 a, V2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline V2 operator*(double s, V2 a) {
  return {s * a.x, s * a.y};
}
inline double dot(V2 a, V2 b) {
  return a.x * b.x + a.y * b.y;
}
inline double norm(V2 a) {
  return std::sqrt(dot(a, a));
}

/// A collider body's motion in the tick: position x and model velocity v at local time t,
/// constant acceleration a, and the integrator's velocity offset (v - offset).
struct Motion {
  V2 x, v, a, offset;
  double t = 0;     ///< s since the tick's start
  double lost = 0;  ///< kinetic energy removed so far, J/kg
  /// The friction of the rests holding the body (their sum, m/s²), whose work over the rest of
  /// the tick `lost` holds as reckoned on the path the motion had when each began.
  V2 friction{};

  void advance(double s) {
    x = x + s * v + (0.5 * s * s) * a;
    v = v + s * a;
    t += s;
  }
};

/// Smallest s in [0, horizon] with gap(s) = g0 + b s + ½ c s² = 0 while approaching, or
/// infinity. g0 <= tol counts as touching (g0 = 0): an event at s = 0 if the body moves or
/// accelerates into the plane (b < -vtol, or b <= vtol and c < 0), else at s = -2b/c when it
/// leaves and falls back (c < 0). The roots use the cancellation-free
/// form q = -½ (b + sgn(b) √(b² - 2 c g0)), s = g0/q and 2q/c (Numerical Recipes §5.6), which
/// also covers c = 0.
inline double first_impact(double g0, double b, double c, double horizon, double tol, double vtol) {
  constexpr double none = std::numeric_limits<double>::infinity();
  if (g0 <= tol) {
    if (b < -vtol || (b <= vtol && c < 0.0)) return 0.0;
    return c < 0.0 && -2.0 * b / c <= horizon ? -2.0 * b / c : none;
  }
  // A gap that stays above its lower bound over the window, g0 + min(0, b h) + min(0, ½ c h²),
  // has no root there: most bodies against most planes, decided without the roots. The margin
  // (far above the bound's rounding) leaves every case near a root to the roots below, so the
  // answer is the one they give.
  const double low = g0 + std::min(0.0, b * horizon) + std::min(0.0, 0.5 * c * horizon * horizon);
  if (low > tol + 1e-12 * (g0 + std::abs(b) * horizon + std::abs(c) * horizon * horizon)) {
    return none;
  }
  const double disc = b * b - 2.0 * c * g0;
  if (disc < 0.0) return none;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double s = none;
  for (const double root : {q != 0.0 ? g0 / q : none, c != 0.0 ? 2.0 * q / c : none}) {
    if (root >= 0.0 && root <= horizon && b + c * root <= 0.0) s = std::min(s, root);
  }
  return s;
}

/// True when a body of radius r moving from x0 (velocity v0) to x1 (v1) in the tick dt stays
/// clear of every plane all the tick, by more than the tests below could see otherwise: its
/// motion is the parabola through x0 and x1 with acceleration (v1 - v0)/dt, which departs from
/// the chord by at most |n·(v1 - v0)| dt/8 along n, so its gap to a plane is at least
/// min(n·x0, n·x1) - that - offset - r. Then no push-out, impact or end-of-tick contact can
/// touch it, and its integrated state stands, as those tests would leave it.
/// The scale of clear_of_planes' rounding margin for one body, once for every plane
/// (|n·u| <= |u_x| + |u_y| for a unit n), m.
inline double clearance_scale(V2 x0, V2 x1, V2 v0, V2 v1, double r, double dt) {
  const auto l1 = [](V2 u) { return std::abs(u.x) + std::abs(u.y); };
  return l1(x0) + l1(x1) + r + 2.0 * (l1(v0) + l1(v1)) * dt;
}

/// clear_of_planes' test for one plane p, with dv = v1 - v0 and body = clearance_scale().
inline bool clear_of_plane(const PlaneDef& p, V2 x0, V2 x1, V2 dv, double r, double dt, double rel,
                           double body) {
  const V2 n{p.normal.x, p.normal.y};
  const double n0 = dot(n, x0), n1 = dot(n, x1);
  const double low = std::min(n0, n1) - 0.125 * std::abs(dot(n, dv)) * dt - p.offset - r;
  return low > (rel + 1e-12) * (body + std::abs(p.offset));
}

inline bool clear_of_planes(std::span<const PlaneDef> planes, V2 x0, V2 x1, V2 v0, V2 v1, double r,
                            double dt, double rel) {
  const double body = clearance_scale(x0, x1, v0, v1, r, dt);
  for (const PlaneDef& p : planes) {
    if (!clear_of_plane(p, x0, x1, v1 - v0, r, dt, rel, body)) return false;
  }
  return true;
}

/// Pushes m out of plane p when it starts inside by more than rounding (rel, relative),
/// dropping its approaching velocity; true when it did.
inline bool push_out(Motion& m, const PlaneDef& p, double r, double rel) {
  const V2 n{p.normal.x, p.normal.y};
  const double g0 = dot(n, m.x) - p.offset - r;
  if (g0 >= -rel * (std::abs(dot(n, m.x)) + std::abs(p.offset) + r)) return false;
  m.x = m.x + -g0 * n;
  const double vn = std::min(dot(n, m.v), 0.0);
  m.lost += 0.5 * vn * vn;
  m.v = m.v - vn * n;
  return true;
}

/// True when m, advanced by s, would bounce off p rather than come to rest on it (impact()'s
/// test).
inline bool bounces(const Motion& m, double s, const PlaneDef& p, double dt) {
  const V2 n{p.normal.x, p.normal.y};
  const double vn = std::min(dot(n, m.v + s * m.a), 0.0);
  return p.restitution * -vn > std::max(-dot(n, m.a), 0.0) * dt;
}

/// A rolling disc's turn (ContactSettings::rolling): angular velocity w (rad/s) and
/// s = m r² / I (2 for a uniform disc), the ratio of the contact point's tangential velocity
/// change through the spin to that through the centre under one friction impulse.
struct Spin {
  double w = 0, s = 0;
};

/// The friction change of tangential velocity (m/s, along t = (-n_y, n_x)) that stops a rolling
/// disc's contact point from slipping, slip u = v·t - ω r: -u / (1 + s), within Coulomb's
/// bound (m/s). The disc's ω changes by -Δ s / r.
inline double stick(double slip, double s, double bound) {
  return std::clamp(-slip / (1.0 + s), -bound, bound);
}

/// Resolves an impact of m with plane p (normal n) at m's current state; r = the radius, dt =
/// the tick; spin: the disc's turn in a world of rolling discs (null otherwise), whose friction
/// then acts at the contact point. Places the body on the plane; updates its velocity, its
/// acceleration when it comes to rest, and the energy lost. Returns true for a bounce, false when
/// the body comes to rest.
inline bool impact(Motion& m, const PlaneDef& p, double r, double dt, Spin* spin) {
  const V2 n{p.normal.x, p.normal.y};
  m.x = m.x + (p.offset + r - dot(n, m.x)) * n;  // exactly on the plane (in double)
  const double vn = std::min(dot(n, m.v), 0.0);
  const double an = dot(n, m.a);
  const V2 vt = m.v - dot(n, m.v) * n;
  const bool rests = p.restitution * -vn <= std::max(-an, 0.0) * dt;
  const double e = rests ? 0.0 : p.restitution;
  // Coulomb over the normal impulse (1 + e)|v_n| (per unit mass): of the trajectory at a
  // bounce; at rest of the integrator's own velocity (semi-implicit Euler's trajectory leads
  // it by a dt/2 into the plane, which no impulse stops).
  const double vn_stopped = rests ? std::min(dot(n, m.v - m.offset), 0.0) : vn;
  V2 vt_after = vt;
  if (spin) {
    const V2 t{-n.y, n.x};
    const double w0 = spin->w;
    // The slip of the integrator's velocity at rest (it is what the next tick starts from),
    // of the trajectory's at a bounce (as the friction without rolling).
    const double vt_slip = dot(t, rests ? vt - m.offset : vt);
    const double d = stick(vt_slip - w0 * r, spin->s, p.friction * (1.0 + e) * -vn_stopped);
    vt_after = vt + d * t;
    spin->w = w0 - d * spin->s / r;
    m.lost += 0.5 * (r * r / spin->s) * (w0 * w0 - spin->w * spin->w);  // ½ (I/m) ω²
  } else {
    const double speed = norm(vt);
    const double cut = std::min(speed, p.friction * (1.0 + e) * -vn_stopped);
    vt_after = speed > 0.0 ? ((speed - cut) / speed) * vt : vt;
  }
  const V2 v_after = vt_after + (-e * vn) * n;
  if (!rests) {
    m.lost += 0.5 * (dot(m.v, m.v) - dot(v_after, v_after));  // on the trajectory
    m.v = v_after;
    return true;
  }
  // At rest the integrator's velocity has no normal part either. The energy lost is the
  // integrator's kinetic energy before and after: semi-implicit Euler's trajectory velocity
  // leads by a dt/2 into the plane each tick it rests, which no physics dissipates.
  const V2 before = m.v - m.offset;
  m.offset = m.offset - dot(n, m.offset) * n;
  const V2 after = v_after - m.offset;
  m.lost += 0.5 * (dot(before, before) - dot(after, after));
  m.v = v_after;
  if (an >= 0.0) return false;
  // Resting: the normal force cancels a_n; sliding friction μ|a_n| acts over the rest T.
  const double T = dt - m.t;
  if (T <= 0.0) return false;
  const V2 at = m.a - an * n;
  const V2 free_end = m.v + T * at;
  V2 end = free_end;
  if (spin) {  // the contact point's slip at T stopped within μ|a_n| T: rolls or slides
    const V2 t{-n.y, n.x};
    const double w0 = spin->w;
    const double d = stick(dot(t, free_end - m.offset) - w0 * r, spin->s, p.friction * -an * T);
    end = free_end + d * t;
    spin->w = w0 - d * spin->s / r;
    m.lost += 0.5 * (r * r / spin->s) * (w0 * w0 - spin->w * spin->w);
  } else {
    const double free_speed = norm(free_end);
    const double slow = std::min(free_speed, p.friction * -an * T);
    end = free_speed > 0.0 ? ((free_speed - slow) / free_speed) * free_end : free_end;
  }
  const V2 a_new = (1.0 / T) * (end - m.v);
  // Work of friction over T (its acceleration a_new - at is constant, v is linear in time).
  m.lost -= dot(a_new - at, 0.5 * T * (m.v + end));
  m.friction = m.friction + (a_new - at);
  m.a = a_new;
  return false;
}

/// A contact with a plane moving at u (a segment a kinematic body carries; world_segments.cpp)
/// is resolved on m seen from the plane's frame (its velocity less u; position, acceleration and
/// the integrator's offset unchanged, u being constant within the tick), and the result is
/// taken back into the world's frame; `work` gets the plane's work on the body per unit mass,
/// Δv·u (J/kg, Δv the change of the integrator's velocity). A static plane (u = 0) is resolved on m
/// itself. As push_out().
inline bool push_out_moving(Motion& m, const PlaneDef& p, double r, double rel, V2 u,
                            double& work) {
  if (u.x == 0.0 && u.y == 0.0) return push_out(m, p, r, rel);
  Motion seen = m;
  seen.v = m.v - u;
  if (!push_out(seen, p, r, rel)) return false;
  const V2 v = seen.v + u;
  work += dot(v - m.v, u);
  seen.v = v;
  m = seen;
  return true;
}

/// impact() against a plane moving at u, as push_out_moving().
inline bool impact_moving(Motion& m, const PlaneDef& p, double r, double dt, Spin* spin, V2 u,
                          double& work) {
  if (u.x == 0.0 && u.y == 0.0) return impact(m, p, r, dt, spin);
  Motion seen = m;
  seen.v = m.v - u;
  const bool bounce = impact(seen, p, r, dt, spin);
  const V2 v = seen.v + u;
  // Of the integrator's velocity (the model's less the offset, which a rest also changes).
  work += dot((v - seen.offset) - (m.v - m.offset), u);
  seen.v = v;
  m = seen;
  return bounce;
}

/// What a body's plane pass carries from event to event besides its Motion. A rest that holds
/// the body's normal acceleration on a segment holds it only while the body slides along it: a
/// bounce off anything else (or off a segment, after a rest on a plane) gives back the free
/// acceleration, so no holding force works on a body that left its surface, and a surface the
/// body still presses on holds it again at once. (A rest on a second surface still keeps the
/// first one's hold for the rest of the tick: the energy account then misses that force's
/// work, ~1e-4 of a level's energy over 10 s.) Worlds without segments never take this path.
struct Surfaces {
  V2 a_free;               ///< the body's acceleration before any rest, m/s²
  bool held = false;       ///< a rest on a segment holds it
  double work = 0.0;       ///< J/kg the kinematic bodies' segments did on it so far
  double held_rate = 0.0;  ///< W/kg, the power of the force holding a rest on a moving segment
};

/// The event of m (advanced to it) with `p`, a segment's local plane when `segment`, moving at u
/// (m/s; 0 for a plane or a static segment): impact_moving(), then the account of the rests it
/// begins and ends (the holding force's work on a moving segment over the rest of the tick, the
/// friction reckoned on the path before the event moved to the path after it, or taken back when
/// a bounce leaves the rest). r, dt, spin as impact(). Returns true for a bounce.
inline bool resolve_event(Motion& m, const PlaneDef& p, bool segment, V2 u, double r, double dt,
                          Spin* spin, Surfaces& s) {
  const V2 a_before = m.a, v_before = m.v, friction = m.friction;
  const bool bounce = impact_moving(m, p, r, dt, spin, u, s.work);
  if (!bounce && (u.x != 0.0 || u.y != 0.0)) {
    // Held on a moving segment: the holding force's work over the rest of the tick.
    const double rate = dot(m.a - a_before, u);
    s.work += rate * (dt - m.t), s.held_rate += rate;
  }
  if (bounce && (s.held || segment)) {
    s.work -= s.held_rate * (dt - m.t), s.held_rate = 0.0;  // the hold ends here
    m.a = s.a_free, s.held = false, m.friction = V2{};
    // The friction of the rests it left acts no more: take back what was reckoned of it.
    const double T = dt - m.t;
    m.lost += dot(friction, T * v_before + (0.5 * T * T) * a_before);
  } else if (friction.x != 0.0 || friction.y != 0.0) {
    // A rest's friction was reckoned on the path before this event: on the path after it.
    const double T = dt - m.t;
    m.lost -= dot(friction, T * (m.v - v_before) + (0.5 * T * T) * (m.a - a_before));
  }
  s.held = s.held || (!bounce && segment);
  return bounce;
}

}  // namespace fixstep::plane_contact
