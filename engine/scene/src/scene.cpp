#include "fixstep/scene/scene.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "fixstep/core/components.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/printable.hpp"
#include "fixstep/scene/scene_stability.hpp"
#include "scene_reader.hpp"

namespace fixstep {

// Every scene the loader reads fits in a recording, and every scene a recording embeds loads.
static_assert(max_recording_scene_bytes == max_scene_bytes);

namespace {
const scene_detail::FileKind scene_file{"scene file", "a", "a scene", "scenes", ".toml"};

/// `text` with each NUL written as \0.
std::string without_nul(std::string_view text) {
  std::string out;
  for (const char c : text) out += c == '\0' ? std::string("\\0") : std::string(1, c);
  return out;
}
}  // namespace

SceneError::SceneError(std::string file, std::size_t line, std::size_t column, std::string key,
                       const std::string& message)
    // The file and key escaped (a path with a newline stays one line); a NUL in the message
    // escaped too, since what() is read as a C string and would end there.
    : std::runtime_error(fmt::format(
          "{}{}{}: {}{}{}", printable(file), line ? fmt::format(":{}", line) : std::string(),
          line && column ? fmt::format(":{}", column) : std::string(), printable(key),
          key.empty() ? "" : ": ", without_nul(message))),
      file_(std::move(file)),
      line_(line),
      column_(column),
      key_(std::move(key)) {}

namespace scene_detail {

Rgba8 parse_color(const Reader& r, const toml::table& t, std::string_view key,
                  const std::string& path) {
  const toml::node* n = t.get(key);
  const std::string s = *r.string(t, key, path);
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  const bool shape_ok = (s.size() == 7 || s.size() == 9) && s[0] == '#' &&
                        std::all_of(s.begin() + 1, s.end(), [&](char c) { return hex(c) >= 0; });
  if (!shape_ok) {
    r.fail(n->source(), path,
           fmt::format("expected \"#rrggbb\" or \"#rrggbbaa\", found \"{}\"", s));
  }
  auto byte = [&](std::size_t i) {
    return static_cast<std::uint8_t>(hex(s[i]) * 16 + hex(s[i + 1]));
  };
  return Rgba8{byte(1), byte(3), byte(5), s.size() == 9 ? byte(7) : std::uint8_t{255}};
}

namespace {

BodyDef parse_body(Reader& r, const toml::table& t, const std::string& path, Precision precision) {
  r.check_keys(t, path,
               {"name",    "type",     "mass",       "position", "velocity",    "spring",
                "force",   "gravity",  "drag",       "radius",   "draw_radius", "color",
                "visible", "trail",    "trail_time", "collide",  "restitution", "friction",
                "sensor",  "category", "mask",       "group",    "angle",       "angular_velocity",
                "inertia", "shape",    "density",    "sprite",   "sprite_size", "mover"});
  BodyDef def;
  if (auto name = r.string(t, "name", path + ".name")) def.name = *name;
  parse_body_parts(r, t, path, def);
  parse_body_mover(r, t, path, def);  // scene_mover.cpp
  auto position = r.vec2(t, "position", path + ".position");
  if (!position) {
    r.fail_missing(t, path, {"position"}, "missing (required)",
                   "the starting position [x, y] in m, e.g. position = [0.0, 0.0]");
  }
  def.body.position = *position;
  r.require_state(t, "position", path + ".position", *position, "m");

  if (const toml::table* s = r.table(t, "spring", path + ".spring")) {
    const std::string sp = path + ".spring";
    r.check_keys(*s, sp,
                 {"anchor", "stiffness", "damping", "rest_length", "frequency", "damping_ratio"});
    SpringDamper spring;
    if (auto a = r.vec2(*s, "anchor", sp + ".anchor")) {
      r.require_state(*s, "anchor", sp + ".anchor", *a, "m");
      spring.anchor = *a;
    }
    const SpringSpec spec = parse_spring_spec(r, *s, sp, true);
    // The frequency form acts on the body's own mass: k = m (2πf)², b = 2 m ζ (2πf).
    const LinkSpring k = resolve_spring(r, spec, def.body.mass, 0.0, precision);
    spring.stiffness = k.stiffness;
    spring.damping = k.damping;
    spring.rest_length = k.rest_length;
    def.spring = spring;
  }
  drop_moving_parts(r, t, path, def);
  return def;
}

/// Every number of a scene is 0 or between min_coefficient and max_coefficient in magnitude
/// (value_ranges.hpp): beyond, a product or quotient a step forms (½ m v², 1/m, r/I) may leave
/// double's range, and a subnormal divisor makes it infinite. Run after the keys' own checks,
/// which name their ranges more precisely.
void check_magnitudes(const Reader& r, const toml::node& node, const std::string& path) {
  if (const toml::table* t = node.as_table()) {
    for (auto&& [k, v] : *t) {
      check_magnitudes(r, v,
                       path.empty() ? std::string(k.str()) : path + "." + std::string(k.str()));
    }
  } else if (const toml::array* a = node.as_array()) {
    for (std::size_t i = 0; i < a->size(); ++i) {
      check_magnitudes(r, *a->get(i), fmt::format("{}[{}]", path, i));
    }
  } else if (const toml::value<double>* f = node.as_floating_point()) {  // integers are exact
    const double v = std::abs(f->get());
    if (std::isfinite(v) && v != 0.0 && !(v >= min_coefficient && v <= max_coefficient)) {
      r.fail(node.source(), path,
             fmt::format("{:g} is beyond what a step's arithmetic holds: a scene's numbers are 0 "
                         "or between 1e-100 and 1e100 in magnitude (products such as m v^2 and "
                         "quotients such as 1/m must stay finite)",
                         f->get()));
    }
  }
}

/// Every number of an f32 scene must stay finite as a float.
void check_f32(const Reader& r, const toml::node& node, const std::string& path) {
  if (const toml::table* t = node.as_table()) {
    for (auto&& [k, v] : *t)
      check_f32(r, v, path.empty() ? std::string(k.str()) : path + "." + std::string(k.str()));
  } else if (const toml::array* a = node.as_array()) {
    for (std::size_t i = 0; i < a->size(); ++i)
      check_f32(r, *a->get(i), fmt::format("{}[{}]", path, i));
  } else if (node.is_number()) {
    const double v = *node.value<double>();
    if (std::isfinite(v)) r.require_f32(v, &node, path);
  }
}

}  // namespace

void parse_body_parts(Reader& r, const toml::table& t, const std::string& path, BodyDef& def) {
  def.type = parse_body_type(r, t, path);
  parse_body_mass(r, t, path, def);
  if (auto v = r.vec2(t, "velocity", path + ".velocity")) {
    r.require_state(t, "velocity", path + ".velocity", *v, "m/s");
    def.body.velocity = *v;
  }
  if (auto f = r.vec2(t, "force", path + ".force")) def.constant_force = ConstantForce{*f};
  if (auto g = r.vec2(t, "gravity", path + ".gravity")) def.gravity = Gravity{*g};
  if (auto c = r.number(t, "drag", path + ".drag")) {
    r.require(*c >= 0.0, t, "drag", path + ".drag", ">= 0 N*s/m", *c);  // <= 1e100: magnitudes
    def.drag = LinearDrag{*c};
  }
  if (t.get("radius") || t.get("draw_radius") || t.get("color") || t.get("visible") ||
      t.get("trail") || t.get("trail_time") || t.get("sprite") || t.get("sprite_size")) {
    Appearance ap;
    if (auto rad = r.number(t, "radius", path + ".radius")) {
      r.require(*rad > 0.0 && *rad <= max_state_magnitude, t, "radius", path + ".radius",
                "> 0 m and <= 1e12 m", *rad);
      ap.radius = *rad;
      def.collider = Collider{.radius = *rad};  // a disc, for planes and [contacts]
    }
    if (auto rad = r.number(t, "draw_radius", path + ".draw_radius")) {
      r.require(*rad > 0.0 && *rad <= max_state_magnitude, t, "draw_radius", path + ".draw_radius",
                "> 0 m and <= 1e12 m", *rad);
      ap.radius = *rad;  // drawing only: no disc without `radius`
    }
    if (t.get("color")) ap.color = parse_color(r, t, "color", path + ".color");
    if (auto v = r.boolean(t, "visible", path + ".visible")) ap.visible = *v;
    if (auto v = r.boolean(t, "trail", path + ".trail")) ap.trail = *v;
    if (auto v = r.number(t, "trail_time", path + ".trail_time")) {
      r.require(*v > 0.0 && *v <= max_trail_time, t, "trail_time", path + ".trail_time",
                "> 0 and <= 10 s", *v);
      ap.trail_time = *v;
    }
    if (t.get("sprite")) ap.sprite = parse_image(r, t, "sprite", path + ".sprite");
    if (auto v = r.vec2(t, "sprite_size", path + ".sprite_size")) {
      r.require(
          v->x > 0.0 && v->y > 0.0 && v->x <= max_state_magnitude && v->y <= max_state_magnitude, t,
          "sprite_size", path + ".sprite_size", "[width, height], each > 0 m and <= 1e12 m",
          std::min(v->x, v->y));
      if (!t.get("sprite")) {
        r.fail(t.get("sprite_size")->source(), path + ".sprite_size",
               "needs a sprite: the size (m) of the image drawn for the body; add sprite = "
               "\"image.png\"");
      }
      ap.sprite_size = *v;
    }
    def.appearance = ap;
  }
  parse_body_shapes(r, t, path, def);
  parse_disc_keys(r, t, path, def);
  parse_rolling_keys(r, t, path, def);
}

namespace {

/// The TOML document of a scene's text: an error when it is empty, or names a table or key no
/// scene has.
toml::table read_document(Reader& r, std::string_view text, const std::string& source_name) {
  toml::table doc = parse_toml(text, source_name, max_scene_bytes, scene_file);
  if (doc.empty()) {
    throw SceneError(source_name, 0, 0, "",
                     "the scene file is empty (no tables or keys): a scene needs a [world] table "
                     "with dt and at least one [[body]]; see README, Scene format");
  }
  r.check_keys(doc, "",
               {"world", "view", "contacts", "body", "spring", "chain", "grid", "plane", "segment",
                "polyline", "joint"});
  return doc;
}

/// The valid integrator a misspelt `name` most likely meant: one within two edits, else the one
/// valid name holding what was written ("verlet"); nullopt when there is none.
std::optional<std::string> suggest_integrator(const std::string& name) {
  std::vector<std::string> valid;
  for (const Integrator v : all_integrators) valid.emplace_back(integrator_name(v));
  std::optional<std::string> best = closest(name, valid);
  if (!best && name.size() >= 2 &&
      std::count_if(valid.begin(), valid.end(),
                    [&](const std::string& v) { return v.find(name) != std::string::npos; }) == 1) {
    best = *std::find_if(valid.begin(), valid.end(),
                         [&](const std::string& v) { return v.find(name) != std::string::npos; });
  }
  return best;
}

/// world.integrator into scene.settings.integrator (an unknown name is an error, with the name
/// it most likely meant).
void read_integrator(const Reader& r, const toml::table& world, Scene& scene) {
  if (auto name = r.string(world, "integrator", "world.integrator")) {
    auto i = parse_integrator(*name);
    if (!i) {
      const std::optional<std::string> best = suggest_integrator(*name);
      r.fail(world.get("integrator")->source(), "world.integrator",
             fmt::format("unknown integrator \"{}\"{} (valid: {})", *name,
                         best ? fmt::format("; did you mean \"{}\"?", *best) : std::string(),
                         integrator_names()));
    }
    scene.def.settings.integrator = *i;
  }
}

/// world.precision into scene.precision.
void read_precision(const Reader& r, const toml::table& world, Scene& scene) {
  if (auto name = r.string(world, "precision", "world.precision")) {
    auto p = parse_precision(*name);
    if (!p) {
      r.fail(world.get("precision")->source(), "world.precision",
             fmt::format("unknown precision \"{}\" (valid: f32, f64)", *name));
    }
    scene.def.precision = *p;
  }
}

/// The optional keys of [world] after dt, integrator and precision, in this order: substeps,
/// seed, allow_unstable, flush_denormals and damping_split.
void read_world_options(const Reader& r, const toml::table& world, Scene& scene) {
  if (const toml::node* n = world.get("substeps")) {
    scene.def.settings.substeps =
        static_cast<int>(r.integer_node(*n, "world.substeps", 1, 1000000));
  }
  if (const toml::node* n = world.get("seed")) {  // TOML integers: 0 .. 2^63 - 1
    scene.def.settings.seed = static_cast<std::uint64_t>(
        r.integer_node(*n, "world.seed", 0, std::numeric_limits<std::int64_t>::max()));
  }
  if (auto b = r.boolean(world, "allow_unstable", "world.allow_unstable")) {
    scene.def.allow_unstable = *b;
  }
  if (auto b = r.boolean(world, "flush_denormals", "world.flush_denormals")) {
    scene.def.settings.flush_denormals = *b;
  }
  if (auto name = r.string(world, "damping_split", "world.damping_split")) {
    const auto split = parse_damping_split(*name);
    if (!split) {
      r.fail(world.get("damping_split")->source(), "world.damping_split",
             fmt::format("unknown damping split \"{}\" (valid: per_stage, per_step)", *name));
    }
    scene.def.settings.damping_split = *split;
  }
}

/// The [world] table (required) into scene.def's settings, precision and allow_unstable;
/// returns it, for the errors of the limits that its keys set.
const toml::table& parse_world(Reader& r, const toml::table& doc, Scene& scene) {
  const toml::table* world = r.table(doc, "world", "world");
  if (!world) {
    r.fail_missing(doc, "", {"world"}, "missing [world] table (required)",
                   "add [world] with dt, the fixed step in s, e.g. dt = 0.01");
  }
  r.check_keys(*world, "world",
               {"dt", "integrator", "precision", "substeps", "allow_unstable", "flush_denormals",
                "damping_split", "seed"});
  scene.def.settings.dt = r.required_number(
      *world, "world", "dt", "the fixed physics step in s, e.g. dt = 0.01 (100 ticks/s)");
  r.require(scene.def.settings.dt > 0.0 && scene.def.settings.dt <= 1.0, *world, "dt", "world.dt",
            "> 0 and <= 1 s", scene.def.settings.dt);
  read_integrator(r, *world, scene);
  read_precision(r, *world, scene);
  read_world_options(r, *world, scene);
  return *world;
}

/// [[body]] tables: appends their bodies (named "body<i>" when unnamed; names must be unique)
/// and lines to the scene.
void parse_bodies(Reader& r, const toml::table& doc, Scene& scene, BodyNames& names) {
  const toml::array* list = r.tables(doc, "body");
  if (!list) return;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table& t = *list->get(i)->as_table();
    const std::string path = fmt::format("body[{}]", i);
    BodyDef def = parse_body(r, t, path, scene.def.precision);
    if (def.name.empty()) def.name = fmt::format("body{}", i);
    if (!names.index.emplace(def.name, scene.def.bodies.size()).second) {
      const toml::node* n = t.get("name");
      r.fail(n ? n->source() : t.source(), path + ".name",
             fmt::format("duplicate body name \"{}\" (names must be unique)", def.name));
    }
    scene.def.bodies.push_back(std::move(def));
    scene.source.body_lines.push_back(t.source().begin.line);
  }
}

/// The work and memory limits (limits.hpp), an error at the key of `world` that sets the work
/// per tick.
void check_limits(const Reader& r, const Scene& scene, const toml::table& doc,
                  const toml::table& world) {
  const WorldDef& def = scene.def;
  try {
    check_world_limits(def.bodies, def.links, def.planes, def.settings, def.segments);
  } catch (const LimitError& e) {
    // check_world_limits checks the implicit solve's size first, then the work per tick. A
    // world within the work without its segments is over it by them: at its first
    // [[segment]] (or [[polyline]]).
    if (!def.segments.empty() &&
        tick_work(def.bodies, def.links, def.planes, def.settings) <= max_tick_work) {
      const bool single = doc.get("segment") != nullptr;
      const toml::array* list = doc.get_as<toml::array>(single ? "segment" : "polyline");
      const toml::node* first = list && !list->empty() ? list->get(0) : nullptr;
      if (first) r.fail(first->source(), single ? "segment[0]" : "polyline[0]", e.what());
    }
    const bool memory = !implicit_solve_within_limits(def.bodies, def.links, def.settings);
    const std::string key = memory ? "integrator" : "substeps";
    const toml::node* at = world.get(key);
    r.fail(at ? at->source() : world.source(), at ? "world." + key : "world", e.what());
  }
}

}  // namespace

}  // namespace scene_detail

Scene parse_scene(std::string_view text, const std::string& source_name) {
  // The numbers read (strtod rounds in the current mode), rest lengths, frequency-form
  // stiffness and damping: the same whatever the caller's FPU mode (fixstep/core/float_mode.hpp).
  const IeeeFloatMode ieee;
  using namespace scene_detail;
  Scene scene;
  scene.file = source_name;
  scene.def.settings.track_dissipation = true;
  Reader r(scene.file);

  const toml::table doc = read_document(r, text, source_name);
  const toml::table& world = parse_world(r, doc, scene);
  // Every number first, so that a generated position beyond float range is the spacing's fault.
  if (scene.def.precision == Precision::f32) check_f32(r, doc, "");
  parse_view(r, doc, scene);

  // Bodies: [[body]] tables, then the generators' bodies; links: the generators', then
  // [[spring]] tables (which may name any body).
  BodyNames names;
  parse_bodies(r, doc, scene, names);
  parse_generators(r, doc, scene, names);
  if (scene.def.bodies.empty()) {
    throw SceneError(source_name, 1, 1, "body",
                     "no [[body]], [[chain]] or [[grid]] tables: a scene needs at least one body; "
                     "add one, e.g. [[body]] with mass = 1.0 and position = [0.0, 0.0]");
  }
  parse_springs(r, doc, scene, names);
  parse_planes(r, doc, scene);
  parse_segments(r, doc, scene, names);
  parse_joints(r, doc, scene, names);
  parse_contacts(r, doc, scene);
  check_magnitudes(r, doc, "");  // every number, after the keys' own ranges
  check_start_overlap(scene, names);
  check_limits(r, scene, doc, world);
  check_image_budget(r, doc, scene);
  scene.warnings = r.take_warnings();
  scene.text = std::string(text);
  return scene;
}

Scene load_scene(const std::filesystem::path& file) {
  return parse_scene(scene_detail::read_text_file(file, max_scene_bytes, scene_file),
                     file.string());
}

}  // namespace fixstep
