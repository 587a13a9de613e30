// The manifold of two convex shapes given in one frame: the separating axis test over both
// shapes' edge normals, reference-face clipping of the incident edge (Catto, "Contact
// Manifolds", GDC 2007; Box2D v3.2 src/manifold.c b2CollidePolygons and b2ClipPolygons), and
// the closest points of the two cores where the cores are apart and the closest features are
// two vertices (Box2D's vertex-vertex fallback) or where neither shape has an area (circles and
// capsules: the SAT over their edge normals misses the axis along a segment, Box2D's
// b2CollideCapsules). Our own code; only + - * / and sqrt.
//
// Feature ids (ManifoldPoint::id), stable while the same features meet:
//   bits 0-7   the reference edge (clipping) or A's vertex (closest points),
//   bits 8-15  the incident vertex the point comes from or B's vertex (closest points),
//   bits 16-17 0: A holds the reference edge, 1: B holds it, 2: closest points of two cores.
#include <cmath>
#include <limits>

#include "shape_geom.hpp"

namespace fixstep::detail {

// Declared where they are used (shape_collide.cpp, shape_segment.cpp).
Manifold collide_placed(const Convex& a, const Convex& b, double speculative);
Manifold clip_reference(const Convex& ref, int edge, const Convex& inc, bool flip,
                        double speculative);

namespace {

/// Preference for A's reference face (m): B's face must separate by this much more, so a
/// resting pair does not flip between two nearly equal axes from tick to tick (Box2D: a tenth
/// of its linear slop).
constexpr double clip_axis_tolerance = 5e-4;
/// Clipping may give points farther apart than the closest points of the cores (two vertices
/// nearest): beyond this much (m) the closest points make the one contact (Box2D likewise).
constexpr double clip_vertex_tolerance = 5e-4;

std::uint32_t clip_id(int first, int second, int kind) {
  return static_cast<std::uint32_t>(first) | (static_cast<std::uint32_t>(second) << 8U) |
         (static_cast<std::uint32_t>(kind) << 16U);
}

int clip_next(const Convex& c, int i) {
  return i + 1 < c.count ? i + 1 : 0;
}

struct ClipAxis {
  double separation = -std::numeric_limits<double>::infinity();
  int edge = 0;
};

/// The edge normal of p1 along which p2 lies farthest out (SAT), the cores' separation on it.
/// A single vertex has no edges: -inf.
ClipAxis clip_max_separation(const Convex& p1, const Convex& p2) {
  ClipAxis best;
  if (p1.count < 2) return best;
  for (int i = 0; i < p1.count; ++i) {
    double si = std::numeric_limits<double>::infinity();
    for (int j = 0; j < p2.count; ++j) {
      const double s = dot(p1.normals[i], p2.vertices[j] - p1.vertices[i]);
      if (s < si) si = s;
    }
    if (si > best.separation) best = {si, i};
  }
  return best;
}

/// The edge of `inc` whose normal is most anti-parallel to `n` (0 for a single vertex).
int clip_incident_edge(const Convex& inc, Vec2 n) {
  if (inc.count < 2) return 0;
  int best = 0;
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < inc.count; ++i) {
    const double d = dot(n, inc.normals[i]);
    if (d < lowest) {
      lowest = d;
      best = i;
    }
  }
  return best;
}

/// The closest points c1 = p1 + f1 (q1 - p1) and c2 = p2 + f2 (q2 - p2) of two segments, either
/// of which may be a point (Box2D's b2SegmentDistance: clamp on one, project, clamp the other).
struct ClipClosest {
  Vec2 c1{}, c2{};
  double f1 = 0.0, f2 = 0.0;
};
double clip_clamp01(double x) {
  return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);
}
ClipClosest clip_segment_closest(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2) {
  const Vec2 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double dd1 = dot(d1, d1), dd2 = dot(d2, d2), rd1 = dot(r, d1), rd2 = dot(r, d2);
  ClipClosest c;
  if (dd1 == 0.0 && dd2 == 0.0) {
    // two points
  } else if (dd1 == 0.0) {
    c.f2 = clip_clamp01(rd2 / dd2);
  } else if (dd2 == 0.0) {
    c.f1 = clip_clamp01(-rd1 / dd1);
  } else {
    const double d12 = dot(d1, d2), denom = dd1 * dd2 - d12 * d12;
    c.f1 = denom != 0.0 ? clip_clamp01((d12 * rd2 - rd1 * dd2) / denom) : 0.0;
    c.f2 = (d12 * c.f1 + rd2) / dd2;
    if (c.f2 < 0.0) {
      c.f2 = 0.0;
      c.f1 = clip_clamp01(-rd1 / dd1);
    } else if (c.f2 > 1.0) {
      c.f2 = 1.0;
      c.f1 = clip_clamp01((d12 - rd1) / dd1);
    }
  }
  c.c1 = p1 + c.f1 * d1;
  c.c2 = p2 + c.f2 * d2;
  return c;
}

/// One contact at the closest points c1 (on A's core, A vertex ia) and c2 (B's core, vertex
/// ib), `fallback` the normal when the cores touch there.
Manifold clip_single(const ClipClosest& c, int ia, int ib, double ra, double rb, Vec2 fallback,
                     double speculative) {
  Manifold m;
  const Vec2 d = c.c2 - c.c1;
  const double dist = std::sqrt(dot(d, d));
  if (dist - ra - rb > speculative) return m;
  m.normal = dist > 0.0 ? d / dist : fallback;
  const Vec2 sa = c.c1 + ra * m.normal, sb = c.c2 - rb * m.normal;
  m.points[0].point = 0.5 * (sa + sb);
  m.points[0].separation = dist - ra - rb;
  m.points[0].id = clip_id(ia, ib, 2);
  m.count = 1;
  return m;
}

/// Moves x (at tangent coordinate sx) along x..y (sy) to the coordinate `bound`.
Vec2 clip_to(Vec2 x, double sx, Vec2 y, double sy, double bound) {
  return x + ((bound - sx) / (sy - sx)) * (y - x);
}

/// An end of the incident edge (moved onto the reference edge's span when it lay outside) and
/// the incident vertex it comes from, which names the point's id.
struct ClipEnd {
  Vec2 at{};
  int vertex = 0;
};
}  // namespace

/// Reference edge `edge` of `ref`, the incident edge of `inc` clipped to its span (Catto 2007):
/// up to two points, each kept when its separation (radii included) is within `speculative`.
/// The normal is ref's edge normal, negated when `flip` (ref is B).
Manifold clip_reference(const Convex& ref, int edge, const Convex& inc, bool flip,
                        double speculative) {
  Manifold m;
  const Vec2 n = ref.normals[edge];
  const Vec2 t{-n.y, n.x};  // along edge -> edge + 1 (counter-clockwise winding)
  const Vec2 v11 = ref.vertices[edge];
  const double upper1 = dot(ref.vertices[clip_next(ref, edge)] - v11, t);
  const int i21 = clip_incident_edge(inc, n);
  const int i22 = clip_next(inc, i21);
  ClipEnd e[2] = {{inc.vertices[i21], i21}, {inc.vertices[i22], i22}};
  const int ends = inc.count < 2 ? 1 : 2;
  const double s0 = dot(e[0].at - v11, t), s1 = dot(e[1].at - v11, t);
  if ((s0 < 0.0 && s1 < 0.0) || (s0 > upper1 && s1 > upper1)) return m;
  const Vec2 a0 = e[0].at, a1 = e[1].at;
  if (s0 < 0.0) e[0].at = clip_to(a0, s0, a1, s1, 0.0);
  if (s0 > upper1) e[0].at = clip_to(a0, s0, a1, s1, upper1);
  if (s1 < 0.0) e[1].at = clip_to(a1, s1, a0, s0, 0.0);
  if (s1 > upper1) e[1].at = clip_to(a1, s1, a0, s0, upper1);
  const double radius = ref.radius + inc.radius;
  m.normal = flip ? -n : n;
  // Both ends clipped onto one point (an end exactly at the span's bound): one contact.
  const int kept = ends == 2 && e[0].at == e[1].at ? 1 : ends;
  for (int k = 0; k < kept; ++k) {
    const double core = dot(e[k].at - v11, n);
    if (core - radius > speculative) continue;
    ManifoldPoint& p = m.points[m.count++];
    // Midway between the surfaces: the reference one lies core - ref.radius behind e along n,
    // the incident one inc.radius behind it.
    p.point = e[k].at + (0.5 * (ref.radius - inc.radius - core)) * n;
    p.separation = core - radius;
    p.id = clip_id(edge, e[k].vertex, flip ? 1 : 0);
  }
  return m;
}

namespace {

/// The smallest core separation along the normal of the points `m` would have had (any
/// speculative limit aside): clip_reference with an infinite limit.
double clip_min_core(const Manifold& m, double radius) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.count; ++i) {
    const double core = m.points[i].separation + radius;
    if (core < lowest) lowest = core;
  }
  return lowest;
}

/// Clipping, unless the cores are apart by noticeably less than the clipped points are (the
/// closest features are two vertices): then the one contact at the closest points.
Manifold clip_or_closest(const Convex& a, const Convex& b, int edge_a, int edge_b, bool flip,
                         const ClipClosest& c, int ia, int ib, double speculative) {
  const double radius = a.radius + b.radius;
  const Vec2 d = c.c2 - c.c1;
  const double dist = std::sqrt(dot(d, d));
  const Vec2 fallback = flip ? -b.normals[edge_b] : a.normals[edge_a];
  const Manifold all =
      flip ? clip_reference(b, edge_b, a, true, std::numeric_limits<double>::max())
           : clip_reference(a, edge_a, b, false, std::numeric_limits<double>::max());
  const bool apart = dist > 0.0;
  if (all.count == 0 || (apart && clip_min_core(all, radius) > dist + clip_vertex_tolerance)) {
    return clip_single(c, ia, ib, a.radius, b.radius, fallback, speculative);
  }
  Manifold m = all;
  m.count = 0;
  for (int i = 0; i < all.count; ++i) {
    if (all.points[i].separation <= speculative) m.points[m.count++] = all.points[i];
  }
  return m;
}

/// The vertex of c nearest to fraction f along edge i (i when f < 1/2, else the next one).
int clip_vertex_at(const Convex& c, int i, double f) {
  return f < 0.5 ? i : clip_next(c, i);
}

}  // namespace

/// The manifold of a and b, both given in one frame (the result in it too; anchors unset).
Manifold collide_placed(const Convex& a, const Convex& b, double speculative) {
  const double radius = a.radius + b.radius;
  const ClipAxis sa = clip_max_separation(a, b);
  const ClipAxis sb = clip_max_separation(b, a);
  if (sa.separation > speculative + radius || sb.separation > speculative + radius) return {};
  const bool no_faces = a.count < 2 && b.count < 2;
  const bool flip =
      a.count < 2 || (b.count >= 2 && sb.separation > sa.separation + clip_axis_tolerance);
  const int edge_a = flip ? clip_incident_edge(a, b.normals[sb.edge]) : sa.edge;
  const int edge_b = flip ? sb.edge : clip_incident_edge(b, a.normals[sa.edge]);
  if (a.count <= 2 && b.count <= 2) {
    // Circles and capsules: the exact closest points of the two cores decide.
    const Vec2 q1 = a.vertices[a.count - 1], q2 = b.vertices[b.count - 1];
    const ClipClosest c = clip_segment_closest(a.vertices[0], q1, b.vertices[0], q2);
    const int ia = c.f1 < 0.5 ? 0 : a.count - 1, ib = c.f2 < 0.5 ? 0 : b.count - 1;
    if (no_faces) return clip_single(c, ia, ib, a.radius, b.radius, Vec2{0.0, 1.0}, speculative);
    return clip_or_closest(a, b, edge_a, edge_b, flip, c, ia, ib, speculative);
  }
  const double best = flip ? sb.separation : sa.separation;
  if (best <= 0.0) {
    // The cores overlap: the reference face's clip (Box2D: "polygons overlap").
    return flip ? clip_reference(b, edge_b, a, true, speculative)
                : clip_reference(a, edge_a, b, false, speculative);
  }
  // Apart: the closest points of the reference and incident edges decide the vertex-vertex
  // case (Box2D b2CollidePolygons with b2SegmentDistance).
  const Vec2 a1 = a.vertices[edge_a], a2 = a.vertices[clip_next(a, edge_a)];
  const Vec2 b1 = b.vertices[edge_b], b2 = b.vertices[clip_next(b, edge_b)];
  const ClipClosest c = clip_segment_closest(a1, a2, b1, b2);
  return clip_or_closest(a, b, edge_a, edge_b, flip, c, clip_vertex_at(a, edge_a, c.f1),
                         clip_vertex_at(b, edge_b, c.f2), speculative);
}

}  // namespace fixstep::detail
