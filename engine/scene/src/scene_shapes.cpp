// Shapes in scene files: a body's `shape = { box = [hx, hy] }` (or circle, capsule, polygon)
// and `[[body.shape]]` tables for a compound body, with their pose and material keys; and
// their text for write_scene, every number the shortest that reads back as the same double.
// See docs/SCENES.md, "Shapes".
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/shape.hpp"
#include "scene_reader.hpp"
#include "scene_values.hpp"

namespace fixstep::scene_detail {

namespace {

constexpr std::array<std::string_view, 4> shape_kinds{"circle", "capsule", "box", "polygon"};

/// The one kind key of shape table t (circle, capsule, box or polygon): an error at the second
/// one when there are two, at the table when there is none.
std::string_view shape_kind_key(const Reader& r, const toml::table& t, const std::string& path) {
  std::optional<std::string_view> kind;
  for (auto&& [key, node] : t) {
    const std::string_view k = key.str();
    if (std::find(shape_kinds.begin(), shape_kinds.end(), k) == shape_kinds.end()) continue;
    if (kind) {
      r.fail(key.source(), path + "." + std::string(k),
             fmt::format("a shape is one circle, capsule, box or polygon; this one gives both {} "
                         "and {}: write each as a shape of its own ([[body.shape]] tables)",
                         *kind, k));
    }
    kind = k;
  }
  if (!kind) {
    r.fail_missing(t, path, {"circle", "capsule", "box", "polygon"}, "missing (required)",
                   "a shape needs one of circle = r, box = [hx, hy], capsule = [[x1, y1], [x2, "
                   "y2]] with radius = r, or polygon = [[x, y], ...] (m)");
  }
  return *kind;
}

/// The [x, y] points of the array at t[key]: `lo` .. `hi` of them.
std::vector<Vec2> points(const Reader& r, const toml::table& t, std::string_view key,
                         const std::string& path, std::size_t lo, std::size_t hi) {
  const toml::node& n = *t.get(key);
  const toml::array* a = n.as_array();
  if (!a)
    r.fail(n.source(), path, fmt::format("expected an array of points [x, y], found {}", found(n)));
  if (a->size() < lo || a->size() > hi) {
    r.fail(n.source(), path,
           lo == hi ? fmt::format("expected {} points [x, y], found {}", lo, elements(a->size()))
                    : fmt::format("{} count must be {} to {} (got {})", key, lo, hi, a->size()));
  }
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    out.push_back(r.vec2_node(*a->get(i), fmt::format("{}[{}]", path, i)));
  }
  return out;
}

/// sensor, category, mask and group of shape table t into s (as a disc's, scene_contacts.cpp).
void read_shape_filter(const Reader& r, const toml::table& t, const std::string& path,
                       ShapeDef& s) {
  if (auto v = r.boolean(t, "sensor", path + ".sensor")) s.sensor = *v;
  if (auto bits = filter_bits(r, t, "category", path + ".category")) s.filter.category = *bits;
  if (auto bits = filter_bits(r, t, "mask", path + ".mask")) s.filter.mask = *bits;
  if (const toml::node* n = t.get("group")) {
    s.filter.group = static_cast<std::int32_t>(
        r.integer_node(*n, path + ".group", std::numeric_limits<std::int32_t>::min(),
                       std::numeric_limits<std::int32_t>::max(),
                       " (positive: the group always collides, negative: never)"));
  }
}

/// The geometry of shape table t: its kind key and radius.
ShapeDef read_geometry(const Reader& r, const toml::table& t, const std::string& path) {
  const std::string_view kind = shape_kind_key(r, t, path);
  const std::string kpath = path + "." + std::string(kind);
  const std::optional<double> radius = r.number(t, "radius", path + ".radius");
  ShapeDef s;
  if (kind == "circle") {
    if (radius) {
      r.fail(t.get("radius")->source(), path + ".radius",
             "a circle's radius is its `circle` key (circle = r); remove radius");
    }
    s = make_circle(*r.number(t, "circle", kpath));
  } else if (kind == "box") {
    const Vec2 h = r.vec2_node(*t.get("box"), kpath);
    s = make_box(h.x, h.y, {}, 0.0, radius.value_or(0.0));
  } else if (kind == "capsule") {
    const std::vector<Vec2> p = points(r, t, "capsule", kpath, 2, 2);
    if (!radius) {
      r.fail_missing(t, path, {"radius"}, "missing (required)",
                     "a capsule's radius in m, e.g. radius = 0.25");
    }
    s = make_capsule(p[0], p[1], *radius);
  } else {
    const std::vector<Vec2> p =
        points(r, t, "polygon", kpath, 3, static_cast<std::size_t>(max_polygon_vertices));
    s = make_polygon(p, radius.value_or(0.0));
  }
  return s;
}

/// Where shape_problem's `message` points in shape table t: the key it starts with when the
/// table has it (radius, offset, angle, density, friction, restitution, rolling_resistance), else
/// the kind key; a density from the body (`body_density`) at the body's key.
std::pair<const toml::node*, std::string> problem_key(const toml::table& t, const std::string& path,
                                                      const ShapeDef& s, std::string_view message,
                                                      const toml::node* body_density,
                                                      const std::string& body_path) {
  const std::string_view word = message.substr(0, message.find(' '));
  if (word == "density" && !t.get("density") && body_density) {
    return {body_density, body_path + ".density"};
  }
  for (const std::string_view k :
       {"radius", "offset", "angle", "density", "friction", "restitution", "rolling_resistance"}) {
    if (word == k && t.get(k)) return {t.get(k), path + "." + std::string(k)};
  }
  const std::string_view kind = shape_kind_name(s.kind);
  return {t.get(kind), path + "." + std::string(kind)};
}

ShapeDef read_shape(Reader& r, const toml::table& t, const std::string& path,
                    std::optional<double> body_density, const toml::node* body_density_node,
                    const std::string& body_path) {
  r.check_keys(t, path,
               {"circle", "capsule", "box", "polygon", "radius", "offset", "angle", "density",
                "friction", "restitution", "rolling_resistance", "sensor", "one_way", "category",
                "mask", "group", "color"});
  ShapeDef s = read_geometry(r, t, path);
  if (auto v = r.vec2(t, "offset", path + ".offset")) s.offset = *v;
  if (auto v = r.number(t, "angle", path + ".angle")) s.angle = *v;
  s.density = r.number(t, "density", path + ".density");
  if (!s.density) s.density = body_density;
  s.friction = r.number(t, "friction", path + ".friction");
  s.restitution = r.number(t, "restitution", path + ".restitution");
  if (auto v = r.number(t, "rolling_resistance", path + ".rolling_resistance")) {
    s.rolling_resistance = *v;
  }
  read_shape_filter(r, t, path, s);
  if (t.get("color")) s.color = parse_color(r, t, "color", path + ".color");  // drawing only
  if (auto v = r.boolean(t, "one_way", path + ".one_way")) s.one_way = *v;
  if (const std::optional<std::string> problem = shape_problem(s)) {
    const auto [node, key] = problem_key(t, path, s, *problem, body_density_node, body_path);
    r.fail(node->source(), key, *problem);
  }
  return s;
}

}  // namespace

void parse_body_shapes(Reader& r, const toml::table& t, const std::string& path, BodyDef& def) {
  const toml::node* n = t.get("shape");
  const toml::node* density_node = t.get("density");
  if (!n) {
    if (density_node) {
      r.fail(density_node->source(), path + ".density",
             "needs a shape: a body's density (kg/m^2) is that of its shapes without their own; "
             "add shape = { ... }, or give the mass alone");
    }
    return;
  }
  if (def.collider) {
    r.fail(n->source(), path + ".shape",
           "a body has a radius (a disc) or shapes, not both; remove radius, or make the disc a "
           "shape: { circle = r }");
  }
  const std::optional<double> density = r.number(t, "density", path + ".density");
  const std::string sp = path + ".shape";
  if (const toml::table* one = n->as_table()) {
    def.shapes.push_back(read_shape(r, *one, sp, density, density_node, path));
    return;
  }
  const toml::array* list = n->as_array();
  if (!list || list->empty()) {
    r.fail(n->source(), sp,
           fmt::format("expected a shape table (shape = {{ box = [hx, hy] }}) or an array of them "
                       "([[body.shape]] tables), found {}",
                       found(*n)));
  }
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::node& e = *list->get(i);
    const std::string ep = fmt::format("{}[{}]", sp, i);
    if (!e.is_table()) r.fail(e.source(), ep, fmt::format("expected a table, found {}", found(e)));
    def.shapes.push_back(read_shape(r, *e.as_table(), ep, density, density_node, path));
  }
}

bool shapes_give_density(const toml::table& t) {
  if (t.get("density")) return true;
  const toml::node* n = t.get("shape");
  if (!n) return false;
  if (const toml::table* one = n->as_table()) return one->get("density") != nullptr;
  const toml::array* list = n->as_array();
  return list && std::any_of(list->begin(), list->end(), [](const toml::node& e) {
           return e.is_table() && e.as_table()->get("density") != nullptr;
         });
}

std::string shapes_text(const BodyDef& b) {
  std::string out;
  auto it = std::back_inserter(out);
  if (b.inertia) fmt::format_to(it, "inertia = {}\n", toml_number(*b.inertia));
  for (const ShapeDef& s : b.shapes) {
    out += "\n[[body.shape]]\n";
    switch (s.kind) {
      case ShapeKind::circle:
        fmt::format_to(it, "circle = {}\n", toml_number(s.radius));
        break;
      case ShapeKind::box:
        fmt::format_to(it, "box = {}\n", toml_point(s.half_extents));
        break;
      case ShapeKind::capsule:
      case ShapeKind::polygon: {
        fmt::format_to(it, "{} = [", shape_kind_name(s.kind));
        for (int i = 0; i < s.count; ++i) {
          fmt::format_to(it, "{}{}", i ? ", " : "",
                         toml_point(s.vertices[static_cast<std::size_t>(i)]));
        }
        out += "]\n";
        break;
      }
    }
    const bool rounded = s.kind == ShapeKind::box || s.kind == ShapeKind::polygon;
    if (s.kind == ShapeKind::capsule || (rounded && !same_bits(s.radius, 0.0))) {
      fmt::format_to(it, "radius = {}\n", toml_number(s.radius));
    }
    if (!same_bits(s.offset.x, 0.0) || !same_bits(s.offset.y, 0.0)) {
      fmt::format_to(it, "offset = {}\n", toml_point(s.offset));
    }
    if (!same_bits(s.angle, 0.0)) fmt::format_to(it, "angle = {}\n", toml_number(s.angle));
    if (s.density) fmt::format_to(it, "density = {}\n", toml_number(*s.density));
    if (s.friction) fmt::format_to(it, "friction = {}\n", toml_number(*s.friction));
    if (s.restitution) fmt::format_to(it, "restitution = {}\n", toml_number(*s.restitution));
    if (!same_bits(s.rolling_resistance, 0.0)) {
      fmt::format_to(it, "rolling_resistance = {}\n", toml_number(s.rolling_resistance));
    }
    if (s.sensor) out += "sensor = true\n";
    if (s.one_way) out += "one_way = true\n";
    const CollisionFilter f = s.filter, none{};
    if (f.category != none.category) {
      fmt::format_to(it, "category = {}\n", toml_filter_bits(f.category));
    }
    if (f.mask != none.mask) fmt::format_to(it, "mask = {}\n", toml_filter_bits(f.mask));
    if (f.group != none.group) fmt::format_to(it, "group = {}\n", f.group);
    if (s.color != Rgba8{0, 0, 0, 0}) fmt::format_to(it, "color = {}\n", toml_color(s.color));
  }
  return out;
}

}  // namespace fixstep::scene_detail
