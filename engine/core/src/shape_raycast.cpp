// Exact ray casts against convex shapes with radius, and the point and overlap tests of World's
// queries (shape_query.hpp). Only + - * / and sqrt.
#include <cmath>
#include <limits>

#include "shape_query.hpp"

namespace fixstep::detail {

namespace {

/// The squared distance from p to the segment a..b, m².
double segment_gap2(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 e = b - a, w = p - a;
  const double ee = dot(e, e), we = dot(w, e);
  if (!(we > 0.0) || !(ee > 0.0)) return dot(w, w);
  if (we >= ee) {
    const Vec2 d = p - b;
    return dot(d, d);
  }
  const Vec2 d = w - (we / ee) * e;
  return dot(d, d);
}

}  // namespace

double ray_disc(Vec2 p, Vec2 t, Vec2 c, double r) {
  const double mx = p.x - c.x, my = p.y - c.y;
  const double cc = mx * mx + my * my - r * r;
  const double a = t.x * t.x + t.y * t.y;
  const double b = mx * t.x + my * t.y;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(cc > 0.0) || !(b < 0.0) || !(a > 0.0)) return nan;  // inside, or heading away
  const double disc = b * b - a * cc;
  if (disc < 0.0) return nan;
  const double s = cc / (-b + std::sqrt(disc));  // = (-b - √disc)/a, without cancellation
  return s <= 1.0 ? s : nan;
}

RayEntry ray_convex(const Convex& c, Vec2 o, Vec2 t) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const RayEntry miss{nan, {}};
  const double r = c.radius;
  if (!(dot(t, t) > 0.0) || convex_contains(c, o)) return miss;
  auto arc = [&](int v) {  // the ray against vertex v's circle
    const double s = ray_disc(o, t, c.vertices[v], r);
    return std::isnan(s) ? miss : RayEntry{s, (o + s * t - c.vertices[v]) / r};
  };
  if (c.count == 1) return arc(0);
  // Clipped by the pushed edges' half-planes (Cyrus-Beck, as Box2D's b2RayCastPolygon): the
  // ray enters the mitered polygon at `lower` through edge `entry`. Exact at a vertex of an
  // unrounded polygon, where two edges meet.
  double lower = 0.0, upper = 1.0;
  int entry = -1;
  for (int i = 0; i < c.count; ++i) {
    const Vec2 n = c.normals[i];
    const double num = dot(n, c.vertices[i] + r * n - o), den = dot(n, t);
    if (den == 0.0) {
      if (num < 0.0) return miss;
    } else if (den < 0.0 && num < lower * den) {
      lower = num / den, entry = i;
    } else if (den > 0.0 && num < upper * den) {
      upper = num / den;
    }
    if (upper < lower) return miss;
  }
  if (r == 0.0) return entry < 0 ? miss : RayEntry{lower, c.normals[entry]};
  if (entry < 0) {
    // It starts in the miter of a corner, outside the shape: there the vertex is the core's
    // nearest point, and the shape's surface ahead that vertex's circle.
    int v = 0;
    for (int i = 1; i < c.count; ++i) {
      const Vec2 di = o - c.vertices[i], dv = o - c.vertices[v];
      if (dot(di, di) < dot(dv, dv)) v = i;
    }
    return arc(v);
  }
  // Within the pushed edge's length: on its flat part. Beyond an end: in that corner's miter,
  // outside the shape, which the ray then enters on the corner's circle or not at all (the
  // miter's border with a neighbouring edge's strip lies within the circle).
  const Vec2 a = c.vertices[entry] + r * c.normals[entry];
  const int next = entry + 1 < c.count ? entry + 1 : 0;
  const Vec2 e = c.vertices[next] - c.vertices[entry];
  const double u = dot(o + lower * t - a, e);
  if (u < 0.0) return arc(entry);
  if (u > dot(e, e)) return arc(next);
  return {lower, c.normals[entry]};
}

double core_gap2(const Convex& c, Vec2 p) {
  if (c.count == 1) {
    const Vec2 d = p - c.vertices[0];
    return dot(d, d);
  }
  if (c.count == 2) return segment_gap2(p, c.vertices[0], c.vertices[1]);
  bool inside = true;
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < c.count; ++i) {
    const Vec2 a = c.vertices[i], b = c.vertices[i + 1 < c.count ? i + 1 : 0];
    if (dot(c.normals[i], p - a) > 0.0) inside = false;
    const double g = segment_gap2(p, a, b);
    if (g < least) least = g;
  }
  return inside ? 0.0 : least;
}

bool convex_contains(const Convex& c, Vec2 p) {
  return core_gap2(c, p) <= c.radius * c.radius;
}

bool convex_overlap(const Convex& a, const Convex& b) {
  const Distance d = distance(a, Pose{}, b, Pose{});
  return d.overlap || d.distance <= 0.0;
}

}  // namespace fixstep::detail
