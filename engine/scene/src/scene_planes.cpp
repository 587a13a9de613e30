// Scene files, part three: static half-planes ([[plane]]: ground and walls). See README
// "Scene format".
#include <cmath>

#include "fixstep/core/components.hpp"
#include "fixstep/core/det_math.hpp"
#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

/// One [[plane]] table: normal (required, non-zero), offset (m) or point ([x, y] m on the
/// plane; not both; default offset 0), restitution in [0, 1] and friction >= 0 (default 0).
PlaneDef parse_plane(Reader& r, const toml::table& t, const std::string& path) {
  r.check_keys(t, path, {"normal", "offset", "point", "restitution", "friction"});
  PlaneDef p;
  const auto normal = r.vec2(t, "normal", path + ".normal");
  if (!normal) r.fail_missing(t, path, {"normal"}, "missing (required): [x, y] into free space");
  const double len = det::hypot(normal->x, normal->y);
  if (!(len > 0.0) || !std::isfinite(len)) {
    r.fail(t.get("normal")->source(), path + ".normal",
           fmt::format("must be a non-zero vector (got [{}, {}])", normal->x, normal->y));
  }
  p.normal = Vec2{normal->x / len, normal->y / len};
  const auto offset = r.number(t, "offset", path + ".offset");
  const auto point = r.vec2(t, "point", path + ".point");
  if (offset && point) {
    r.fail(t.get("point")->source(), path + ".point",
           "`offset` and `point` both given: a plane takes one of them");
  }
  if (offset) {
    r.require_state(t, "offset", path + ".offset", *offset, "m");
    p.offset = *offset;
  }
  if (point) {
    r.require_state(t, "point", path + ".point", *point, "m");
    p.offset = p.normal.x * point->x + p.normal.y * point->y;
  }
  if (!std::isfinite(p.offset)) {
    r.fail(t.get("point")->source(), path + ".point",
           fmt::format("gives a non-finite offset ({})", p.offset));
  }
  if (auto e = r.number(t, "restitution", path + ".restitution")) {
    r.require(*e >= 0.0 && *e <= 1.0, t, "restitution", path + ".restitution", "in [0, 1]", *e);
    p.restitution = *e;
  }
  if (auto mu = r.number(t, "friction", path + ".friction")) {
    r.require(*mu >= 0.0, t, "friction", path + ".friction", ">= 0", *mu);
    p.friction = *mu;
  }
  return p;
}

}  // namespace

void parse_planes(Reader& r, const toml::table& doc, Scene& scene) {
  const toml::array* list = r.tables(doc, "plane");
  if (!list) return;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table& t = *list->get(i)->as_table();
    scene.def.planes.push_back(parse_plane(r, t, fmt::format("plane[{}]", i)));
    scene.source.plane_lines.push_back(t.source().begin.line);
  }
}

}  // namespace fixstep::scene_detail
