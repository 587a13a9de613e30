// Renderer::rounded_polygon: a convex polygon rounded by a radius (a disc, a capsule, a rounded
// box), anti-aliased by the shapes program as discs are, drawn as one mesh that covers each
// pixel once.
//
// The mesh partitions the rounded polygon, plus the anti-aliasing margin, into pieces on which
// the distance to the polygon is simple: 0 inside the polygon, the distance to the edge's line
// in the band outside each edge, the distance to the vertex in the wedge between the normals of
// the two edges that meet there (Box2D's b2MakeRoundedPolygon describes the same shape). Each
// is an affine function of the position on its piece, written as shape coordinates
// uv = (p - nearest point of the polygon) / radius, which the GL interpolates exactly; the
// pieces share their vertices (the same numbers) along their common edges, so neighbouring
// pieces agree there and GL's tie rule gives each pixel to one triangle. The shapes program's
// coverage clamp((1 - |uv|) / fwidth + 0.5, 0, 1) is then the rounded polygon's, smoothed over
// one pixel at distance `radius`, on OSMesa and on WebGL2 alike.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "aa_pad.hpp"
#include "fixstep/render/render.hpp"

namespace fixstep {

namespace {

using Point = Renderer::Point;

Point vadd(Point a, Point b) {
  return {a.x + b.x, a.y + b.y};
}
Point vsub(Point a, Point b) {
  return {a.x - b.x, a.y - b.y};
}
Point vscale(Point a, float s) {
  return {a.x * s, a.y * s};
}
float vdot(Point a, Point b) {
  return a.x * b.x + a.y * b.y;
}
Point vunit(Point a) {
  const float len = std::sqrt(vdot(a, a));
  return {a.x / len, a.y / len};
}
/// The point at distance 1 along both unit normals a and b (at most 90° apart): a mitre.
Point mitre(Point a, Point b) {
  return vscale(vadd(a, b), 1.0f / (1.0f + vdot(a, b)));
}

}  // namespace

void Renderer::rounded_polygon(std::span<const Point> points, float radius, Rgba8 c) {
  if (!(radius >= 0.0f) || !std::isfinite(radius)) return;
  constexpr float min_step = 1e-3f;  // px, as line()
  std::vector<Point>& pts = rounded_points_;
  pts.clear();
  for (const Point& p : points) {
    if (pts.empty() || std::hypot(p.x - pts.back().x, p.y - pts.back().y) >= min_step) {
      pts.push_back(p);
    }
  }
  while (pts.size() > 1 &&
         std::hypot(pts.back().x - pts[0].x, pts.back().y - pts[0].y) < min_step) {
    pts.pop_back();
  }
  const std::size_t n = pts.size();
  if (n == 0 || (n < 3 && radius == 0.0f)) return;
  if (n == 1) {
    disc(pts[0].x, pts[0].y, radius, c);
    return;
  }
  // Outward unit normals of the edges pts[i] -> pts[i + 1]: (d.y, -d.x) turned by the winding
  // (twice the signed area; 0 for a capsule's two edges, which face apart either way).
  float area2 = 0.0f;
  for (std::size_t i = 0; i < n; ++i) {
    const Point a = pts[i], b = pts[(i + 1) % n];
    area2 += a.x * b.y - b.x * a.y;
  }
  const float side = area2 < 0.0f ? -1.0f : 1.0f;
  rounded_normals_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point d = vunit(vsub(pts[(i + 1) % n], pts[i]));
    rounded_normals_[i] = {side * d.y, -side * d.x};
  }
  if (radius == 0.0f) {
    // Sharp: shrink by 1 px (each vertex along its mitre) and round by 1 px, which smooths
    // the edges where they were; unless the polygon is too small to shrink (an edge would turn
    // round), which is drawn unsmoothed. The edges keep their directions, hence their normals.
    constexpr float shrink = 1.0f;
    bool kept = true;
    point_scratch_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Point m = mitre(rounded_normals_[(i + n - 1) % n], rounded_normals_[i]);
      point_scratch_[i] = vsub(pts[i], vscale(m, shrink));
    }
    for (std::size_t i = 0; i < n && kept; ++i) {
      const std::size_t j = (i + 1) % n;
      kept = vdot(vsub(point_scratch_[j], point_scratch_[i]), vsub(pts[j], pts[i])) > 0.0f;
    }
    if (kept) {
      pts.swap(point_scratch_);
      radius = shrink;
    }
  }
  use(shapes, {});
  rounded_mesh(radius, c);
}

void Renderer::rounded_mesh(float radius, Rgba8 c) {
  const std::vector<Point>& pts = rounded_points_;
  const std::vector<Point>& normal = rounded_normals_;
  const std::size_t n = pts.size();
  const auto base = static_cast<std::uint32_t>(vertices_.size());
  // The polygon: vertices base + i, shape coordinates 0 (full coverage).
  for (const Point& p : pts) vertex(p.x, p.y, 0.0f, 0.0f, c);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    for (const std::size_t k : {std::size_t{0}, i, i + 1}) {
      indices_.push_back(base + static_cast<std::uint32_t>(k));
    }
  }
  if (radius == 0.0f) return;
  const float reach = radius + detail::aa_pad_px, to_uv = 1.0f / radius;
  // The band outside edge i: vertices base + n + 2i (beyond pts[i]) and base + n + 2i + 1
  // (beyond pts[i + 1]), both at shape coordinates normal * reach / radius.
  auto index = [&](std::size_t k) { return base + static_cast<std::uint32_t>(k); };
  for (std::size_t i = 0; i < n; ++i) {
    const Point off = vscale(normal[i], reach), uv = vscale(normal[i], reach * to_uv);
    const Point a = vadd(pts[i], off), b = vadd(pts[(i + 1) % n], off);
    vertex(a.x, a.y, uv.x, uv.y, c);
    vertex(b.x, b.y, uv.x, uv.y, c);
    const std::uint32_t p = index(i), q = index((i + 1) % n);
    const std::uint32_t qb = index(n + 2 * i + 1), pa = index(n + 2 * i);
    for (const std::uint32_t k : {p, q, qb, p, qb, pa}) indices_.push_back(k);
  }
  // The wedge at vertex j, from the band of the edge before it to the band of the edge after
  // it: a fan from pts[j] through corners on the tangents of the circle of radius `reach`, one
  // corner for a turn of up to 90°, two beyond (a capsule's end turns 180°).
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = (j + n - 1) % n;
    const Point ni = normal[i], nj = normal[j], p = pts[j];
    std::uint32_t fan[4] = {index(n + 2 * i + 1), 0, 0, 0};
    std::size_t count = 1;
    auto corner = [&](Point dir) {
      const Point q = vadd(p, vscale(dir, reach)), uv = vscale(dir, reach * to_uv);
      fan[count++] = static_cast<std::uint32_t>(vertices_.size());
      vertex(q.x, q.y, uv.x, uv.y, c);
    };
    if (vdot(ni, nj) >= 0.0f) {
      corner(mitre(ni, nj));
    } else {
      // The outward bisector: the incoming edge's direction less the outgoing one's.
      const Point m = vunit(vsub(vunit(vsub(p, pts[i])), vunit(vsub(pts[(j + 1) % n], p))));
      corner(mitre(ni, m));
      corner(mitre(m, nj));
    }
    fan[count++] = index(n + 2 * j);
    for (std::size_t k = 0; k + 1 < count; ++k) {
      for (const std::uint32_t v : {index(j), fan[k], fan[k + 1]}) indices_.push_back(v);
    }
  }
}

}  // namespace fixstep
