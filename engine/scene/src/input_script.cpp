// Input scripts: [[at]] tables of a TOML file read with the scene loader's Reader (FILE:LINE:
// COLUMN: KEY errors, unknown keys warned about with a suggestion).
#include "fixstep/scene/input_script.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "scene_reader.hpp"

namespace fixstep {

namespace {

using scene_detail::Reader;
const scene_detail::FileKind script_file{"input script", "an", "an input script", "input scripts",
                                         ".toml"};

constexpr std::array<std::pair<std::string_view, std::uint32_t>, 7> buttons{{
    {"left", button_left},
    {"right", button_right},
    {"up", button_up},
    {"down", button_down},
    {"action", button_action},
    {"pointer_primary", button_pointer_primary},
    {"pointer_secondary", button_pointer_secondary},
}};

/// `press` / `release`: an array of action names, as their bits.
std::uint32_t button_list(const Reader& r, const toml::table& t, std::string_view key,
                          const std::string& path, const ScriptNames& known) {
  const toml::node* n = t.get(key);
  if (!n) return 0;
  const toml::array* a = n->as_array();
  if (!a)
    r.fail(n->source(), path,
           fmt::format("expected an array of action names, e.g. [\"{}\"], found {}",
                       known.actions.empty() ? "left" : known.actions.front().first,
                       scene_detail::found(*n)));
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const std::string at = fmt::format("{}[{}]", path, i);
    if (!e.is_string()) {
      r.fail(e.source(), at,
             fmt::format("expected an action name (a string), found {}", scene_detail::found(e)));
    }
    const std::string_view name = e.as_string()->get();
    const auto found = std::find_if(known.actions.begin(), known.actions.end(),
                                    [&](const auto& b) { return b.first == name; });
    if (found == known.actions.end()) {
      std::vector<std::string> names;
      for (const auto& b : known.actions) names.push_back(b.first);
      const auto best = closest(name, names);
      r.fail(e.source(), at,
             fmt::format("unknown action \"{}\"{} (valid: {})", name,
                         best ? fmt::format("; did you mean \"{}\"?", *best) : "",
                         fmt::join(names, ", ")));
    }
    bits |= found->second;
  }
  return bits;
}

/// `axes = { NAME = VALUE, ... }`: levels in [-1, 1], in the order of the table's keys.
std::vector<std::pair<std::size_t, double>> axis_list(Reader& r, const toml::table& t,
                                                      const std::string& path,
                                                      const ScriptNames& known) {
  std::vector<std::pair<std::size_t, double>> out;
  const toml::node* n = t.get("axes");
  if (!n) return out;
  const toml::table* table = n->as_table();
  if (!table) {
    r.fail(n->source(), path,
           fmt::format("expected a table of axis values, e.g. {{ {} = 0.5 }}, found {}",
                       known.axes.empty() ? "steer" : known.axes.front().first,
                       scene_detail::found(*n)));
  }
  for (const auto& [key, value] : *table) {
    const std::string name(key.str());  // a structured binding no lambda may capture (clang 14)
    const std::string at = fmt::format("{}.{}", path, name);
    const auto found = std::find_if(known.axes.begin(), known.axes.end(),
                                    [&](const auto& a) { return a.first == name; });
    if (found == known.axes.end()) {
      std::vector<std::string> names;
      for (const auto& a : known.axes) names.push_back(a.first);
      const auto best = closest(key.str(), names);
      r.fail(value.source(), at,
             fmt::format("unknown axis \"{}\"{} (valid: {})", key.str(),
                         best ? fmt::format("; did you mean \"{}\"?", *best) : "",
                         names.empty() ? std::string("none: the program declares no axes")
                                       : fmt::format("{}", fmt::join(names, ", "))));
    }
    const double v = r.number_node(value, at);
    if (!(v >= -1.0 && v <= 1.0)) {
      r.fail(value.source(), at, fmt::format("must be in [-1, 1] (got {})", v));
    }
    out.emplace_back(found->second, v);
  }
  return out;
}

/// The index into `bodies` of the body named by string node n (the first of that name).
std::size_t body_index(const Reader& r, const toml::node& n, const std::string& path,
                       std::span<const BodyDef> bodies) {
  const std::string_view name = n.as_string()->get();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == name) return i;
  }
  std::vector<std::string> names;
  names.reserve(bodies.size());
  for (const BodyDef& b : bodies) names.push_back(b.name);
  const auto best = closest(name, names);
  r.fail(n.source(), path,
         fmt::format("no body named \"{}\"{}", name,
                     best ? fmt::format(" (did you mean \"{}\"?)", *best) : ""));
}

/// `drag`: a body name (its handle in the world World(def) builds) or false (no body).
Entity drag_target(const Reader& r, const toml::node& n, const std::string& path,
                   std::span<const BodyDef> bodies) {
  if (n.is_boolean() && !n.as_boolean()->get()) return null_entity;
  if (!n.is_string()) {
    r.fail(n.source(), path,
           fmt::format("expected a body name or false, found {}",
                       n.is_boolean() ? std::string("true") : scene_detail::found(n)));
  }
  return fixstep::defined_entity(body_index(r, n, path, bodies));
}

constexpr bool angular(BodyInputKind kind) {
  return kind >= BodyInputKind::torque;
}

/// Whether `kind` sets what a kinematic body moves at (velocity, angular_velocity,
/// target_angle) rather than pushing a dynamic one.
constexpr bool kinematic_kind(BodyInputKind kind) {
  return kind == BodyInputKind::velocity || kind == BodyInputKind::angular_velocity ||
         kind == BodyInputKind::target_angle;
}

/// Why body b cannot take input `kind`, or "" when it can (World::check_input's rules).
std::string wrong_type(BodyInputKind kind, const BodyDef& b) {
  const char* name = body_input_kind_name(kind);
  const bool turn = angular(kind);
  if (kinematic_kind(kind)) {
    if (b.type != BodyType::kinematic) {
      return fmt::format("\"{}\" is a {} body: {} is for kinematic bodies only{}", b.name,
                         body_type_name(b.type), name,
                         b.type != BodyType::dynamic ? ""
                         : turn ? " (turn a dynamic one with angular_impulse or torque)"
                                : " (push a dynamic one with impulse or force)");
    }
  } else if (b.type != BodyType::dynamic) {
    return fmt::format("\"{}\" is a {} body: {} acts on dynamic bodies only{}", b.name,
                       body_type_name(b.type), name,
                       b.type != BodyType::kinematic ? ""
                       : turn ? " (turn a kinematic one with angular_velocity or target_angle)"
                              : " (move a kinematic one with velocity)");
  }
  if (turn && b.shapes.empty()) {
    return fmt::format("\"{}\" has no shapes: {} turns bodies with shapes only", b.name, name);
  }
  return {};
}

/// What `value` is for kind, in the words of a missing value's help.
const char* value_help(BodyInputKind kind) {
  switch (kind) {
    case BodyInputKind::force:
      return "the force [x, y] in N, e.g. value = [0.0, 40.0]";
    case BodyInputKind::impulse:
      return "the impulse [x, y] in N*s, e.g. value = [1.0, 0.5]";
    case BodyInputKind::velocity:
      return "the velocity [x, y] in m/s, e.g. value = [2.0, 0.0]";
    case BodyInputKind::torque:
      return "the torque in N*m (counter-clockwise positive), e.g. value = 5.0";
    case BodyInputKind::angular_impulse:
      return "the angular impulse in N*m*s (counter-clockwise positive), e.g. value = 0.5";
    case BodyInputKind::angular_velocity:
      return "the angular velocity in rad/s (counter-clockwise positive), e.g. value = 3.0";
    case BodyInputKind::target_angle:
      return "the angle in rad reached at the tick's end, e.g. value = 0.5";
  }
  return "";
}

/// The value of an angular kind: one number (stored as [x, 0]).
Vec2 angular_value(const Reader& r, const toml::node& n, BodyInputKind kind,
                   const std::string& path) {
  if (n.is_array()) {
    r.fail(n.source(), path,
           fmt::format("expected one number, not [x, y]: {} (found {})", value_help(kind),
                       scene_detail::found(n)));
  }
  return {r.number_node(n, path), 0.0};
}

/// One `{ body = "NAME", value = [x, y] }` table at `path` (value = NUMBER for the angular
/// kinds).
BodyInput body_input(Reader& r, const toml::table& t, BodyInputKind kind, const std::string& path,
                     std::span<const BodyDef> bodies) {
  r.check_keys(t, path, {"body", "value"});
  const toml::node* name = t.get("body");
  if (!name) {
    r.fail_missing(t, path, {"body"}, "missing (required)",
                   "the name of the body it acts on, e.g. body = \"ball\"");
  }
  if (!name->is_string()) {
    r.fail(name->source(), path + ".body",
           fmt::format("expected a body name (a string), found {}", scene_detail::found(*name)));
  }
  const std::size_t i = body_index(r, *name, path + ".body", bodies);
  if (const std::string why = wrong_type(kind, bodies[i]); !why.empty()) {
    r.fail(name->source(), path + ".body", why);
  }
  const toml::node* value = t.get("value");
  if (!value) r.fail_missing(t, path, {"value"}, "missing (required)", value_help(kind));
  const std::string at = path + ".value";
  return BodyInput{fixstep::defined_entity(i), kind,
                   angular(kind) ? angular_value(r, *value, kind, at) : r.vec2_node(*value, at)};
}

[[noreturn]] void not_body_input(const Reader& r, const toml::node& n, BodyInputKind kind,
                                 const std::string& path) {
  r.fail(n.source(), path,
         fmt::format("expected {{ body = \"NAME\", value = {} }} or an array of them, found {}",
                     angular(kind) ? "NUMBER" : "[x, y]", scene_detail::found(n)));
}

/// A per-body input key of an [[at]] table (force, impulse, velocity, torque, angular_impulse,
/// angular_velocity, target_angle): one inline table or an array of them, appended to out.
void body_inputs(Reader& r, const toml::table& t, BodyInputKind kind, const std::string& path,
                 std::span<const BodyDef> bodies, std::vector<BodyInput>& out) {
  const toml::node* n = t.get(body_input_kind_name(kind));
  if (!n) return;
  if (const toml::table* one = n->as_table()) {
    out.push_back(body_input(r, *one, kind, path, bodies));
    return;
  }
  const toml::array* a = n->as_array();
  if (!a) not_body_input(r, *n, kind, path);
  for (std::size_t i = 0; i < a->size(); ++i) {
    const std::string at = fmt::format("{}[{}]", path, i);
    const toml::table* e = a->get(i)->as_table();
    if (!e) not_body_input(r, *a->get(i), kind, at);
    out.push_back(body_input(r, *e, kind, at, bodies));
  }
}

ScriptEvent parse_event(Reader& r, const toml::table& t, std::size_t index,
                        std::span<const BodyDef> bodies, const ScriptNames& known) {
  const std::string path = fmt::format("at[{}]", index);
  r.check_keys(t, path,
               {"tick", "press", "release", "axes", "pointer", "push", "drag", "force", "impulse",
                "velocity", "torque", "angular_impulse", "angular_velocity", "target_angle"});
  ScriptEvent e;
  e.line = t.source().begin.line;
  const toml::node* tick = t.get("tick");
  if (!tick) {
    r.fail_missing(t, path, {"tick"}, "missing (required)",
                   "the tick (0, 1, ...) at which this [[at]] table's inputs apply, e.g. tick = 0");
  }
  e.tick = static_cast<std::uint64_t>(
      r.integer_node(*tick, path + ".tick", 0, static_cast<std::int64_t>(max_recording_ticks - 1)));
  e.press = button_list(r, t, "press", path + ".press", known);
  e.release = button_list(r, t, "release", path + ".release", known);
  e.axes = axis_list(r, t, path + ".axes", known);
  e.pointer = r.vec2(t, "pointer", path + ".pointer");
  e.push = r.vec2(t, "push", path + ".push");
  if (const toml::node* d = t.get("drag")) e.drag = drag_target(r, *d, path + ".drag", bodies);
  // In BodyInputKind order: forces, impulses, velocities, torques, angular impulses, angular
  // velocities, target angles, each in file order.
  for (int k = 0; k <= static_cast<int>(last_body_input_kind); ++k) {
    const auto kind = static_cast<BodyInputKind>(k);
    body_inputs(r, t, kind, path + "." + body_input_kind_name(kind), bodies, e.bodies);
  }
  if (e.bodies.size() > max_body_inputs) {
    r.fail(t.source(), path,
           fmt::format("{} per-body inputs (force, impulse, velocity, torque, angular_impulse, "
                       "angular_velocity, target_angle) in one tick; at most {}",
                       e.bodies.size(), max_body_inputs));
  }
  return e;
}

}  // namespace

std::span<const std::pair<std::string_view, std::uint32_t>> button_names() {
  return buttons;
}

ScriptNames default_script_names() {
  ScriptNames names;
  for (const auto& [name, bit] : buttons) names.actions.emplace_back(std::string(name), bit);
  return names;
}

InputScript parse_input_script(std::string_view text, const std::string& source_name,
                               std::span<const BodyDef> bodies, const ScriptNames& known) {
  const IeeeFloatMode ieee;  // numbers read by strtod, which rounds in the current mode
  InputScript script;
  script.file = source_name;
  Reader r(script.file);
  const toml::table doc =
      scene_detail::parse_toml(text, source_name, max_script_bytes, script_file);
  if (!doc.get("at") && (doc.get("world") || doc.get("body"))) {
    // Without this, a scene given as the script would run with no input and two warnings.
    const toml::node* n = doc.get("world") ? doc.get("world") : doc.get("body");
    r.fail(
        n->source(), "",
        "this is a scene file, not an input script: a script holds [[at]] tables (tick, "
        "press, release, pointer, push, drag, force, impulse, velocity, torque, angular_impulse, "
        "angular_velocity, target_angle); see docs/CLI.md, Input scripts");
  }
  r.check_keys(doc, "", {"at"});
  if (const toml::array* list = r.tables(doc, "at")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table& t = *list->get(i)->as_table();
      ScriptEvent e = parse_event(r, t, i, bodies, known);
      if (!script.events.empty() && e.tick <= script.events.back().tick) {
        r.fail(t.get("tick")->source(), fmt::format("at[{}].tick", i),
               fmt::format("ticks must increase from one [[at]] to the next ({} after {})", e.tick,
                           script.events.back().tick));
      }
      script.events.push_back(e);
    }
  }
  script.warnings = r.take_warnings();
  return script;
}

InputScript load_input_script(const std::filesystem::path& file, std::span<const BodyDef> bodies,
                              const ScriptNames& known) {
  return parse_input_script(scene_detail::read_text_file(file, max_script_bytes, script_file),
                            file.string(), bodies, known);
}

TickInput ScriptPlayer::next() {
  feed(tick_, sampler_);
  return sampler_.sample(tick_++);
}

void ScriptPlayer::feed(std::uint64_t tick, InputSampler& sampler) {
  while (event_ < script_.events.size() && script_.events[event_].tick < tick) ++event_;
  if (event_ < script_.events.size() && script_.events[event_].tick == tick) {
    const ScriptEvent& e = script_.events[event_++];
    if (e.press) sampler.press(e.press);
    for (const auto& [index, value] : e.axes) sampler.set_axis(index, value);
    if (e.release) sampler.release(e.release);
    if (e.pointer) sampler.set_pointer(*e.pointer);
    if (e.push) sampler.set_push(*e.push);
    if (e.drag) sampler.set_drag_body(*e.drag);
    for (const BodyInput& b : e.bodies) {
      switch (b.kind) {
        case BodyInputKind::force:
          sampler.apply_force(b.body, b.value);
          break;
        case BodyInputKind::impulse:
          sampler.apply_impulse(b.body, b.value);
          break;
        case BodyInputKind::velocity:
          sampler.set_velocity(b.body, b.value);
          break;
        case BodyInputKind::torque:
          sampler.apply_torque(b.body, b.value.x);
          break;
        case BodyInputKind::angular_impulse:
          sampler.apply_angular_impulse(b.body, b.value.x);
          break;
        case BodyInputKind::angular_velocity:
          sampler.set_angular_velocity(b.body, b.value.x);
          break;
        case BodyInputKind::target_angle:
          sampler.set_target_angle(b.body, b.value.x);
          break;
      }
    }
  }
}

std::vector<TickInput> script_inputs(const InputScript& script, std::uint64_t ticks) {
  ScriptPlayer player(script);
  std::vector<TickInput> out;
  out.reserve(ticks);
  for (std::uint64_t t = 0; t < ticks; ++t) out.push_back(player.next());
  return out;
}

}  // namespace fixstep
