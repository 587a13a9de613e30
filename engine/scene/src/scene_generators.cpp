// Scene files, part three: the generators of ropes and cloth ([[chain]], [[grid]]). See README
// "Scene format".
#include <cmath>
#include <cstdint>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/work_progress.hpp"
#include "fixstep/core/world_def.hpp"
#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

/// The bodies and links one generator table adds to the scene.
class Generator {
 public:
  Generator(Reader& r, Scene& scene, BodyNames& names, const toml::table& t, std::string path)
      : r_(r), scene_(scene), names_(names), t_(t), path_(std::move(path)) {}

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] std::string key(std::string_view k) const { return path_ + "." + std::string(k); }

  /// A required key's node, else "missing (required): `what`" at the table.
  const toml::node& required(std::string_view k, std::string_view what = {}) const {
    const toml::node* n = t_.get(k);
    if (!n) r_.fail_missing(t_, path_, {k}, "missing (required)", what);
    return *n;
  }

  /// The generator's name prefix (default `fallback`): bodies are named prefix[...].
  std::string name(const std::string& fallback) {
    std::string name = r_.string(t_, "name", key("name")).value_or(fallback);
    if (name.empty()) {
      r_.fail(t_.get("name")->source(), key("name"),
              fmt::format("must not be empty: it begins the bodies' names; leave it out for the "
                          "default \"{}\"",
                          fallback));
    }
    name_node_ = t_.get("name");
    return name;
  }

  /// Refuses a generator that would take the scene beyond max_scene_bodies.
  void reserve_bodies(std::uint64_t count, const toml::node& at, const std::string& at_key) {
    if (scene_.def.bodies.size() + count > max_scene_bodies) {
      r_.fail(at.source(), at_key,
              fmt::format("the scene would have {} bodies; at most {} are allowed",
                          scene_.def.bodies.size() + count, max_scene_bodies));
    }
    bodies_target_ = scene_.def.bodies.size() + count;
    scene_.def.bodies.reserve(scene_.def.bodies.size() + count);
    scene_.source.body_lines.reserve(scene_.def.bodies.size() + count);
    names_.index.reserve(names_.index.size() + count);
  }

  /// Refuses links that would take the scene beyond max_scene_links.
  void reserve_links(std::uint64_t count, const toml::node& at, const std::string& at_key) {
    if (scene_.def.links.size() + count > max_scene_links) {
      r_.fail(at.source(), at_key,
              fmt::format("the scene would have {} links; at most {} are allowed",
                          scene_.def.links.size() + count, max_scene_links));
    }
    links_target_ = scene_.def.links.size() + count;
    scene_.def.links.reserve(scene_.def.links.size() + count);
    scene_.source.link_lines.reserve(scene_.def.links.size() + count);
  }

  /// The body template `body = { mass = ..., ... }`.
  BodyDef body_template() {
    const toml::table* b = r_.table(t_, "body", key("body"));
    if (!b) {
      r_.fail_missing(t_, path_, {"body"}, "missing (required)",
                      "the bodies' template, e.g. body = { mass = 0.1 }");
    }
    r_.check_keys(
        *b, key("body"),
        {"type",        "mass",   "velocity", "force",  "gravity",    "drag",    "radius",
         "draw_radius", "color",  "visible",  "trail",  "trail_time", "collide", "restitution",
         "friction",    "sensor", "category", "mask",   "group",      "angle",   "angular_velocity",
         "inertia",     "shape",  "density",  "sprite", "sprite_size"});
    BodyDef def;
    parse_body_parts(r_, *b, key("body"), def);
    drop_moving_parts(r_, *b, key("body"), def);
    return def;
  }

  /// For generated static or kinematic bodies: warns that the spring tables `keys` given are
  /// ignored (a link between two such bodies, or a pin on one, moves nothing) and returns
  /// true, so that the generator makes no links and no pins.
  bool ignore_springs(const BodyDef& body, std::initializer_list<std::string_view> keys) {
    if (body.type == BodyType::dynamic) return false;
    for (const std::string_view k : keys) {
      if (const toml::node* n = t_.get(k)) {
        r_.warn(n->source(), key(k),
                fmt::format("ignored: the bodies are {} (body.type), and a spring between two "
                            "{} bodies or pinning one moves nothing",
                            body_type_name(body.type), body_type_name(body.type)));
      }
    }
    return true;
  }

  /// A spring table (stiffness/damping or frequency/damping_ratio, and rest_length if
  /// with_rest_length), or nullopt when absent.
  std::optional<SpringSpec> spring(std::string_view k, bool with_rest_length) {
    const toml::table* s = r_.table(t_, k, key(k));
    if (!s) return std::nullopt;
    if (with_rest_length) {
      r_.check_keys(*s, key(k),
                    {"stiffness", "damping", "rest_length", "frequency", "damping_ratio"});
    } else {
      r_.check_keys(*s, key(k), {"stiffness", "damping", "frequency", "damping_ratio"});
    }
    return parse_spring_spec(r_, *s, key(k), with_rest_length);
  }

  /// Appends a body named `body_name` at `position` (start or origin plus a multiple of the
  /// spacing, so a position beyond the scene's precision is the spacing's fault). The name must
  /// be unused.
  void add_body(BodyDef def, std::string body_name, Vec2 position) {
    const bool fits = representable(position.x, scene_.def.precision) &&
                      representable(position.y, scene_.def.precision);
    if (!fits || !within_state(position.x) || !within_state(position.y)) {
      const toml::node& at = required("spacing");
      r_.fail(
          at.source(), key("spacing"),
          fmt::format("body {} would be at ({:g}, {:g}) m, beyond {}", body_name, position.x,
                      position.y,
                      fits ? std::string("+-1e12 m, the runtime guard's range")
                           : fmt::format("the range of {}", precision_text(scene_.def.precision))));
    }
    def.name = std::move(body_name);
    def.body.position = position;
    const auto [it, inserted] = names_.index.emplace(def.name, scene_.def.bodies.size());
    if (!inserted) {
      r_.fail(name_node_ ? name_node_->source() : t_.source(), key("name"),
              fmt::format("body name \"{}\" is already taken by the body of line {} (names must "
                          "be unique)",
                          def.name, scene_.source.body_lines[it->second]));
    }
    scene_.def.bodies.push_back(std::move(def));
    scene_.source.body_lines.push_back(t_.source().begin.line);
    checkpoint("body", scene_.def.bodies.size(), bodies_target_);
  }

  /// Appends a link between bodies a and b (scene indices) with `spring`, whose rest length is
  /// the bodies' starting distance unless `spec` gives one.
  void add_link(std::size_t a, std::size_t b, LinkSpring spring, const SpringSpec& spec) {
    const Vec2 pa = scene_.def.bodies[a].body.position, pb = scene_.def.bodies[b].body.position;
    if (!spec.rest_length) spring.rest_length = det::hypot(pb.x - pa.x, pb.y - pa.y);
    const bool fits = representable(spring.rest_length, scene_.def.precision);
    if (!fits || !within_state(spring.rest_length)) {
      r_.fail(
          required("spacing").source(), key("spacing"),
          fmt::format("bodies {} and {} start {:g} m apart, beyond {}", scene_.def.bodies[a].name,
                      scene_.def.bodies[b].name, spring.rest_length,
                      fits ? std::string("1e12 m, the largest rest length")
                           : fmt::format("the range of {}", precision_text(scene_.def.precision))));
    }
    if (spring.rest_length > 0.0 && same_point(pa, pb, scene_.def.precision)) {
      r_.fail(required("spacing").source(), key("spacing"),
              fmt::format("bodies {} and {} start at the same point, so the direction of a link "
                          "with rest length {:g} m ({}) is undefined; use a spacing that "
                          "separates them or leave rest_length out",
                          scene_.def.bodies[a].name, scene_.def.bodies[b].name, spring.rest_length,
                          spec.path));
    }
    scene_.def.links.push_back(
        LinkDef{fixstep::defined_entity(a), fixstep::defined_entity(b), spring});
    scene_.source.link_lines.push_back(t_.source().begin.line);
    scene_.source.link_keys.push_back(spec.path);
    checkpoint("link", scene_.def.links.size(), links_target_);
  }

  /// Pins body i at its starting position with an anchored spring (rest length 0).
  void pin(std::size_t i, const SpringSpec& spec) {
    BodyDef& def = scene_.def.bodies[i];
    const LinkSpring k = resolve_spring(r_, spec, def.body.mass, 0.0, scene_.def.precision);
    def.spring = SpringDamper{.anchor = def.body.position,
                              .stiffness = k.stiffness,
                              .damping = k.damping,
                              .rest_length = 0.0};
  }

  /// `pin` (an array) and `pin_spring`; each element of `pin` goes through `index`, which
  /// returns the body's scene index. pin without pin_spring is an error, pin_spring without
  /// pin a warning.
  template <class Index>
  void pins(Index&& index) {
    const std::optional<SpringSpec> spec = spring("pin_spring", false);
    const toml::node* n = t_.get("pin");
    if (!n) {
      if (spec) {
        r_.warn(t_.get("pin_spring")->source(), key("pin_spring"),
                "ignored: there is no `pin` list of bodies for it to hold (e.g. pin = [0])");
      }
      return;
    }
    const toml::array* list = n->as_array();
    if (!list) {
      r_.fail(n->source(), key("pin"),
              fmt::format("expected an array of the bodies to pin, found {}", found(*n)));
    }
    if (!spec && !list->empty()) {
      r_.fail(n->source(), key("pin"),
              "needs pin_spring = { stiffness = ... } (N/m) or { frequency = ... } (Hz): the "
              "anchored spring holding each pinned body");
    }
    for (std::size_t k = 0; k < list->size(); ++k) {
      pin(index(*list->get(k), fmt::format("{}[{}]", key("pin"), k)), *spec);
    }
  }

  /// Records what the generator made, for the hints of unknown body names, and where its
  /// bodies begin (scene index `first`), for the keys of messages about them.
  void describe(std::size_t first, std::string prefix, std::string text) {
    names_.generators.emplace_back(std::move(prefix), std::move(text));
    names_.generated.emplace_back(first, path_);
  }

 private:
  /// Every 2^16 items (a few ms): a pending stop request throws StopRequested, and the progress
  /// ("generating the scene: body 65536/1000000") goes to the thread's WorkProgressScope.
  static void checkpoint(std::string_view unit, std::size_t done, std::size_t total) {
    if (done % 65536 != 0) return;
    throw_if_stop_requested();
    if (total > 0) report_work_progress("generating the scene", unit, done, total);
  }

  Reader& r_;
  Scene& scene_;
  BodyNames& names_;
  const toml::table& t_;
  std::string path_;
  const toml::node* name_node_ = nullptr;
  std::size_t bodies_target_ = 0,
              links_target_ = 0;  ///< the scene's counts once this table is done
};

/// The link spring of a generator's equal bodies of mass m: the frequency form acts on the
/// pair's reduced mass m/2.
LinkSpring pair_spring(const Reader& r, const SpringSpec& spec, double m, Precision p) {
  return resolve_spring(r, spec, reduced_mass(m, m), 0.0, p);
}

void parse_chain(Reader& r, const toml::table& t, std::size_t c, Scene& scene, BodyNames& names) {
  Generator g(r, scene, names, t, fmt::format("chain[{}]", c));
  r.check_keys(t, g.path(),
               {"name", "count", "start", "spacing", "body", "link", "pin", "pin_spring"});
  const std::string name = g.name(fmt::format("chain{}", c));
  const toml::node& count_node = g.required("count", "the number of bodies, e.g. count = 10");
  const auto count = static_cast<std::size_t>(
      r.integer_node(count_node, g.key("count"), 1, std::int64_t{max_scene_bodies}));
  g.reserve_bodies(count, count_node, g.key("count"));
  const Vec2 start = r.vec2_node(
      g.required("start", "the first body's position [x, y] in m, e.g. start = [0.0, 0.0]"),
      g.key("start"));
  const Vec2 spacing = r.vec2_node(
      g.required("spacing", "the step [x, y] in m from one body to the next, e.g. [0.1, 0.0]"),
      g.key("spacing"));
  const BodyDef body = g.body_template();
  const std::size_t first = scene.def.bodies.size();
  for (std::size_t i = 0; i < count; ++i) {
    const double s = static_cast<double>(i);
    g.add_body(body, fmt::format("{}[{}]", name, i),
               Vec2{start.x + s * spacing.x, start.y + s * spacing.y});
  }
  g.describe(first, name, fmt::format("{} makes {}[0] .. {}[{}]", g.path(), name, name, count - 1));
  if (g.ignore_springs(body, {"link", "pin", "pin_spring"})) return;
  // Without `link` the bodies are not linked: a row of discs.
  if (const std::optional<SpringSpec> link = g.spring("link", true)) {
    g.reserve_links(count - 1, *t.get("link"), g.key("link"));
    const LinkSpring spring = pair_spring(r, *link, body.body.mass, scene.def.precision);
    for (std::size_t i = 0; i + 1 < count; ++i) {
      g.add_link(first + i, first + i + 1, spring, *link);
    }
  }
  g.pins([&](const toml::node& n, const std::string& key) {
    return first + static_cast<std::size_t>(r.integer_node(
                       n, key, 0, static_cast<std::int64_t>(count) - 1,
                       fmt::format(", the index of one of the chain's {} bodies", count)));
  });
}

/// A grid's bodies: `columns` in a row, `rows` rows, the body of column i and row j at scene
/// index first + j * columns + i.
struct GridShape {
  std::size_t columns = 0, rows = 0, first = 0;

  [[nodiscard]] std::size_t at(std::size_t i, std::size_t j) const {
    return first + j * columns + i;
  }
};

/// A grid's columns and rows (each required, 1 .. max_scene_bodies) and room for its bodies,
/// which begin at scene index `first`.
GridShape read_grid_shape(const Reader& r, Generator& g, std::size_t first) {
  const std::int64_t limit = max_scene_bodies;
  const toml::node& columns_node =
      g.required("columns", "the number of bodies in a row, e.g. columns = 10");
  const auto columns =
      static_cast<std::size_t>(r.integer_node(columns_node, g.key("columns"), 1, limit));
  const toml::node& rows_node = g.required("rows", "the number of rows, e.g. rows = 10");
  const auto rows = static_cast<std::size_t>(r.integer_node(rows_node, g.key("rows"), 1, limit));
  g.reserve_bodies(std::uint64_t{columns} * rows, rows_node, g.key("rows"));
  return GridShape{.columns = columns, .rows = rows, .first = first};
}

/// Appends the grid's bodies, row by row, each a copy of `body` named name[column,row] at
/// origin + (column * spacing.x, row * spacing.y).
void add_grid_bodies(Generator& g, const GridShape& s, const std::string& name, const BodyDef& body,
                     Vec2 origin, Vec2 spacing) {
  for (std::size_t j = 0; j < s.rows; ++j) {
    for (std::size_t i = 0; i < s.columns; ++i) {
      g.add_body(body, fmt::format("{}[{},{}]", name, i, j),
                 Vec2{origin.x + double(i) * spacing.x, origin.y + double(j) * spacing.y});
    }
  }
  g.describe(s.first, name,
             fmt::format("{} makes {}[0,0] .. {}[{},{}] ([column,row])", g.path(), name, name,
                         s.columns - 1, s.rows - 1));
}

/// Links each body to its neighbours `gap` columns and `gap` rows on, row by row.
void link_grid_neighbours(Generator& g, const GridShape& s, const SpringSpec& spec,
                          const LinkSpring& spring, std::size_t gap) {
  for (std::size_t j = 0; j < s.rows; ++j) {
    for (std::size_t i = 0; i < s.columns; ++i) {
      if (i + gap < s.columns) g.add_link(s.at(i, j), s.at(i + gap, j), spring, spec);
      if (j + gap < s.rows) g.add_link(s.at(i, j), s.at(i, j + gap), spring, spec);
    }
  }
}

/// Links both diagonals of each cell, row by row.
void link_grid_diagonals(Generator& g, const GridShape& s, const SpringSpec& spec,
                         const LinkSpring& spring) {
  for (std::size_t j = 0; j + 1 < s.rows; ++j) {
    for (std::size_t i = 0; i + 1 < s.columns; ++i) {
      g.add_link(s.at(i, j), s.at(i + 1, j + 1), spring, spec);
      g.add_link(s.at(i + 1, j), s.at(i, j + 1), spring, spec);
    }
  }
}

/// The grid's link, shear and bend springs (each optional: without any, the bodies are not
/// linked, a box of discs), between bodies of mass m.
void add_grid_links(const Reader& r, Generator& g, const toml::table& t, const GridShape& s,
                    double m, Precision precision) {
  const std::optional<SpringSpec> link = g.spring("link", true);
  const std::optional<SpringSpec> shear = g.spring("shear", true);
  const std::optional<SpringSpec> bend = g.spring("bend", true);
  // Links in order: structural (row then column neighbours, row by row), shear (both
  // diagonals of each cell), bend (neighbours two apart).
  auto pairs = [](std::size_t n, std::size_t gap) { return n > gap ? n - gap : 0; };
  const std::size_t columns = s.columns, rows = s.rows;
  const std::uint64_t structural = link ? pairs(columns, 1) * rows + columns * pairs(rows, 1) : 0;
  const std::uint64_t diagonal = shear ? 2 * pairs(columns, 1) * pairs(rows, 1) : 0;
  const std::uint64_t two_apart = bend ? pairs(columns, 2) * rows + columns * pairs(rows, 2) : 0;
  const std::string_view first_key = link ? "link" : shear ? "shear" : "bend";
  if (link || shear || bend) {
    g.reserve_links(structural + diagonal + two_apart, *t.get(first_key), g.key(first_key));
  }
  if (link) link_grid_neighbours(g, s, *link, pair_spring(r, *link, m, precision), 1);
  if (shear) link_grid_diagonals(g, s, *shear, pair_spring(r, *shear, m, precision));
  if (bend) link_grid_neighbours(g, s, *bend, pair_spring(r, *bend, m, precision), 2);
}

/// The scene index of the body an element n of a grid's `pin` names: [column, row].
std::size_t grid_pin(const Reader& r, const GridShape& s, const toml::node& n,
                     const std::string& key) {
  const toml::array* ij = n.as_array();
  if (!ij || ij->size() != 2) {
    r.fail(n.source(), key,
           ij ? fmt::format("expected [column, row] (2 integers), found {}", elements(ij->size()))
              : fmt::format("expected [column, row], found {}", found(n)));
  }
  const auto i = r.integer_node(*ij->get(0), key + "[0]", 0, std::int64_t(s.columns) - 1,
                                fmt::format(", one of the grid's {} columns", s.columns));
  const auto j = r.integer_node(*ij->get(1), key + "[1]", 0, std::int64_t(s.rows) - 1,
                                fmt::format(", one of the grid's {} rows", s.rows));
  return s.at(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
}

void parse_grid(Reader& r, const toml::table& t, std::size_t c, Scene& scene, BodyNames& names) {
  Generator g(r, scene, names, t, fmt::format("grid[{}]", c));
  r.check_keys(t, g.path(),
               {"name", "columns", "rows", "origin", "spacing", "body", "link", "shear", "bend",
                "pin", "pin_spring"});
  const std::string name = g.name(fmt::format("grid{}", c));
  const GridShape shape = read_grid_shape(r, g, scene.def.bodies.size());
  const Vec2 origin = r.vec2_node(
      g.required("origin", "the position [x, y] in m of the first body, e.g. [0.0, 0.0]"),
      g.key("origin"));
  const Vec2 spacing =
      r.vec2_node(g.required("spacing",
                             "the steps [x, y] in m between columns (x) and rows (y), e.g. "
                             "[0.1, -0.1]"),
                  g.key("spacing"));
  const BodyDef body = g.body_template();
  add_grid_bodies(g, shape, name, body, origin, spacing);
  if (g.ignore_springs(body, {"link", "shear", "bend", "pin", "pin_spring"})) return;
  add_grid_links(r, g, t, shape, body.body.mass, scene.def.precision);
  g.pins([&](const toml::node& n, const std::string& key) { return grid_pin(r, shape, n, key); });
}

}  // namespace

void parse_generators(Reader& r, const toml::table& doc, Scene& scene, BodyNames& names) {
  if (const toml::array* list = r.tables(doc, "chain")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      parse_chain(r, *list->get(i)->as_table(), i, scene, names);
    }
  }
  if (const toml::array* list = r.tables(doc, "grid")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      parse_grid(r, *list->get(i)->as_table(), i, scene, names);
    }
  }
}

}  // namespace fixstep::scene_detail
