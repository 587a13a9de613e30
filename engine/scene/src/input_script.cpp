// Input scripts: [[at]] tables of a TOML file read with the scene loader's Reader (FILE:LINE:
// COLUMN: KEY errors, unknown keys warned about with a suggestion).
#include "fixstep/scene/input_script.hpp"

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

/// `press` / `release`: an array of button names, as InputButton bits.
std::uint32_t button_list(const Reader& r, const toml::table& t, std::string_view key,
                          const std::string& path) {
  const toml::node* n = t.get(key);
  if (!n) return 0;
  const toml::array* a = n->as_array();
  if (!a)
    r.fail(n->source(), path,
           fmt::format("expected an array of button names, e.g. [\"left\"], found {}",
                       scene_detail::found(*n)));
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const std::string at = fmt::format("{}[{}]", path, i);
    if (!e.is_string()) {
      r.fail(e.source(), at,
             fmt::format("expected a button name (a string), found {}", scene_detail::found(e)));
    }
    const std::string_view name = e.as_string()->get();
    const auto found = std::find_if(buttons.begin(), buttons.end(),
                                    [&](const auto& b) { return b.first == name; });
    if (found == buttons.end()) {
      std::vector<std::string> names;
      names.reserve(buttons.size());
      for (const auto& b : buttons) names.emplace_back(b.first);
      const auto best = closest(name, names);
      r.fail(e.source(), at,
             fmt::format("unknown button \"{}\"{} (valid: left, right, up, down, action, "
                         "pointer_primary, pointer_secondary)",
                         name, best ? fmt::format("; did you mean \"{}\"?", *best) : ""));
    }
    bits |= found->second;
  }
  return bits;
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

/// Why body b cannot take input `kind`, or "" when it can.
std::string wrong_type(BodyInputKind kind, const BodyDef& b) {
  if (kind == BodyInputKind::velocity) {
    if (b.type == BodyType::kinematic) return {};
    return fmt::format(
        "\"{}\" is a {} body: velocity is for kinematic bodies only{}", b.name,
        body_type_name(b.type),
        b.type == BodyType::dynamic ? " (push a dynamic one with impulse or force)" : "");
  }
  if (b.type == BodyType::dynamic) return {};
  return fmt::format("\"{}\" is a {} body: {} acts on dynamic bodies only{}", b.name,
                     body_type_name(b.type), kind == BodyInputKind::force ? "force" : "impulse",
                     b.type == BodyType::kinematic ? " (move a kinematic one with velocity)" : "");
}

/// One `{ body = "NAME", value = [x, y] }` table at `path`.
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
  if (!value) {
    r.fail_missing(t, path, {"value"}, "missing (required)",
                   kind == BodyInputKind::force ? "the force [x, y] in N, e.g. value = [0.0, 40.0]"
                   : kind == BodyInputKind::impulse
                       ? "the impulse [x, y] in N*s, e.g. value = [1.0, 0.5]"
                       : "the velocity [x, y] in m/s, e.g. value = [2.0, 0.0]");
  }
  return BodyInput{fixstep::defined_entity(i), kind, r.vec2_node(*value, path + ".value")};
}

[[noreturn]] void not_body_input(const Reader& r, const toml::node& n, const std::string& path) {
  r.fail(n.source(), path,
         fmt::format("expected {{ body = \"NAME\", value = [x, y] }} or an array of them, found {}",
                     scene_detail::found(n)));
}

/// `force`, `impulse` or `velocity` of an [[at]] table: one inline table or an array of them,
/// appended to out.
void body_inputs(Reader& r, const toml::table& t, std::string_view key, BodyInputKind kind,
                 const std::string& path, std::span<const BodyDef> bodies,
                 std::vector<BodyInput>& out) {
  const toml::node* n = t.get(key);
  if (!n) return;
  if (const toml::table* one = n->as_table()) {
    out.push_back(body_input(r, *one, kind, path, bodies));
    return;
  }
  const toml::array* a = n->as_array();
  if (!a) not_body_input(r, *n, path);
  for (std::size_t i = 0; i < a->size(); ++i) {
    const std::string at = fmt::format("{}[{}]", path, i);
    const toml::table* e = a->get(i)->as_table();
    if (!e) not_body_input(r, *a->get(i), at);
    out.push_back(body_input(r, *e, kind, at, bodies));
  }
}

ScriptEvent parse_event(Reader& r, const toml::table& t, std::size_t index,
                        std::span<const BodyDef> bodies) {
  const std::string path = fmt::format("at[{}]", index);
  r.check_keys(
      t, path,
      {"tick", "press", "release", "pointer", "push", "drag", "force", "impulse", "velocity"});
  ScriptEvent e;
  e.line = t.source().begin.line;
  const toml::node* tick = t.get("tick");
  if (!tick) {
    r.fail_missing(t, path, {"tick"}, "missing (required)",
                   "the tick (0, 1, ...) at which this [[at]] table's inputs apply, e.g. tick = 0");
  }
  e.tick = static_cast<std::uint64_t>(
      r.integer_node(*tick, path + ".tick", 0, static_cast<std::int64_t>(max_recording_ticks - 1)));
  e.press = button_list(r, t, "press", path + ".press");
  e.release = button_list(r, t, "release", path + ".release");
  e.pointer = r.vec2(t, "pointer", path + ".pointer");
  e.push = r.vec2(t, "push", path + ".push");
  if (const toml::node* d = t.get("drag")) e.drag = drag_target(r, *d, path + ".drag", bodies);
  body_inputs(r, t, "force", BodyInputKind::force, path + ".force", bodies, e.bodies);
  body_inputs(r, t, "impulse", BodyInputKind::impulse, path + ".impulse", bodies, e.bodies);
  body_inputs(r, t, "velocity", BodyInputKind::velocity, path + ".velocity", bodies, e.bodies);
  if (e.bodies.size() > max_body_inputs) {
    r.fail(t.source(), path,
           fmt::format("{} per-body inputs (force, impulse, velocity) in one tick; at most {}",
                       e.bodies.size(), max_body_inputs));
  }
  return e;
}

}  // namespace

std::span<const std::pair<std::string_view, std::uint32_t>> button_names() {
  return buttons;
}

InputScript parse_input_script(std::string_view text, const std::string& source_name,
                               std::span<const BodyDef> bodies) {
  const IeeeFloatMode ieee;  // numbers read by strtod, which rounds in the current mode
  InputScript script;
  script.file = source_name;
  Reader r(script.file);
  const toml::table doc =
      scene_detail::parse_toml(text, source_name, max_script_bytes, script_file);
  if (!doc.get("at") && (doc.get("world") || doc.get("body"))) {
    // Without this, a scene given as the script would run with no input and two warnings.
    const toml::node* n = doc.get("world") ? doc.get("world") : doc.get("body");
    r.fail(n->source(), "",
           "this is a scene file, not an input script: a script holds [[at]] tables (tick, "
           "press, release, pointer, push, drag, force, impulse, velocity); see docs/CLI.md, Input "
           "scripts");
  }
  r.check_keys(doc, "", {"at"});
  if (const toml::array* list = r.tables(doc, "at")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table& t = *list->get(i)->as_table();
      ScriptEvent e = parse_event(r, t, i, bodies);
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

InputScript load_input_script(const std::filesystem::path& file, std::span<const BodyDef> bodies) {
  return parse_input_script(scene_detail::read_text_file(file, max_script_bytes, script_file),
                            file.string(), bodies);
}

TickInput ScriptPlayer::next() {
  if (event_ < script_.events.size() && script_.events[event_].tick == tick_) {
    const ScriptEvent& e = script_.events[event_++];
    if (e.press) sampler_.press(e.press);
    if (e.release) sampler_.release(e.release);
    if (e.pointer) sampler_.set_pointer(*e.pointer);
    if (e.push) sampler_.set_push(*e.push);
    if (e.drag) sampler_.set_drag_body(*e.drag);
    for (const BodyInput& b : e.bodies) {
      switch (b.kind) {
        case BodyInputKind::force:
          sampler_.apply_force(b.body, b.value);
          break;
        case BodyInputKind::impulse:
          sampler_.apply_impulse(b.body, b.value);
          break;
        case BodyInputKind::velocity:
          sampler_.set_velocity(b.body, b.value);
          break;
        case BodyInputKind::torque:
          sampler_.apply_torque(b.body, b.value.x);
          break;
        case BodyInputKind::angular_impulse:
          sampler_.apply_angular_impulse(b.body, b.value.x);
          break;
        case BodyInputKind::angular_velocity:
          sampler_.set_angular_velocity(b.body, b.value.x);
          break;
        case BodyInputKind::target_angle:
          sampler_.set_target_angle(b.body, b.value.x);
          break;
      }
    }
  }
  return sampler_.sample(tick_++);
}

std::vector<TickInput> script_inputs(const InputScript& script, std::uint64_t ticks) {
  ScriptPlayer player(script);
  std::vector<TickInput> out;
  out.reserve(ticks);
  for (std::uint64_t t = 0; t < ticks; ++t) out.push_back(player.next());
  return out;
}

}  // namespace fixstep
