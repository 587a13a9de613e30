// The manifold between a shape and a static segment, or a chain segment whose ghost vertices
// (SegmentDef::prev, next) say where its neighbours go. A two-sided form of Box2D v3.2's
// b2CollideChainSegmentAndPolygon (src/manifold.c; Catto, "Ghost collisions", box2d.org
// 2020-06): the manifold's normal is classified against the Gauss map of the joint it points
// towards, as segment.hpp's disc rule does for a disc's centre:
//   * the segment's own face normal (either side) is always kept;
//   * a normal leaning towards end a with no prev, or towards b with no next, is kept (free end);
//   * towards a joint that is convex on the side B is on: kept when it lies in the joint's
//     wedge (between the two segments' normals, within `ghost_sin_tolerance`), dropped beyond
//     it (the neighbour's face covers B there); at b, a point at the joint vertex itself is
//     dropped, for the segment that starts at a joint owns its vertex (points along the
//     segment's interior stay: a box resting on the segment, a little turned, near a hilltop);
//   * towards a straight or concave joint: snapped to the segment's face normal, the manifold
//     then B's incident edge clipped to the segment (a shape sliding across a flat joint sees the
//     flat floor only).
#include <cmath>

#include "shape_geom.hpp"

namespace fixstep::detail {

// shape_clip.cpp
Manifold collide_placed(const Convex& a, const Convex& b, double speculative);
Manifold clip_reference(const Convex& ref, int edge, const Convex& inc, bool flip,
                        double speculative);

namespace {

/// How far (sine of the angle) a vertex normal may lie outside a convex joint's wedge and
/// still be kept; and how sharp a bend (sine) makes a joint convex rather than straight
/// (Box2D: sinTol and convexTol, 0.01 both).
constexpr double ghost_sin_tolerance = 0.01;
constexpr double ghost_convex_tolerance = 0.01;
/// A point closer than this (m) to the end b along the segment is at b.
constexpr double ghost_vertex_tolerance = 1e-9;

Vec2 ghost_unit(Vec2 v) {
  return v / std::sqrt(dot(v, v));
}

enum class GhostVerdict { keep, keep_but_b, drop, snap };

/// The verdict on normal n (from the segment towards B), on side s (+1: the left of a -> b).
GhostVerdict ghost_classify(const SegmentDef& seg, Vec2 u, double s, Vec2 n) {
  const double along = dot(n, u);
  if (along == 0.0) return GhostVerdict::keep;
  if (along < 0.0) {
    if (!seg.prev) return GhostVerdict::keep;
    const Vec2 d0 = ghost_unit(seg.a - *seg.prev);
    if (s * cross(d0, u) > -ghost_convex_tolerance) return GhostVerdict::snap;
    return dot(n, d0) >= -ghost_sin_tolerance ? GhostVerdict::keep : GhostVerdict::drop;
  }
  if (!seg.next) return GhostVerdict::keep;
  const Vec2 d2 = ghost_unit(*seg.next - seg.b);
  if (s * cross(u, d2) > -ghost_convex_tolerance) return GhostVerdict::snap;
  return dot(n, d2) <= ghost_sin_tolerance ? GhostVerdict::keep_but_b : GhostVerdict::drop;
}

/// m without its points at the segment's end b (the segment's own point of each lies at
/// separation/2 behind the point along the normal; 1 nm of rounding allowed).
Manifold ghost_without_b(Manifold m, const SegmentDef& seg, Vec2 u) {
  const double length = dot(seg.b - seg.a, u);
  int kept = 0;
  for (int i = 0; i < m.count; ++i) {
    const ManifoldPoint& p = m.points[i];
    const Vec2 on_segment = p.point - (0.5 * p.separation) * m.normal;
    if (dot(on_segment - seg.a, u) < length - ghost_vertex_tolerance) m.points[kept++] = p;
  }
  m.count = kept;
  return m;
}

}  // namespace

Manifold collide_segment(const SegmentDef& seg, const Convex& b, const Pose& tb,
                         double speculative) {
  const Convex a = segment_convex(seg.a, seg.b);
  const Convex bw = convex_placed(b, tb);
  Manifold m = collide_placed(a, bw, speculative);
  if (m.count > 0) {
    const Vec2 u = ghost_unit(seg.b - seg.a);
    // a.normals[0] is the right side of a -> b, a.normals[1] the left.
    const double s = dot(a.normals[1], m.normal) >= 0.0 ? 1.0 : -1.0;
    switch (ghost_classify(seg, u, s, m.normal)) {
      case GhostVerdict::keep:
        break;
      case GhostVerdict::keep_but_b:
        m = ghost_without_b(m, seg, u);
        break;
      case GhostVerdict::drop:
        return {};
      case GhostVerdict::snap:
        m = clip_reference(a, s > 0.0 ? 1 : 0, bw, false, speculative);
        break;
    }
  }
  for (int i = 0; i < m.count; ++i) {
    m.points[i].anchor_a = m.points[i].point;  // a segment has no centre: the world origin
    m.points[i].anchor_b = m.points[i].point - tb.p;
  }
  return m;
}

}  // namespace fixstep::detail
