// fit_camera (session.hpp): the automatic view of a world definition.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "fixstep/app/session.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

namespace {
/// With planes, bodies bounce: a collider body under gravity g rises at most |v|²/(2|g|)
/// above its start along -g (its kinetic energy all turned into height; restitution <= 1 never
/// adds energy), so that point is included; then the point of each plane nearest the box's
/// centre, so the ground and walls the bodies bounce between are in view.
template <class Include>
void include_bounces(const WorldDef& def, Include&& include, double& x0, double& x1, double& y0,
                     double& y1) {
  for (const BodyDef& b : def.bodies) {
    if (!b.collider || !b.gravity) continue;
    const Vec2 g = b.gravity->acceleration;
    const double gn = std::hypot(g.x, g.y);
    if (!(gn > 0.0)) continue;
    const Vec2 v = b.body.velocity, p = b.body.position;
    const double rise = (v.x * v.x + v.y * v.y) / (2.0 * gn);
    include(p.x - g.x / gn * rise, p.y - g.y / gn * rise, b.collider->radius);
  }
  if (!(x0 <= x1)) return;  // no bodies
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  for (const PlaneDef& p : def.planes) {
    const double len = std::hypot(p.normal.x, p.normal.y);
    if (!(len > 0.0)) continue;
    const double nx = p.normal.x / len, ny = p.normal.y / len;
    const double gap = nx * cx + ny * cy - p.offset;
    include(cx - gap * nx, cy - gap * ny, 0.0);
  }
}
}  // namespace

Camera fit_camera(const WorldDef& def, int width, int height) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto include = [&](double x, double y, double r) {
    x0 = std::min(x0, x - r), x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r), y1 = std::max(y1, y + r);
  };
  for (const BodyDef& b : def.bodies) {
    include(b.body.position.x, b.body.position.y, b.appearance ? b.appearance->radius : 0.0);
    for (const ShapeDef& shape : b.shapes) {  // where the body starts, turned as it starts
      const Aabb box = shape_aabb(shape, b.body.position, b.body.angle);
      include(box.lower.x, box.lower.y, 0.0);
      include(box.upper.x, box.upper.y, 0.0);
    }
    if (b.spring) {
      const auto& s = *b.spring;
      const double dx = b.body.position.x - s.anchor.x, dy = b.body.position.y - s.anchor.y;
      const double omega = std::sqrt(s.stiffness / b.body.mass);
      const double speed = std::hypot(b.body.velocity.x, b.body.velocity.y);
      const double reach = std::hypot(dx, dy) + s.rest_length + (omega > 0 ? speed / omega : 0);
      include(s.anchor.x, s.anchor.y, reach);
    }
  }
  // Bodies held at one anchor through links (a rope pinned at one end) may swing all the way
  // round it: include the circle through the farthest body of each such group. Groups held at
  // two or more anchors (a cloth) keep to their bodies' box.
  if (!def.links.empty()) {
    const std::size_t n = def.bodies.size();
    std::vector<std::size_t> group(n);
    std::iota(group.begin(), group.end(), std::size_t{0});
    auto root = [&](std::size_t i) {
      while (group[i] != i) i = group[i] = group[group[i]];
      return i;
    };
    for (const fixstep::IndexLink& l : fixstep::index_links(def.links, n)) {
      group[root(l.body_a)] = root(l.body_b);
    }
    std::vector<std::size_t> anchors(n, 0), held_by(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (def.bodies[i].spring) ++anchors[root(i)], held_by[root(i)] = i;
    }
    std::vector<double> reach(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t g = root(i);
      if (anchors[g] != 1) continue;
      const Vec2 a = def.bodies[held_by[g]].spring->anchor, p = def.bodies[i].body.position;
      reach[g] = std::max(reach[g], std::hypot(p.x - a.x, p.y - a.y));
    }
    for (std::size_t g = 0; g < n; ++g) {
      if (anchors[g] == 1 && group[g] == g) {
        const Vec2 a = def.bodies[held_by[g]].spring->anchor;
        include(a.x, a.y, reach[g]);
      }
    }
  }
  if (!def.planes.empty()) include_bounces(def, include, x0, x1, y0, y1);
  const double aspect = double(width) / double(height);
  Camera c;
  c.center = {0.5 * (x0 + x1), 0.5 * (y0 + y1)};
  c.width = std::max({(x1 - x0), (y1 - y0) * aspect, 1.0}) * 1.15;
  return c;
}

}  // namespace fixstep
