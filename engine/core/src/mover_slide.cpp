// The character mover's collide-and-slide (mover_slide.hpp; docs/MOVER.md): contacts and what
// they are to a walker, the plane solver, the sweep, and the rounds of the slide. Only
// + - * / and sqrt.
#include "mover_slide.hpp"

#include <algorithm>
#include <cmath>

#include "one_way.hpp"

namespace fixstep::detail {

namespace {

/// A corner lies within this distance of a polygon's or segment's vertex (m): GJK's closest
/// point at a vertex is that vertex, up to the rounding of a rounded shape's radius.
constexpr double mover_vertex_tolerance = 1e-9;
/// Sweeps of the plane solver (Box2D's b2SolvePlanes: 20) and rounds of the slide (its Mover
/// sample: 5).
constexpr int mover_solver_sweeps = 20;
constexpr int mover_slide_rounds = 5;

/// Which of c's vertices the core point p is (-1: none, the contact is on a face).
int mover_vertex_of(const Convex& c, Vec2 p) {
  for (int i = 0; i < c.count; ++i) {
    const Vec2 d = p - c.vertices[i];
    if (dot(d, d) <= mover_vertex_tolerance * mover_vertex_tolerance) return i;
  }
  return -1;
}

/// The face beside vertex i of obstacle o that faces n (the contact normal) and points most
/// nearly up; false when none faces n. A polygon's two edges at i; a segment's two sides and
/// the sides of the chain's neighbour at that end.
bool mover_corner_face(const MoverObstacle& o, int i, Vec2 n, Vec2& best) {
  Vec2 faces[4];
  int count = 0;
  const Convex& c = o.convex;
  if (c.count >= 3) {
    faces[count++] = c.normals[(i + c.count - 1) % c.count];
    faces[count++] = c.normals[i];
  } else {
    faces[count++] = c.normals[0];
    faces[count++] = c.normals[1];
    const Vec2 g = o.ghost[i];
    if (o.ghosts & (1 << i)) faces[count++] = g, faces[count++] = -g;
  }
  bool found = false;
  for (int k = 0; k < count; ++k) {
    if (!(dot(faces[k], n) > 0.0)) continue;
    if (!found || faces[k].y > best.y) best = faces[k], found = true;
  }
  return found;
}

/// What a contact of normal n is by its angle alone.
MoverSurface mover_surface_of(Vec2 n, double cos_floor) {
  if (n.y >= cos_floor) return MoverSurface::floor;
  if (n.y <= -cos_floor) return MoverSurface::ceiling;
  return MoverSurface::wall;
}

/// Classifies c: a sharp or rounded corner of a polygon or segment under the mover is a ledge
/// (stood on, its face's normal as the floor's) when a face beside it is a floor and it is no
/// higher than step_height above the mover's foot; a corner higher than that is a wall however
/// its normal leans. Anything else by its normal's angle.
void mover_classify(const MoverGeometry& g, const MoverObstacle& o, double foot, MoverContact& c) {
  c.support = c.normal;
  c.surface = mover_surface_of(c.normal, g.cos_floor);
  const bool cornered = !o.plane && (o.convex.count >= 3 || o.segment);
  if (!cornered || !(c.normal.y > 0.0)) return;
  const Vec2 core = c.point - o.convex.radius * c.normal;
  const int i = mover_vertex_of(o.convex, core);
  if (i < 0) return;
  Vec2 face{};
  const bool floor_face = mover_corner_face(o, i, c.normal, face) && face.y >= g.cos_floor;
  const double height = o.convex.vertices[i].y + o.convex.radius;
  if (floor_face && height <= foot + g.def.step_height + mover_vertex_tolerance) {
    c.surface = MoverSurface::ledge;
    c.support = face;
  } else if (c.surface == MoverSurface::floor) {
    c.surface = MoverSurface::wall;  // a corner above the step height
  }
}

/// The capsule at `position` against the half-plane of o: its deepest core vertex.
bool mover_plane_contact(const MoverGeometry& g, const MoverObstacle& o, Vec2 position,
                         MoverContact& c) {
  const Vec2 n = o.plane_normal;
  double least = INFINITY;
  Vec2 at{};
  for (int i = 0; i < g.capsule.count; ++i) {
    const Vec2 w = position + g.capsule.vertices[i];
    const double s = dot(n, w) - o.plane_offset - g.capsule.radius;
    if (s < least) least = s, at = w;
  }
  c.normal = n;
  c.distance = least;
  c.point = at - (dot(n, at) - o.plane_offset) * n;
  return least <= 2.0 * g.def.skin;
}

}  // namespace

Vec2 mover_push_direction(const MoverContact& c, bool walking) {
  switch (c.surface) {
    case MoverSurface::floor:
      return Vec2{0.0, 1.0};  // stands: no sliding down a floor (Godot's floor_stop_on_slope)
    case MoverSurface::ledge:
      return c.normal;  // rolls over the corner
    case MoverSurface::wall:
      // Walking, a wall too steep to climb stops it without lifting it (floor_block_on_wall).
      if (walking && c.normal.y > 0.0) return Vec2{c.normal.x < 0.0 ? -1.0 : 1.0, 0.0};
      return c.normal;
    case MoverSurface::ceiling:
      return c.normal;
  }
  return c.normal;
}

void MoverSlide::contacts(const MoverGeometry& g, std::span<const MoverObstacle> obstacles,
                          Vec2 position, std::vector<MoverContact>& out) const {
  out.clear();
  const double foot = position.y + g.lowest - g.def.skin;
  const Pose at{position, Rot{}};
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const MoverObstacle& o = obstacles[k];
    MoverContact c;
    c.obstacle = static_cast<std::uint32_t>(k);
    if (o.plane) {
      if (!mover_plane_contact(g, o, position, c)) continue;
    } else {
      const Distance d = distance(g.capsule, at, o.convex, Pose{});
      if (d.overlap || d.distance > 2.0 * g.def.skin) continue;  // cores crossed: left alone
      c.normal = -d.normal;
      c.distance = d.distance;
      c.point = d.point_b;
      if (o.one_way && !(dot(c.normal, o.up) > one_way_min_dot)) continue;  // from below, aside
    }
    c.need = g.def.skin - c.distance;
    if (o.dynamic) c.need = std::min(c.need, 0.0);
    mover_classify(g, o, foot, c);
    out.push_back(c);
  }
}

double MoverSlide::cast(const MoverGeometry& g, std::span<const MoverObstacle> obstacles,
                        Vec2 position, Vec2 delta, Entity skip) const {
  const double skin = g.def.skin;
  const double tolerance = skin * 1e-3;
  double fraction = 1.0;
  const Sweep sweep{position, position + delta, 0.0, 0.0};
  const Sweep still{};
  // Starting within skin of something, it may still move along it or away, as far as the
  // plane solver allows (n·delta >= skin - distance); deeper, it does not move at all.
  auto deeper = [&](Vec2 n, double dist, bool dynamic) {
    const double need = dynamic ? std::min(skin - dist, 0.0) : skin - dist;
    return dot(n, delta) < need - 1e-12;
  };
  for (const MoverObstacle& o : obstacles) {
    if (!skip.is_null() && o.entity == skip) continue;
    if (o.plane) {
      const double rate = dot(o.plane_normal, delta);
      for (int i = 0; i < g.capsule.count; ++i) {
        const Vec2 w = position + g.capsule.vertices[i];
        const double s = dot(o.plane_normal, w) - o.plane_offset - g.capsule.radius;
        if (s <= skin) {
          if (deeper(o.plane_normal, s, false)) fraction = 0.0;
        } else if (rate < 0.0) {
          fraction = std::min(fraction, (s - skin) / -rate);
        }
      }
      continue;
    }
    // What it touches (within 2·skin) the plane solver has already kept it from: it stops
    // only if the motion still goes deeper (a sweep along a face it touches would crawl: the
    // advancement's steps shrink with the gap). The rest by conservative advancement.
    const Distance d = distance(g.capsule, Pose{position, Rot{}}, o.convex, Pose{});
    if (d.overlap) continue;  // cores crossed: left alone, as by contacts()
    if (o.one_way && !(dot(-d.normal, o.up) > one_way_min_dot)) continue;
    if (d.distance <= 2.0 * skin) {
      if (deeper(-d.normal, d.distance, o.dynamic)) fraction = 0.0;
      continue;
    }
    const Toi toi = time_of_impact(g.capsule, sweep, o.convex, still, skin, tolerance, fraction);
    if (toi.hit) fraction = std::min(fraction, toi.t);
  }
  return fraction;
}

Vec2 MoverSlide::solve(std::span<const MoverContact> contacts, Vec2 target, bool walking) const {
  double pushes[64] = {};
  const std::size_t n = std::min<std::size_t>(contacts.size(), 64);
  Vec2 delta = target;
  for (int sweep = 0; sweep < mover_solver_sweeps; ++sweep) {
    double total = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const MoverContact& c = contacts[k];
      Vec2 dir = mover_push_direction(c, walking);
      double along = dot(c.normal, dir);
      if (!(along > 1e-9)) dir = c.normal, along = 1.0;
      const double separation = dot(c.normal, delta) - c.need;
      const double next = std::max(pushes[k] - separation / along, 0.0);
      const double change = next - pushes[k];
      pushes[k] = next;
      delta += change * dir;
      total += std::abs(change);
    }
    if (total < 1e-12) break;
  }
  return delta;
}

Vec2 MoverSlide::slide(const MoverGeometry& g, std::span<const MoverObstacle> obstacles,
                       Vec2 position, Vec2 delta, bool walking) {
  const Vec2 target = position + delta;
  Vec2 p = position;
  for (int round = 0; round < mover_slide_rounds; ++round) {
    contacts(g, obstacles, p, contacts_);
    const Vec2 solved = solve(contacts_, target - p, walking);
    if (dot(solved, solved) < 1e-24) break;
    const double f = cast(g, obstacles, p, solved, Entity{});
    p += f * solved;
    if (f >= 1.0 || f * std::sqrt(dot(solved, solved)) < 1e-9) break;
  }
  return p;
}

}  // namespace fixstep::detail
