// Disc contacts, phase 1, continued: walls (planes and segments) within the disc impacts. The
// plane pass (world_contacts.cpp) meets each disc's walls on its free motion before the discs'
// impacts; a disc whose motion an impact changes afterwards meets them here, on its new motion,
// at their time of impact and in time order with the disc pairs' (see disc_contacts.hpp), so that
// a disc another drives into a wall does not pass through it. A wall impact is resolved as the
// plane pass resolves it (plane_contact.hpp: Newton's restitution, Coulomb friction, a rest on
// the wall when the bounce would be less than a tick of the normal acceleration); a segment is
// met as the plane of its closest feature (segment_set.hpp), a segment a kinematic body carries
// in its own frame, its work external. Past max_impacts impacts of the disc in the tick, only
// bounces are resolved (a rest is the resting solver's, as in the plane pass), and an inelastic
// wall that the disc would end the tick inside holds it where it meets it, as a pair past the
// cap does (disc_holds.cpp).
#include <cmath>
#include <limits>

#include "disc_contacts.hpp"
#include "plane_contact.hpp"
#include "segment_set.hpp"

namespace fixstep::detail {

namespace {

/// The tolerance of plane_contact's tests, relative to the coordinates (as the plane pass's).
template <class Real>
constexpr double wall_rel = 8.0 * double(std::numeric_limits<Real>::epsilon());

}  // namespace

template <class Real>
bool DiscContacts<Real>::next_wall_event(const Tick& tick, std::uint32_t k, double now, double dt,
                                         DiscEvent& out, std::uint64_t& looked) {
  using plane_contact::V2;
  // The box of its path from now to the tick's end (beyond the window the impacts run in, whose
  // boxes_ hold only that window's), padded by the radius and more.
  const DiscMotion& d = motion_[k];
  const double s0 = now - d.t;  // the motion at now
  const SweptBox box = path_box(d, now, dt, box_pad(discs_[k]));
  // The box's nearest corner clear of the plane: the path cannot meet it.
  auto clear = [&box](const PlaneDef& pl) {
    const double nx = pl.normal.x, ny = pl.normal.y;
    return nx * (nx > 0.0 ? box.min_x : box.max_x) + ny * (ny > 0.0 ? box.min_y : box.max_y) >
           pl.offset;
  };
  bool near = tick.segments && !tick.segments->empty();
  for (std::size_t p = 0; p < tick.planes.size() && !near; ++p) near = !clear(tick.planes[p]);
  looked += tick.planes.size();
  if (!near) return false;
  const double r = discs_[k].radius, h = dt - now, rel = wall_rel<Real>;
  const V2 x{d.px(now), d.py(now)}, v{d.ux + s0 * d.ax, d.uy + s0 * d.ay}, a{d.ax, d.ay};
  const double vtol =
      rel * (plane_contact::norm(v) + plane_contact::norm(a) * dt + plane_contact::norm(x) / dt);
  double first = std::numeric_limits<double>::infinity();
  std::uint32_t wall = 0;
  // Meeting a wall slower than the slop in a tick is resting contact (the resting solver's, as
  // for a pair): a disc on the floor that another presses on has no event.
  const double rest = slop * r / dt;
  auto impact_speed = [&](V2 n, V2 u, double s) {
    return -plane_contact::dot(n, (v - u) + s * a) > rest + vtol;
  };
  for (std::size_t p = 0; p < tick.planes.size(); ++p) {
    const PlaneDef& pl = tick.planes[p];
    if (clear(pl)) continue;
    const V2 n{pl.normal.x, pl.normal.y};
    const double nx = plane_contact::dot(n, x);
    const double tol = rel * (std::abs(nx) + std::abs(pl.offset) + r);
    const double s = plane_contact::first_impact(nx - pl.offset - r, plane_contact::dot(n, v),
                                                 plane_contact::dot(n, a), h, tol, vtol);
    if (s < first && impact_speed(n, V2{}, s)) first = s, wall = static_cast<std::uint32_t>(p);
  }
  if (tick.segments && !tick.segments->empty()) {
    const SegmentSet& set = *tick.segments;
    const double reach = disc_reach(plane_contact::norm(v), plane_contact::norm(a), h, r);
    set.query(x.x - reach, x.y - reach, x.x + reach, x.y + reach, wall_found_);
    looked += wall_found_.size();
    const double tol = rel * (std::abs(x.x) + std::abs(x.y) + r);
    for (const std::uint32_t i : wall_found_) {
      const Vec2 u = set.velocity(i);  // met in the segment's frame (its place at the tick's start)
      const SegmentMotion m{x.x - u.x * now, x.y - u.y * now, v.x - u.x, v.y - u.y, a.x, a.y};
      SegmentTouch at;
      const double s = segment_impact(set.shapes()[i], m, r, h, tol, vtol, at);
      if (s < first && impact_speed(V2{at.nx, at.ny}, V2{u.x, u.y}, s) &&
          segment_acts(set.shapes()[i], x0_[k], y0_[k], r, at.nx, at.ny, 0.0)) {
        first = s, wall = static_cast<std::uint32_t>(tick.planes.size() + i);
      }
    }
  }
  if (!(first <= h)) return false;
  out = DiscEvent{now + first, wall_event | k, stamp_[k], wall};
  return true;
}

template <class Real>
void DiscContacts<Real>::predict_wall(ImpactLane& q, const Tick& tick, std::uint32_t k, double now,
                                      double dt, std::uint64_t& looked) {
  if (discs_[k].plane_slot < 0 || held_[k].on) return;
  DiscEvent ev;
  if (!next_wall_event(tick, k, now, dt, ev, looked)) return;
  q.heap.push_back(ev);
  std::push_heap(q.heap.begin(), q.heap.end(), later_event);
}

template <class Real>
bool DiscContacts<Real>::wall_plane(const Tick& tick, std::uint32_t k, std::uint32_t wall,
                                    double now, PlaneDef& plane, Vec2& u) const {
  if (wall < tick.planes.size()) {
    plane = tick.planes[wall], u = Vec2{};
    return true;
  }
  const std::uint32_t i = wall - static_cast<std::uint32_t>(tick.planes.size());
  const SegmentShape& s = tick.segments->shapes()[i];
  u = tick.segments->velocity(i);
  const DiscMotion& m = motion_[k];
  SegmentTouch t;
  if (!segment_touch(s, m.px(now) - u.x * now, m.py(now) - u.y * now, t)) return false;
  const bool moving = u.x != 0.0 || u.y != 0.0;
  const double offset = t.offset + (t.nx * u.x + t.ny * u.y) * now;  // where it is now
  plane = PlaneDef{Vec2{t.nx, t.ny}, moving ? offset : t.offset, s.restitution, s.friction};
  return true;
}

template <class Real>
typename DiscContacts<Real>::WallOutcome DiscContacts<Real>::wall_impact(
    ImpactLane& q, const Tick& tick, std::uint32_t k, std::uint32_t wall, double now) {
  using plane_contact::V2;
  const double dt = tick.dt;
  PlaneDef plane;
  Vec2 u;
  if (!wall_plane(tick, k, wall, now, plane, u)) return WallOutcome::none;
  DiscMotion& d = motion_[k];
  d.advance(now);
  walled_[k] = 1;
  const Disc& disc = discs_[k];
  const V2 n{plane.normal.x, plane.normal.y};
  if (impacts_[k] >= max_impacts) {
    // Past the cap, as in the plane pass, a rest is left to the resting solver (in a corner it
    // recurs without end), and a disc that would end the tick inside an inelastic wall (deeper
    // than the slop, for a rest) is held where it meets it.
    const double s = dt - now;
    const V2 end{d.x + s * (d.ux + 0.5 * s * d.ax) - u.x * s,
                 d.y + s * (d.uy + 0.5 * s * d.ay) - u.y * s};
    const double gap = plane_contact::dot(n, end) - plane.offset - disc.radius;
    const plane_contact::Motion seen{V2{d.x, d.y}, V2{d.ux - u.x, d.uy - u.y}, V2{d.ax, d.ay},
                                     V2{model_offset_[k].x, model_offset_[k].y}, now};
    const bool bounce = plane_contact::bounces(seen, 0.0, plane, dt);
    const bool inside = bounce ? plane.restitution < 1.0 && gap < 0.0 : gap < -slop * disc.radius;
    if (inside && held_[k].released) return WallOutcome::none;  // the resting solver's
    if (inside) {
      held_[k] = HeldMotion{d.ux, d.uy, d.ax, d.ay, 1};
      q.held.push_back(k);
      d.ux = d.uy = d.ax = d.ay = 0.0;
      ++stamp_[k], changed_[k] = 1;
      return WallOutcome::held;
    }
    if (!bounce) return WallOutcome::none;
  }
  plane_contact::Motion m{V2{d.x, d.y}, V2{d.ux, d.uy}, V2{d.ax, d.ay},
                          V2{model_offset_[k].x, model_offset_[k].y}, now};
  plane_contact::Spin turn;
  plane_contact::Spin* spin = nullptr;
  if (rolling_ && disc.inv_inertia > 0.0) {
    turn =
        plane_contact::Spin{ew_[k], disc.radius * disc.radius * disc.inv_inertia / disc.inv_mass};
    spin = &turn;
  }
  double work = 0.0;
  (void)plane_contact::impact_moving(m, plane, disc.radius, dt, spin, V2{u.x, u.y}, work);
  if (spin) ew_[k] = turn.w;
  if (work != 0.0) external_[k] += work / disc.inv_mass;  // J/kg to J
  d.x = m.x.x, d.y = m.x.y, d.ux = m.v.x, d.uy = m.v.y, d.ax = m.a.x, d.ay = m.a.y;
  model_offset_[k] = DiscOffset{m.offset.x, m.offset.y};
  ++stamp_[k], ++impacts_[k], changed_[k] = 1;
  return WallOutcome::impact;
}

}  // namespace fixstep::detail
