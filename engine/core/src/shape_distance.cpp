// The distance between two convex shapes by GJK on their cores (G. van den Bergen, "A Fast and
// Robust GJK Implementation for Collision Detection of Convex Objects", JGT 4(2), 1999; the
// simplex solver by Voronoi regions and barycentric coordinates as in Box2D v3.2 src/distance.c
// b2ShapeDistance), and the time of impact of two moving shapes by conservative advancement
// (B. Mirtich, "Impulse-based Dynamic Simulation of Rigid Body Systems", PhD thesis, 1996, ch. 3).
// Our own code; only + - * / and sqrt, and det::sin / det::cos in pose_at.
#include <cmath>

#include "shape_geom.hpp"

namespace fixstep::detail {

namespace {

/// Most GJK iterations: a pair of polygons of 8 vertices needs far fewer (each iteration adds a
/// vertex of the Minkowski difference not in the simplex; a repeat ends the search).
constexpr int gjk_max_iterations = 32;
/// Cores closer than this (m) touch: the origin is on the simplex.
constexpr double gjk_touch = 1e-12;
/// Most distance evaluations of one time of impact (shape_geom.hpp).
constexpr int toi_max_iterations = 64;

/// One vertex of the simplex: a support point of each core and their difference w = wb - wa,
/// with its barycentric weight.
struct GjkVertex {
  Vec2 wa{}, wb{}, w{};
  double weight = 1.0;
  int ia = 0, ib = 0;
};

struct GjkSimplex {
  GjkVertex v[3];
  int count = 1;
};

/// The world form of c at t.
Convex gjk_world(const Convex& c, const Pose& t) {
  Convex out = c;
  for (int i = 0; i < c.count; ++i) out.vertices[i] = transform(t, c.vertices[i]);
  return out;
}

/// The index of c's vertex farthest along d (the first of equals).
int gjk_support(const Convex& c, Vec2 d) {
  int best = 0;
  double far = dot(c.vertices[0], d);
  for (int i = 1; i < c.count; ++i) {
    const double x = dot(c.vertices[i], d);
    if (x > far) {
      far = x;
      best = i;
    }
  }
  return best;
}

/// The closest point of segment w1..w2 to the origin, by the region it falls in.
void gjk_solve2(GjkSimplex& s) {
  const Vec2 w1 = s.v[0].w, w2 = s.v[1].w, e12 = w2 - w1;
  const double d12_2 = -dot(w1, e12);  // w1's region when <= 0
  const double d12_1 = dot(w2, e12);   // w2's region when <= 0
  if (d12_2 <= 0.0) {
    s.v[0].weight = 1.0;
    s.count = 1;
  } else if (d12_1 <= 0.0) {
    s.v[0] = s.v[1];
    s.v[0].weight = 1.0;
    s.count = 1;
  } else {
    const double inv = 1.0 / (d12_1 + d12_2);
    s.v[0].weight = d12_1 * inv;
    s.v[1].weight = d12_2 * inv;
  }
}

/// Keeps vertices i and j of the triangle with weights proportional to wi and wj.
void gjk_keep_edge(GjkSimplex& s, int i, int j, double wi, double wj) {
  const double inv = 1.0 / (wi + wj);
  const GjkVertex vi = s.v[i], vj = s.v[j];
  s.v[0] = vi;
  s.v[1] = vj;
  s.v[0].weight = wi * inv;
  s.v[1].weight = wj * inv;
  s.count = 2;
}

void gjk_keep_vertex(GjkSimplex& s, int i) {
  s.v[0] = s.v[i];
  s.v[0].weight = 1.0;
  s.count = 1;
}

/// The closest point of triangle w1 w2 w3 to the origin: a vertex, an edge or the inside.
void gjk_solve3(GjkSimplex& s) {
  const Vec2 w1 = s.v[0].w, w2 = s.v[1].w, w3 = s.v[2].w;
  const Vec2 e12 = w2 - w1, e13 = w3 - w1, e23 = w3 - w2;
  const double d12_1 = dot(w2, e12), d12_2 = -dot(w1, e12);
  const double d13_1 = dot(w3, e13), d13_2 = -dot(w1, e13);
  const double d23_1 = dot(w3, e23), d23_2 = -dot(w2, e23);
  const double n123 = cross(e12, e13);
  const double d123_1 = n123 * cross(w2, w3), d123_2 = n123 * cross(w3, w1),
               d123_3 = n123 * cross(w1, w2);
  if (d12_2 <= 0.0 && d13_2 <= 0.0) return gjk_keep_vertex(s, 0);
  if (d12_1 > 0.0 && d12_2 > 0.0 && d123_3 <= 0.0) return gjk_keep_edge(s, 0, 1, d12_1, d12_2);
  if (d13_1 > 0.0 && d13_2 > 0.0 && d123_2 <= 0.0) return gjk_keep_edge(s, 0, 2, d13_1, d13_2);
  if (d12_1 <= 0.0 && d23_2 <= 0.0) return gjk_keep_vertex(s, 1);
  if (d13_1 <= 0.0 && d23_1 <= 0.0) return gjk_keep_vertex(s, 2);
  if (d23_1 > 0.0 && d23_2 > 0.0 && d123_1 <= 0.0) return gjk_keep_edge(s, 1, 2, d23_1, d23_2);
  const double inv = 1.0 / (d123_1 + d123_2 + d123_3);
  s.v[0].weight = d123_1 * inv;
  s.v[1].weight = d123_2 * inv;
  s.v[2].weight = d123_3 * inv;
}

void gjk_solve(GjkSimplex& s) {
  if (s.count == 2) gjk_solve2(s);
  if (s.count == 3) gjk_solve3(s);
}

/// Towards the origin from the simplex's closest point; for an edge its perpendicular on the
/// origin's side, which keeps its accuracy when the edge passes near the origin (Box2D).
Vec2 gjk_search_direction(const GjkSimplex& s) {
  if (s.count == 1) return -s.v[0].w;
  const Vec2 e12 = s.v[1].w - s.v[0].w;
  return cross(e12, -s.v[0].w) > 0.0 ? Vec2{-e12.y, e12.x} : Vec2{e12.y, -e12.x};
}

bool gjk_has(const GjkSimplex& s, int ia, int ib) {
  for (int i = 0; i < s.count; ++i) {
    if (s.v[i].ia == ia && s.v[i].ib == ib) return true;
  }
  return false;
}

GjkVertex gjk_vertex(const Convex& a, const Convex& b, int ia, int ib) {
  GjkVertex v;
  v.ia = ia;
  v.ib = ib;
  v.wa = a.vertices[ia];
  v.wb = b.vertices[ib];
  v.w = v.wb - v.wa;
  return v;
}

}  // namespace

Distance distance(const Convex& a, const Pose& ta, const Convex& b, const Pose& tb) {
  const Convex wa = gjk_world(a, ta), wb = gjk_world(b, tb);
  GjkSimplex s;
  s.v[0] = gjk_vertex(wa, wb, 0, 0);
  for (int iter = 0; iter < gjk_max_iterations; ++iter) {
    gjk_solve(s);
    if (s.count == 3) break;
    const Vec2 d = gjk_search_direction(s);
    if (dot(d, d) < gjk_touch * gjk_touch) break;
    const int ia = gjk_support(wa, -d), ib = gjk_support(wb, d);
    if (gjk_has(s, ia, ib)) break;
    s.v[s.count++] = gjk_vertex(wa, wb, ia, ib);
  }
  gjk_solve(s);
  Vec2 pa{}, pb{};
  for (int i = 0; i < s.count; ++i) {
    pa += s.v[i].weight * s.v[i].wa;
    pb += s.v[i].weight * s.v[i].wb;
  }
  Distance r;
  const Vec2 gap = pb - pa;
  const double core = std::sqrt(dot(gap, gap));
  if (s.count == 3 || core < gjk_touch) {
    r.overlap = true;
    r.point_a = r.point_b = pa;
    return r;
  }
  r.normal = gap / core;
  r.distance = core - a.radius - b.radius;
  r.point_a = pa + a.radius * r.normal;
  r.point_b = pb - b.radius * r.normal;
  return r;
}

Pose pose_at(const Sweep& s, double t) {
  return {s.c0 + t * (s.c1 - s.c0), rot_of(s.a0 + t * (s.a1 - s.a0))};
}

Toi time_of_impact(const Convex& a, const Sweep& sa, const Convex& b, const Sweep& sb,
                   double target, double tolerance, double t_max) {
  // No point of a body moves faster (per unit t) than its centre's |Δc| plus |Δa| times its
  // extent, so the distance shrinks at most at the rate `bound` (the centres' relative motion
  // taken together, which is no more than the sum of the two |Δc|): advancing t by
  // (distance - target) / bound never passes the first time the distance reaches target.
  const Vec2 dc = (sb.c1 - sb.c0) - (sa.c1 - sa.c0);
  const double da = sa.a1 - sa.a0, db = sb.a1 - sb.a0;
  const double bound = std::sqrt(dot(dc, dc)) + (da < 0.0 ? -da : da) * extent(a) +
                       (db < 0.0 ? -db : db) * extent(b);
  Toi r;
  double t = 0.0;
  for (int iter = 1; iter <= toi_max_iterations; ++iter) {
    r.iterations = iter;
    const Distance d = distance(a, pose_at(sa, t), b, pose_at(sb, t));
    if (d.overlap || d.distance <= target + tolerance) {
      r.t = t;
      r.hit = true;
      return r;
    }
    if (!(bound > 0.0)) return {t_max, false, iter};
    t += (d.distance - target) / bound;
    if (t >= t_max) return {t_max, false, iter};
  }
  // Out of evaluations before they met: t is still before the first touch.
  r.t = t;
  r.hit = true;
  return r;
}

}  // namespace fixstep::detail
