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
  RayEntry best{nan, {}};
  const double r = c.radius;
  if (!(dot(t, t) > 0.0) || convex_contains(c, o)) return best;
  // The pushed edges, each crossed from its outer side while heading in, within its length.
  for (int i = 0; c.count >= 2 && i < c.count; ++i) {
    const Vec2 n = c.normals[i];
    const Vec2 a = c.vertices[i] + r * n;
    const Vec2 e = c.vertices[i + 1 < c.count ? i + 1 : 0] - c.vertices[i];
    const double along = dot(n, t), start = dot(n, o - a);
    if (!(along < 0.0) || !(start >= 0.0)) continue;
    const double s = start / -along;
    if (!(s <= 1.0) || !(std::isnan(best.s) || s < best.s)) continue;
    const double u = dot(o + s * t - a, e);
    if (u < 0.0 || u > dot(e, e)) continue;
    best = {s, n};
  }
  // The vertex arcs (a circle's whole surface; none without a radius).
  for (int i = 0; r > 0.0 && i < c.count; ++i) {
    const double s = ray_disc(o, t, c.vertices[i], r);
    if (std::isnan(s) || !(std::isnan(best.s) || s < best.s)) continue;
    best = {s, (o + s * t - c.vertices[i]) / r};
  }
  return best;
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
