// The exact mass properties of shapes and of the bodies made of them. Every formula is a
// closed form of the area, the first moment and the polar moment ∫|x|² dA of the region; only
// + - * / and sqrt, and det::atan2 for a rounded polygon's corner angles.
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>

#include "fixstep/core/det_math.hpp"
#include "fixstep/core/shape.hpp"
#include "shape_geom.hpp"

namespace fixstep {

namespace {

constexpr double mass_pi = std::numbers::pi;

/// A region's area A (m²), centroid c (m) and polar moment J = ∫|x - c|² dA about c (m⁴), in
/// the shape's own frame: the mass properties of unit density.
struct Region {
  double area = 0.0;
  Vec2 centroid{};
  double polar = 0.0;
};

/// A circle of radius r about its centre: A = π r², J = π r⁴ / 2.
Region circle_region(double r) {
  return {mass_pi * r * r, {}, 0.5 * mass_pi * r * r * r * r};
}

/// The capsule a..b swept by r, L = |b - a|, about the segment's midpoint: the rectangle 2r × L
/// (J = 2rL (L² + 4r²) / 12) plus two half discs (area π r²/2 each, centroid 4r/(3π) beyond
/// its end of the segment, J about that centroid π r⁴/4 - (π r²/2)(4r/(3π))², moved to the
/// midpoint, at L/2 + 4r/(3π), by the parallel-axis theorem). As Box2D v3's
/// b2ComputeCapsuleMass (geometry.c); the sum is L³r/6 + 2Lr³ + π r⁴/2 + π r² L²/4.
Region capsule_region(Vec2 a, Vec2 b, double r) {
  const double len = length(b - a);
  const double rect_area = 2.0 * r * len;
  const double rect_polar = rect_area * (len * len + 4.0 * r * r) / 12.0;
  const double half_area = 0.5 * mass_pi * r * r;
  const double lever = 4.0 * r / (3.0 * mass_pi);  // a half disc's centroid from its flat side
  const double half_polar_own = 0.25 * mass_pi * r * r * r * r - half_area * lever * lever;
  const double arm = 0.5 * len + lever;
  const double halves_polar = 2.0 * (half_polar_own + half_area * arm * arm);
  return {rect_area + 2.0 * half_area, 0.5 * (a + b), rect_polar + halves_polar};
}

/// A polygon by its triangle fan (Eberly, "Polyhedral Mass Properties (Revisited)", 2002, the
/// 2D case; the same integrals as Box2D v3's b2ComputePolygonMass): the triangle o, o + e1,
/// o + e2 with D = e1 × e2 has area D/2, centroid o + (e1 + e2)/3 and
/// ∫|x - o|² dA = D (e1·e1 + e1·e2 + e2·e2) / 12. The area and centroid come from the fan
/// about vertex 0, the polar moment from the fan about the centroid (no large terms cancel).
Region polygon_region(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  double area = 0.0;
  Vec2 moment{};  // ∫(x - v0) dA
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec2 e1 = v[i] - v[0], e2 = v[i + 1] - v[0];
    const double a = 0.5 * cross(e1, e2);
    area += a;
    moment += (a / 3.0) * (e1 + e2);
  }
  const Vec2 c = v[0] + moment / area;
  double polar = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e1 = v[i] - c, e2 = v[(i + 1) % n] - c;
    polar += cross(e1, e2) * (dot(e1, e1) + dot(e1, e2) + dot(e2, e2)) / 12.0;
  }
  return {area, c, polar};
}

/// The outward unit normal of the edge a -> b of a counter-clockwise polygon.
Vec2 edge_normal(Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  return Vec2{e.y, -e.x} / length(e);
}

/// The polygon `v` rounded by r > 0: its Minkowski sum with a disc, exactly. The sum is the
/// polygon, a rectangle L × r outside each edge (centroid at the edge's midpoint + (r/2) n,
/// J about it L r (L² + r²) / 12) and a circular sector of radius r at each vertex between the
/// normals n₁, n₂ of its two edges (angle θ = atan2(n₁ × n₂, n₁·n₂), the exterior angle; the
/// sectors make one full disc since the exterior angles of a convex polygon sum to 2π). About
/// its apex w a sector has area θ r²/2, first moment ∫(x - w) dA = (r³/3)(n₂.y - n₁.y,
/// n₁.x - n₂.x) and J = θ r⁴/4 (integrate ρ dρ dφ over [0, r] × [φ₁, φ₂]). Everything is
/// summed about the polygon's centroid and moved to the sum's centroid by the parallel-axis
/// theorem. (Box2D v3's b2ComputePolygonMass approximates this by pushing the vertices out.)
Region rounded_region(std::span<const Vec2> v, double r) {
  const Region core = polygon_region(v);
  const std::size_t n = v.size();
  std::array<Vec2, max_polygon_vertices> w{}, normal{};
  for (std::size_t i = 0; i < n; ++i) w[i] = v[i] - core.centroid;
  for (std::size_t i = 0; i < n; ++i) normal[i] = edge_normal(w[i], w[(i + 1) % n]);

  double area = core.area, polar = core.polar;
  Vec2 moment{};  // ∫(x - core.centroid) dA of the rim
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = w[i], b = w[(i + 1) % n];
    const double len = length(b - a), rect = len * r;
    const Vec2 mid = 0.5 * (a + b) + (0.5 * r) * normal[i];
    area += rect;
    moment += rect * mid;
    polar += rect * (len * len + r * r) / 12.0 + rect * dot(mid, mid);
  }
  // The corners' angles, scaled to sum to exactly 2π (one full disc).
  std::array<double, max_polygon_vertices> theta{};
  double turn = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 n1 = normal[(i + n - 1) % n], n2 = normal[i];
    theta[i] = det::atan2(cross(n1, n2), dot(n1, n2));
    turn += theta[i];
  }
  const double disc_area = mass_pi * r * r;
  area += disc_area;
  polar += 0.5 * disc_area * r * r;  // Σ θ r⁴/4 about the apices
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 n1 = normal[(i + n - 1) % n], n2 = normal[i];
    const double sector = disc_area * (theta[i] / turn);
    const Vec2 own = (r * r * r / 3.0) * Vec2{n2.y - n1.y, n1.x - n2.x};
    moment += sector * w[i] + own;  // the `own` terms telescope to 0 over the polygon
    polar += sector * dot(w[i], w[i]) + 2.0 * dot(w[i], own);
  }
  const Vec2 shift = moment / area;
  return {area, core.centroid + shift, polar - area * dot(shift, shift)};
}

Region shape_region(const ShapeDef& s) {
  switch (s.kind) {
    case ShapeKind::circle:
      return circle_region(s.radius);
    case ShapeKind::capsule:
      return capsule_region(s.vertices[0], s.vertices[1], s.radius);
    case ShapeKind::box: {
      const double hx = s.half_extents.x, hy = s.half_extents.y;
      const std::array<Vec2, 4> corners{Vec2{-hx, -hy}, Vec2{hx, -hy}, Vec2{hx, hy}, Vec2{-hx, hy}};
      return s.radius > 0.0 ? rounded_region(corners, s.radius) : polygon_region(corners);
    }
    case ShapeKind::polygon: {
      const std::span<const Vec2> v(s.vertices.data(), static_cast<std::size_t>(s.count));
      return s.radius > 0.0 ? rounded_region(v, s.radius) : polygon_region(v);
    }
  }
  return {};
}

}  // namespace

MassProperties shape_mass(const ShapeDef& shape, double density) {
  const Region g = shape_region(shape);
  // The centroid into the body frame: offset + R(angle) c (a turn leaves J unchanged).
  const detail::Rot q{det::cos(shape.angle), det::sin(shape.angle)};
  return {density * g.area, shape.offset + detail::rotate(q, g.centroid), density * g.polar,
          g.area};
}

MassProperties body_mass(std::span<const ShapeDef> shapes, double mass) {
  bool densities = false;
  for (const ShapeDef& s : shapes) densities = densities || s.density.has_value();
  // Each shape's weight: its density, or 1 while the mass is spread evenly (scaled at the end).
  double total = 0.0, area = 0.0;
  Vec2 moment{};
  for (const ShapeDef& s : shapes) {
    const MassProperties m = shape_mass(s, densities ? s.density.value_or(0.0) : 1.0);
    total += m.mass;
    area += m.area;
    moment += m.mass * m.center;
  }
  if (!std::isfinite(area) || !(area > 0.0)) {
    throw std::invalid_argument("body_mass: the shapes have no area");
  }
  if (!std::isfinite(total) || !(total > 0.0)) {
    throw std::invalid_argument("body_mass: the shapes have no mass (every density is 0)");
  }
  const Vec2 center = moment / total;
  double inertia = 0.0;  // about `center`, by the parallel-axis theorem
  for (const ShapeDef& s : shapes) {
    const MassProperties m = shape_mass(s, densities ? s.density.value_or(0.0) : 1.0);
    const Vec2 d = m.center - center;
    inertia += m.inertia + m.mass * dot(d, d);
  }
  if (densities) return {total, center, inertia, area};
  if (!std::isfinite(mass) || !(mass > 0.0)) {
    throw std::invalid_argument("body_mass: mass must be finite and > 0 kg");
  }
  // Spread evenly: density mass / area; the mass itself is kept exactly.
  return {mass, center, inertia * (mass / total), area};
}

}  // namespace fixstep
