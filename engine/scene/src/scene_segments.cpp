// Scene files: segments and polylines ([[segment]], [[polyline]]: level geometry), static or
// carried by a kinematic body (`body`). See docs/SCENES.md.
#include <cmath>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_def.hpp"
#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

/// A point within max_state_magnitude of the origin (the world refuses others).
Vec2 point_node(Reader& r, const toml::node& n, const std::string& path) {
  const Vec2 p = r.vec2_node(n, path);
  if (!(std::abs(p.x) <= max_state_magnitude && std::abs(p.y) <= max_state_magnitude)) {
    r.fail(n.source(), path,
           fmt::format("must lie within {:g} m of the origin (got [{}, {}])", max_state_magnitude,
                       p.x, p.y));
  }
  return p;
}

/// restitution in [0, 1] and friction >= 0 (default 0) of a [[segment]] or [[polyline]].
void parse_surface(Reader& r, const toml::table& t, const std::string& path, double& e,
                   double& mu) {
  if (auto v = r.number(t, "restitution", path + ".restitution")) {
    r.require(*v >= 0.0 && *v <= 1.0, t, "restitution", path + ".restitution", "in [0, 1]", *v);
    e = *v;
  }
  if (auto v = r.number(t, "friction", path + ".friction")) {
    r.require(*v >= 0.0, t, "friction", path + ".friction", ">= 0", *v);
    mu = *v;
  }
}

/// The carrier of a [[segment]] or [[polyline]] table (`what`, for the message): the WorldDef
/// handle of the body its `body` key names, or null (a static segment) without the key. Errors
/// at the key: not a string, no body of that name (find_body), a body that is not kinematic.
Entity parse_carrier(const Reader& r, const toml::table& t, const std::string& path,
                     const Scene& scene, const BodyNames& names, std::string_view what) {
  const toml::node* n = t.get("body");
  if (!n) return Entity{};
  const std::string key = path + ".body";
  const std::size_t i = find_body(r, *n, key, names);
  const BodyDef& b = scene.def.bodies[i];
  if (b.type != BodyType::kinematic) {
    r.fail(n->source(), key,
           fmt::format("\"{}\" (line {}) is a {} body: only a kinematic body can carry segments; "
                       "give it type = \"kinematic\", or leave `body` out for a static {}",
                       b.name, scene.source.body_lines[i], body_type_name(b.type), what));
  }
  return fixstep::defined_entity(i);
}

/// One [[segment]] table: a and b ([x, y] m, required, distinct), restitution, friction, the
/// ghost vertices prev and next ([x, y] m, optional; SegmentDef) and the carrying body.
SegmentDef parse_segment(Reader& r, const toml::table& t, const std::string& path,
                         const Scene& scene, const BodyNames& names) {
  r.check_keys(
      t, path,
      {"a", "b", "restitution", "friction", "prev", "next", "body", "color", "width", "one_way"});
  SegmentDef s;
  for (const char* key : {"a", "b"}) {
    const toml::node* n = t.get(key);
    if (!n) r.fail_missing(t, path, {key}, "missing (required): an end point [x, y] in m");
    (std::string_view(key) == "a" ? s.a : s.b) = point_node(r, *n, path + "." + key);
  }
  if (s.a == s.b) {
    r.fail(t.get("b")->source(), path + ".b",
           fmt::format("equals a ([{}, {}]): a segment needs two distinct ends", s.a.x, s.a.y));
  }
  if (const toml::node* n = t.get("prev")) s.prev = point_node(r, *n, path + ".prev");
  if (const toml::node* n = t.get("next")) s.next = point_node(r, *n, path + ".next");
  parse_surface(r, t, path, s.restitution, s.friction);
  s.body = parse_carrier(r, t, path, scene, names, "segment");
  parse_segment_looks(r, t, path, std::span(&s, 1));
  s.one_way = r.boolean(t, "one_way", path + ".one_way").value_or(false);
  return s;
}

/// One [[polyline]] table: points (an array of at least 2 [x, y], 3 when closed, consecutive
/// ones distinct), restitution, friction, closed (default false) and the body carrying every
/// segment. Appends its segments to the scene.
void parse_polyline(Reader& r, const toml::table& t, const std::string& path, Scene& scene,
                    const BodyNames& names) {
  r.check_keys(
      t, path,
      {"points", "restitution", "friction", "closed", "body", "color", "width", "one_way"});
  const toml::node* n = t.get("points");
  if (!n) r.fail_missing(t, path, {"points"}, "missing (required): [[x, y], [x, y], ...] in m");
  const toml::array* a = n->as_array();
  if (!a) r.fail(n->source(), path + ".points", "expected an array of [x, y] points");
  const bool closed = r.boolean(t, "closed", path + ".closed").value_or(false);
  if (a->size() < (closed ? 3u : 2u)) {
    r.fail(n->source(), path + ".points",
           fmt::format("needs at least {} points{} (got {})", closed ? 3 : 2,
                       closed ? " when closed" : "", a->size()));
  }
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const std::string at = fmt::format("{}.points[{}]", path, i);
    points.push_back(point_node(r, *a->get(i), at));
    if (i > 0 && points[i] == points[i - 1]) {
      r.fail(a->get(i)->source(), at,
             fmt::format("repeats point {} ([{}, {}]): a segment needs two distinct ends", i - 1,
                         points[i].x, points[i].y));
    }
  }
  if (closed && points.back() == points.front()) {
    r.fail(a->get(a->size() - 1)->source(), fmt::format("{}.points[{}]", path, a->size() - 1),
           "repeats point 0: a closed polyline joins its last point to its first itself");
  }
  double e = 0.0, mu = 0.0;
  parse_surface(r, t, path, e, mu);
  const Entity body = parse_carrier(r, t, path, scene, names, "polyline");
  const bool one_way = r.boolean(t, "one_way", path + ".one_way").value_or(false);
  const std::size_t first = scene.def.segments.size();
  scene.def.add_polyline(points, e, mu, closed, body, one_way);
  parse_segment_looks(r, t, path, std::span(scene.def.segments).subspan(first));
}

}  // namespace

void parse_segments(Reader& r, const toml::table& doc, Scene& scene, const BodyNames& names) {
  if (const toml::array* list = r.tables(doc, "segment")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table& t = *list->get(i)->as_table();
      scene.def.segments.push_back(
          parse_segment(r, t, fmt::format("segment[{}]", i), scene, names));
      scene.source.segment_lines.push_back(t.source().begin.line);
    }
  }
  if (const toml::array* list = r.tables(doc, "polyline")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table& t = *list->get(i)->as_table();
      parse_polyline(r, t, fmt::format("polyline[{}]", i), scene, names);
      scene.source.segment_lines.resize(scene.def.segments.size(), t.source().begin.line);
    }
  }
}

}  // namespace fixstep::scene_detail
