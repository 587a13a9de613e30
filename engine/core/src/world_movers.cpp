// Character movers (BodyDef::mover, mover.hpp), the kernel's side: the checks at creation, the
// tick's mover phase (world_tick.cpp: after the input, before the integration), the obstacles a
// mover meets this tick and where, the pushes on dynamic bodies, and the state it leaves. The
// geometry is mover_slide.cpp; docs/MOVER.md has the method. Included by kernel_instances.cpp.
#include <fmt/format.h>

#include <cmath>

#include "fixstep/core/det_math.hpp"
#include "fixstep/core/mover.hpp"
#include "mover_slide.hpp"
#include "one_way.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {

template <class Real>
void detail::WorldKernel<Real>::check_mover(const BodyDef& def, const std::string& who) const {
  if (!def.mover) return;
  if (auto problem = mover_problem(*def.mover)) {
    throw std::invalid_argument(fmt::format("{}: mover: {}", who, *problem));
  }
  if (def.type != BodyType::kinematic) {
    throw std::invalid_argument(fmt::format("{}: mover: the body must be kinematic", who));
  }
  if (def.shapes.size() != 1 || def.shapes[0].kind != ShapeKind::capsule) {
    throw std::invalid_argument(
        fmt::format("{}: mover: the body must carry exactly one shape, a capsule", who));
  }
  if (def.body.angle != 0.0 || def.body.angular_velocity != 0.0) {
    throw std::invalid_argument(
        fmt::format("{}: mover: the body's angle and angular_velocity must be 0", who));
  }
  const double r = def.shapes[0].radius;
  if (!(def.mover->step_height < r)) {
    throw std::invalid_argument(
        fmt::format("{}: mover: step_height must be below the capsule radius {} m (got {})", who, r,
                    def.mover->step_height));
  }
  if (!(def.mover->skin < 0.5 * r)) {
    throw std::invalid_argument(
        fmt::format("{}: mover: skin must be below half the capsule radius {} m (got {})", who, r,
                    def.mover->skin));
  }
}

template <class Real>
MoverState detail::WorldKernel<Real>::mover_state(Entity e) const {
  require(e);
  if (!movers_.set.contains(e)) {
    throw std::invalid_argument("mover_state: the body is not a mover (BodyDef::mover)");
  }
  MoverState s = movers_.data[movers_.set.index(e)].state;
  const std::size_t j = bodies_.index(e);
  s.velocity = Vec2{double(vx_[j]), double(vy_[j])};
  return s;
}

template <class Real>
detail::MoverGeometry detail::WorldKernel<Real>::mover_geometry(const MoverRecord& m,
                                                                Entity e) const {
  MoverGeometry g;
  g.def = m.def;
  g.capsule = to_convex(shape_sets_.data[shape_sets_.set.index(e)].defs[0], Vec2{});
  g.lowest = std::min(g.capsule.vertices[0].y, g.capsule.vertices[1].y) - g.capsule.radius;
  g.cos_floor = det::cos(m.def.max_floor_angle);
  return g;
}

// The obstacles within `box` of the mover at dense index `self`, where this tick puts them:
// static bodies and dynamic ones where they are (the dynamic ones are pushed), kinematic ones
// where their velocity and spin take them by the tick's end, segments likewise (a carried one
// by its body's velocity), and the planes.
template <class Real>
void detail::WorldKernel<Real>::gather_mover_obstacles(std::size_t self, const Aabb& box,
                                                       const CollisionFilter& filter,
                                                       const MoverGeometry& g, Vec2 start) {
  mover_obstacles_.clear();
  // A one-way surface is met this tick only when the capsule, where the tick starts it, is on
  // its up side (one_way_blocks: its closest contact leans up, not crossing it by more than the
  // shapes' slop): from below or half-way through, it passes as if the surface were not there.
  auto above = [&](const MoverObstacle& o) {
    const Distance d = distance(g.capsule, Pose{start, Rot{}}, o.convex, Pose{});
    return !d.overlap && one_way_blocks(o.up, -d.normal, d.distance, one_way_shape_slop);
  };
  const double dt = settings_.dt;
  auto outside = [&](const Aabb& b) {
    return b.upper.x < box.lower.x || b.lower.x > box.upper.x || b.upper.y < box.lower.y ||
           b.lower.y > box.upper.y;
  };
  const ShapeWorld& w = *shape_world_;
  for (const ShapedBody& b : w.bodies_) {
    if (b.body == self) continue;
    const std::uint32_t j = b.body;
    Vec2 c{double(x_[j]), double(y_[j])};
    double angle = b.set == ShapedBody::none ? 0.0 : shape_sets_.data[b.set].angle;
    if (b.type == BodyType::kinematic) {
      c += dt * Vec2{double(vx_[j]), double(vy_[j])};
      if (b.set != ShapedBody::none) angle += dt * shape_sets_.data[b.set].spin;
    }
    const Aabb reach{c - Vec2{b.extent, b.extent}, c + Vec2{b.extent, b.extent}};
    if (outside(reach)) continue;
    const Pose pose{c, rot_of(angle)};
    for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
      const ShapeEntry& s = w.shapes_[k];
      if (s.sensor || !should_collide(filter, s.filter)) continue;
      MoverObstacle o;
      o.convex = convex_placed(s.convex, pose);
      if (outside(convex_aabb(o.convex, Pose{}))) continue;
      if (s.one_way) {
        o.one_way = true, o.up = rotate(pose.q, s.up);
        if (!above(o)) continue;
      }
      o.body = j;
      o.entity = bodies_.dense[j];
      o.dynamic = b.type == BodyType::dynamic;
      mover_obstacles_.push_back(o);
    }
  }
  if (!segments_.empty()) {
    segments_.query(box.lower.x, box.lower.y, box.upper.x, box.upper.y, mover_segments_);
    for (const std::uint32_t i : mover_segments_) {
      const SegmentDef& d = segments_.defs()[i];
      const Vec2 shift = dt * segments_.velocity(i);
      MoverObstacle o;
      o.segment = true;
      o.convex = segment_convex(d.a + shift, d.b + shift);
      auto left = [](Vec2 from, Vec2 to) {
        const Vec2 e = to - from;
        return Vec2{-e.y, e.x} / std::sqrt(dot(e, e));
      };
      if (d.prev) o.ghost[0] = left(*d.prev, d.a), o.ghosts |= 1;
      if (d.next) o.ghost[1] = left(d.b, *d.next), o.ghosts |= 2;
      o.entity = d.body;
      if (d.one_way) {
        o.one_way = true, o.up = one_way_up_of(d);
        if (!above(o)) continue;
      }
      mover_obstacles_.push_back(o);
    }
  }
  for (const PlaneDef& p : planes_) {
    MoverObstacle o;
    o.plane = true;
    o.plane_normal = p.normal;
    o.plane_offset = p.offset;
    mover_obstacles_.push_back(o);
  }
}

// A dynamic body the mover walks into gets the impulse that brings its contact point up to the
// mover's speed along the normal, at most push_force·dt (Box2D's Mover sample, PushBodies, with
// the bound): Δv = J n / m, Δω = (r × J n) / I.
template <class Real>
void detail::WorldKernel<Real>::push_by_mover(const MoverContact& c, Vec2 velocity, double limit) {
  const MoverObstacle& o = mover_obstacles_[c.obstacle];
  const std::uint32_t k = o.body;
  const Entity e = bodies_.dense[k];
  ShapeSet* set =
      shape_sets_.set.contains(e) ? &shape_sets_.data[shape_sets_.set.index(e)] : nullptr;
  const Vec2 n = -c.normal;
  const Vec2 r = c.point - Vec2{double(x_[k]), double(y_[k])};
  const double inv_m = 1.0 / mass_[k];
  const double inv_i = set ? 1.0 / set->inertia : 0.0;
  const double spin = set ? set->spin : 0.0;
  const double rn = cross(r, n);
  const Vec2 v0{double(vx_[k]), double(vy_[k])};
  const Vec2 point = v0 + Vec2{-spin * r.y, spin * r.x};
  const double gap = dot(velocity - point, n);  // how much faster the mover goes into it
  if (!(gap > 0.0)) return;
  const double impulse = std::min(gap / (inv_m + inv_i * rn * rn), limit);
  const Vec2 v1 = v0 + (impulse * inv_m) * n;
  vx_[k] = static_cast<Real>(v1.x), vy_[k] = static_cast<Real>(v1.y);
  double spin1 = spin;
  if (set) spin1 = set->spin = rounded_to<Real>(spin + inv_i * impulse * rn);
  if (sleep_ && asleep(k)) wake(k);
  if (settings_.track_dissipation) {  // the mover's work, external as a kinematic body's
    const Vec2 u{double(vx_[k]), double(vy_[k])};
    const double turn = inv_i > 0.0 ? 0.5 * (spin1 * spin1 - spin * spin) / inv_i : 0.0;
    external_work_ += 0.5 * mass_[k] * (dot(u, u) - dot(v0, v0)) + turn;
  }
}

// What the mover met at its end position: floor (the one most nearly flat), wall, ceiling;
// the velocity it keeps: on a floor its vertical part dropped (landing), otherwise clipped
// against what it moved into (b2ClipVector); walls too steep to climb clip a walker
// horizontally; dynamic bodies, which it pushes, clip nothing.
template <class Real>
void detail::WorldKernel<Real>::mover_outcome(MoverRecord& m, Vec2 v, Vec2 attempt,
                                              std::span<const MoverContact> cs) {
  MoverState& st = m.state;
  st.on_floor = st.on_wall = st.on_ceiling = false;
  st.floor_normal = st.wall_normal = Vec2{};
  st.floor_body = Entity{};
  const bool rising = v.y > 0.0;
  for (const MoverContact& c : cs) {
    const bool floor = c.surface == MoverSurface::floor || c.surface == MoverSurface::ledge;
    if (floor && !rising) {
      if (!st.on_floor || c.support.y > st.floor_normal.y) {
        st.floor_normal = c.support;
        st.floor_body = mover_obstacles_[c.obstacle].entity;
      }
      st.on_floor = true;
    } else if (!floor && dot(attempt, c.normal) < 0.0) {
      if (c.surface == MoverSurface::ceiling) {
        st.on_ceiling = true;
      } else if (!st.on_wall) {
        st.on_wall = true, st.wall_normal = c.normal;
      }
    }
  }
  Vec2 out = st.on_floor ? Vec2{v.x, 0.0} : v;
  for (const MoverContact& c : cs) {
    const bool floor = c.surface == MoverSurface::floor || c.surface == MoverSurface::ledge;
    // A dynamic body is pushed, not slid along: the mover keeps pressing into it.
    if ((floor && st.on_floor) || mover_obstacles_[c.obstacle].dynamic) continue;
    Vec2 n = c.normal;
    if (st.on_floor && n.y > 0.0) n = Vec2{n.x < 0.0 ? -1.0 : 1.0, 0.0};
    const double into = dot(out, n);
    if (into < 0.0) out -= into * n;
  }
  st.velocity = Vec2{double(static_cast<Real>(out.x)), double(static_cast<Real>(out.y))};
}

// One mover's tick: carried by its kinematic floor (translation, and the turn of its foot about
// the floor's centre; the floor itself left out of that sweep), then walked or flown by
// collide-and-slide, snapped down onto a floor within snap_distance when it walked off one, its
// contacts classified, the bodies it walked into pushed. Sets its velocity for the integration to
// the displacement over dt (so the contact solver sees it move as it does) and keeps the target.
template <class Real>
void detail::WorldKernel<Real>::move_mover(MoverRecord& m, Entity e) {
  const double dt = settings_.dt;
  const std::size_t j = bodies_.index(e);
  ShapeSet& own = shape_sets_.data[shape_sets_.set.index(e)];
  own.spin = 0.0;  // a mover never turns
  const MoverGeometry g = mover_geometry(m, e);
  const Vec2 p0{double(x_[j]), double(y_[j])};
  const Vec2 v{double(vx_[j]), double(vy_[j])};
  Vec2 carry{};
  const Entity floor = m.state.floor_body;
  if (m.state.on_floor && bodies_.contains(floor) &&
      types_[bodies_.index(floor)] == BodyType::kinematic) {
    const std::size_t k = bodies_.index(floor);
    const Vec2 c0{double(x_[k]), double(y_[k])};
    const Vec2 u{double(vx_[k]), double(vy_[k])};
    const double w =
        shape_sets_.set.contains(floor) ? shape_sets_.data[shape_sets_.set.index(floor)].spin : 0.0;
    // The point it stands on turns with the floor: the centre of the capsule's lower end,
    // which keeps its distance from the turning surface (the capsule itself does not turn).
    const int low = g.capsule.vertices[1].y < g.capsule.vertices[0].y ? 1 : 0;
    const Vec2 rel = p0 + g.capsule.vertices[low] - c0;
    carry = dt * u + (w != 0.0 ? rotate(rot_of(w * dt), rel) - rel : Vec2{});
  }
  const bool walking = m.state.on_floor && !(v.y > 0.0);
  const Vec2 n = m.state.floor_normal;
  // Walking, the wanted horizontal speed is kept along the floor (Godot's floor_constant_speed).
  const Vec2 attempt = walking ? v.x * Vec2{n.y, -n.x} : v;
  const Vec2 delta = dt * attempt;
  const double reach = std::sqrt(dot(carry, carry)) + std::sqrt(dot(delta, delta)) +
                       m.def.snap_distance + m.def.step_height + 4.0 * m.def.skin;
  const Aabb box = convex_aabb(g.capsule, Pose{p0, Rot{}}, reach * (1.0 + 1e-9) + 1e-9);
  gather_mover_obstacles(j, box, own.defs[0].filter, g, p0);
  const std::span<const MoverObstacle> obstacles = mover_obstacles_;
  Vec2 p = p0;
  if (carry.x != 0.0 || carry.y != 0.0)
    p += mover_slide_.cast(g, obstacles, p, carry, floor) * carry;
  p = mover_slide_.slide(g, obstacles, p, delta, walking);
  std::vector<MoverContact>& cs = mover_slide_.contacts_;
  mover_slide_.contacts(g, obstacles, p, cs);
  auto has_floor = [&] {
    for (const MoverContact& c : cs) {
      if (c.surface == MoverSurface::floor || c.surface == MoverSurface::ledge) return true;
    }
    return false;
  };
  if (walking && m.def.snap_distance > 0.0 && !has_floor()) {
    const Vec2 down{0.0, -m.def.snap_distance};
    const Vec2 snapped = p + mover_slide_.cast(g, obstacles, p, down, Entity{}) * down;
    mover_slide_.contacts(g, obstacles, snapped, cs);
    if (has_floor()) {
      p = snapped;
    } else {
      mover_slide_.contacts(g, obstacles, p, cs);
    }
  }
  mover_outcome(m, v, attempt, cs);
  if (m.def.push_force > 0.0) {
    for (const MoverContact& c : cs) {
      if (mover_obstacles_[c.obstacle].dynamic && dot(attempt, c.normal) < 0.0) {
        push_by_mover(c, attempt, m.def.push_force * dt);
      }
    }
  }
  m.target = Vec2{double(static_cast<Real>(p.x)), double(static_cast<Real>(p.y))};
  m.state.displacement = m.target - p0;
  vx_[j] = static_cast<Real>(m.state.displacement.x / dt);
  vy_[j] = static_cast<Real>(m.state.displacement.y / dt);
}

template <class Real>
void detail::WorldKernel<Real>::move_movers() {
  for (std::size_t i = 0; i < movers_.data.size(); ++i) {
    move_mover(movers_.data[i], movers_.set.dense[i]);
  }
}

// After the integration: each mover exactly where its slide left it (the integrator's
// x0 + v dt rounds).
template <class Real>
void detail::WorldKernel<Real>::place_movers() {
  for (std::size_t i = 0; i < movers_.data.size(); ++i) {
    const std::size_t j = bodies_.index(movers_.set.dense[i]);
    x_[j] = static_cast<Real>(movers_.data[i].target.x);
    y_[j] = static_cast<Real>(movers_.data[i].target.y);
  }
}

// At the tick's end: each mover's velocity is its slid velocity (MoverState::velocity).
template <class Real>
void detail::WorldKernel<Real>::finish_movers() {
  for (std::size_t i = 0; i < movers_.data.size(); ++i) {
    const std::size_t j = bodies_.index(movers_.set.dense[i]);
    vx_[j] = static_cast<Real>(movers_.data[i].state.velocity.x);
    vy_[j] = static_cast<Real>(movers_.data[i].state.velocity.y);
  }
}

}  // namespace fixstep
