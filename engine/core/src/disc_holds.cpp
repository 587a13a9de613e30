// Disc contacts, phase 1, past the cap: what becomes of a pair's impact once either disc has
// had max_impacts in the tick (see disc_contacts.hpp): resolved, left to the resting solver, or
// its discs held where they meet for the rest of the tick, so that a pair driven on past what
// the push-out can part never ends on the wrong side (docs/ROBUSTNESS.md, "No physics dropped
// by a cap").
#include <algorithm>

#include "disc_contacts.hpp"
#include "segment_set.hpp"

namespace fixstep::detail {

template <class Real>
typename DiscContacts<Real>::PastCap DiscContacts<Real>::past_cap(const Tick& tick,
                                                                  std::uint32_t pair, double now) {
  const double dt = tick.dt;
  const std::uint32_t a = pairs_[pair].a, b = pairs_[pair].b;
  if (impacts_[a] < max_impacts && impacts_[b] < max_impacts) return PastCap::impact;
  if (std::max(discs_[a].restitution, discs_[b].restitution) >= 1.0) return PastCap::impact;
  const DiscMotion &ma = motion_[a], &mb = motion_[b];
  const double ex = ma.px(dt) - mb.px(dt), ey = ma.py(dt) - mb.py(dt);  // at the tick's end
  const double gap = length(ex, ey) - (discs_[a].radius + discs_[b].radius);
  if (gap > 0.0) return PastCap::impact;  // it would pass through
  // It ends the tick overlapping: the resting solver stops it approaching, unless its centres
  // would cross (the push-out would then part them the wrong way) or it would end deeper than
  // hold_depth radii, or one of them met a wall in the tick and ends it clear of the walls, or
  // one is held already: its discs are then held where they meet.
  const double cross = ex * (ma.px(now) - mb.px(now)) + ey * (ma.py(now) - mb.py(now));
  const double r = std::min(discs_[a].radius, discs_[b].radius);
  const bool deep = cross <= 0.0 || gap < -hold_depth * r;
  if (deep || held_[a].on || held_[b].on) return PastCap::hold;
  // A disc that met a wall in the tick may be pressed on into it. The resting solver sees a
  // wall only where the disc ends the tick touching it; there it stops the disc approaching
  // the wall as it stops the pair (a pile's bottom row on the floor, whose holds would spread
  // up the pile through the held discs' pairs and freeze it mid-fall).
  for (const std::uint32_t k : {a, b}) {
    if (walled_[k] != 0 && !ends_on_a_wall(tick, k)) return PastCap::hold;
  }
  return PastCap::rest;
}

template <class Real>
bool DiscContacts<Real>::ends_on_a_wall(const Tick& tick, std::uint32_t k) {
  // Where its motion ends the tick, tested as the gather tests the walls there.
  const DiscMotion& m = motion_[k];
  const double r = discs_[k].radius, x = m.px(tick.dt), y = m.py(tick.dt);
  for (const PlaneDef& p : tick.planes) {
    if (on_plane(p, x, y, r)) return true;
  }
  if (tick.segments == nullptr || tick.segments->empty()) return false;
  const double reach = r * (1.0 + slop), s = tick.dt - m.t;
  const DiscOffset& o = model_offset_[k];
  const double vx = m.ux + s * m.ax - o.x, vy = m.uy + s * m.ay - o.y;  // the integrator's
  tick.segments->query(x - reach, y - reach, x + reach, y + reach, wall_found_);
  SegmentTouch t;
  for (const std::uint32_t i : wall_found_) {
    if (rests_on_segment(tick, k, i, x, y, vx, vy, t)) return true;
  }
  return false;
}

template <class Real>
void DiscContacts<Real>::release(std::uint32_t k) {
  HeldMotion& h = held_[k];
  DiscMotion& m = motion_[k];
  m.ux = h.ux, m.uy = h.uy, m.ax = h.ax, m.ay = h.ay;
  h.on = 0, h.released = 1;
}

template <class Real>
std::size_t DiscContacts<Real>::hold_pair(ImpactLane& q, std::uint32_t pair, double now) {
  const std::uint32_t a = pairs_[pair].a, b = pairs_[pair].b;
  for (const std::uint32_t k : {a, b}) {  // a kinematic partner would move on into it
    const DiscMotion& m = motion_[k];
    if (!discs_[k].dynamic && (m.ux != 0.0 || m.uy != 0.0 || m.ax != 0.0 || m.ay != 0.0)) {
      return 0;
    }
  }
  std::size_t held = 0;
  for (const std::uint32_t k : {a, b}) {
    if (!discs_[k].dynamic || held_[k].on || held_[k].released) continue;
    DiscMotion& m = motion_[k];
    m.advance(now);
    held_[k] = HeldMotion{m.ux, m.uy, m.ax, m.ay, 1};
    q.held.push_back(k);
    m.ux = m.uy = m.ax = m.ay = 0.0;
    ++stamp_[k], changed_[k] = 1;
    ++held;
  }
  return held;
}

}  // namespace fixstep::detail
