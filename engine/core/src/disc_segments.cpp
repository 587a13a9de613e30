// Disc contacts, phase 2, with segments: each segment a disc touches at the tick's end is a
// resting contact as a plane is (disc_gather.cpp), along the normal of its closest feature
// under the ghost-vertex rule (segment_set.hpp), so that a polyline's joints catch nothing. A
// segment a kinematic body carries is where its body has moved it by the tick's end (u dt on
// from where the tick found it), and the contact's target is its velocity u: the impulses stop
// the disc approaching it and sliding along it relative to u, and their work J·u is the
// body's (external_).
#include <cmath>

#include "disc_contacts.hpp"

namespace fixstep::detail {

template <class Real>
void DiscContacts<Real>::gather_segment_contacts(const Tick& tick, std::uint32_t k) {
  const Disc& d = discs_[k];
  const double reach = d.radius * (1.0 + slop);
  const double x = ex_[k], y = ey_[k];
  tick.segments->query(x - reach, y - reach, x + reach, y + reach, segments_near_);
  const auto base = static_cast<std::uint32_t>(discs_.size() + tick.planes.size());
  for (const std::uint32_t i : segments_near_) {
    const SegmentShape& s = tick.segments->shapes()[i];
    const Vec2 u = tick.segments->velocity(i);
    SegmentTouch t;
    if (!rests_on_segment(tick, k, i, x, y, evx_[k], evy_[k], t)) continue;
    const bool moves = u.x != 0.0 || u.y != 0.0;  // its velocity is wall_velocity()'s
    kinematic_contacts_ = kinematic_contacts_ || moves;
    if (moves) on_moving_segment_.push_back(k);
    contacts_.push_back(wall_contact(k, base + i, t.nx, t.ny, s.friction));
  }
}

template <class Real>
bool DiscContacts<Real>::rests_on_segment(const Tick& tick, std::uint32_t k, std::uint32_t i,
                                          double x, double y, double vx, double vy,
                                          SegmentTouch& t) const {
  const double r = discs_[k].radius;
  const SegmentShape& s = tick.segments->shapes()[i];
  const Vec2 u = tick.segments->velocity(i);
  if (!segment_touch(s, x - u.x * tick.dt, y - u.y * tick.dt, t)) return false;  // a neighbour's
  const double gap = t.distance - r;
  if (gap > slop * r) return false;
  if (!segment_acts(s, x0_[k], y0_[k], r, t.nx, t.ny, gap)) return false;  // one-way
  // Still apart and closing faster than a tick of acceleration: the next tick's impact.
  const double vn = (vx - u.x) * t.nx + (vy - u.y) * t.ny;
  const double cn = motion_[k].ax * t.nx + motion_[k].ay * t.ny;
  return !(gap > 0.0 && -vn > std::abs(cn) * tick.dt);
}

template <class Real>
double DiscContacts<Real>::segment_overlap_of(const Tick& tick, const RestContact& c, double& nx,
                                              double& ny) const {
  const auto base = discs_.size() + tick.planes.size();
  const SegmentShape& s = tick.segments->shapes()[c.b - base];
  const Vec2 u = wall_velocity(tick, c);
  const double x = ex_[c.a] - u.x * tick.dt, y = ey_[c.a] - u.y * tick.dt;
  SegmentTouch t;
  nx = c.nx, ny = c.ny;
  if (!segment_touch(s, x, y, t)) return 0.0;  // moved where a neighbour holds it
  nx = t.nx, ny = t.ny;
  return c.radii - t.distance;
}

}  // namespace fixstep::detail
