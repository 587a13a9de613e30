// Scene files: joints ([[joint]]: revolute, prismatic, weld, distance, wheel and motor joints
// between two bodies with shapes, or a body and the world) into WorldDef::joints, each key the
// type does not use refused at the key; and their text for write_scene, every number the
// shortest that reads back as the same double. See docs/SCENES.md, "Joints".
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "scene_reader.hpp"
#include "scene_values.hpp"

namespace fixstep::scene_detail {

namespace {

constexpr std::array<JointType, 6> joint_types{JointType::revolute, JointType::prismatic,
                                               JointType::weld,     JointType::distance,
                                               JointType::wheel,    JointType::motor};

/// The keys every joint table may have.
constexpr std::array<std::string_view, 7> joint_common_keys{
    "type", "name", "body_a", "body_b", "break_force", "break_torque", "collide_connected"};

/// The keys of a `type` joint beyond the common ones (joint.hpp: which fields each type uses).
std::span<const std::string_view> joint_type_keys(JointType type) {
  static constexpr std::array<std::string_view, 8> revolute{
      "anchor",           "lower",     "upper",         "motor_speed",
      "max_motor_torque", "frequency", "damping_ratio", "target"};
  static constexpr std::array<std::string_view, 9> prismatic{
      "anchor",          "axis",      "lower",         "upper", "motor_speed",
      "max_motor_force", "frequency", "damping_ratio", "target"};
  static constexpr std::array<std::string_view, 3> weld{"anchor", "frequency", "damping_ratio"};
  static constexpr std::array<std::string_view, 7> distance{
      "anchor", "anchor_b", "length", "lower", "upper", "frequency", "damping_ratio"};
  static constexpr std::array<std::string_view, 9> wheel{
      "anchor",           "axis",      "lower",         "upper", "motor_speed",
      "max_motor_torque", "frequency", "damping_ratio", "target"};
  static constexpr std::array<std::string_view, 2> motor{"max_motor_force", "max_motor_torque"};
  switch (type) {
    case JointType::revolute:
      return revolute;
    case JointType::prismatic:
      return prismatic;
    case JointType::weld:
      return weld;
    case JointType::distance:
      return distance;
    case JointType::wheel:
      return wheel;
    case JointType::motor:
      return motor;
  }
  return {};
}

bool has_key(std::span<const std::string_view> keys, std::string_view k) {
  return std::find(keys.begin(), keys.end(), k) != keys.end();
}

/// "revolute, prismatic, weld, distance, wheel, motor".
std::string joint_type_names() {
  std::string out;
  for (const JointType j : joint_types)
    out += (out.empty() ? "" : ", ") + std::string(joint_type_name(j));
  return out;
}

/// t.type: required, one of the six names; an unknown one is refused with the closest name (or
/// the type another engine's word means: a hinge is a revolute joint).
JointType parse_joint_type(const Reader& r, const toml::table& t, const std::string& path) {
  const toml::node* n = t.get("type");
  if (!n) {
    r.fail_missing(t, path, {"type"}, "missing (required)",
                   fmt::format("what the joint holds: one of {}, e.g. type = \"revolute\"",
                               joint_type_names()));
  }
  const std::string name = *r.string(t, "type", path + ".type");
  std::vector<std::string> valid;
  for (const JointType j : joint_types) {
    if (name == joint_type_name(j)) return j;
    valid.emplace_back(joint_type_name(j));
  }
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 6> words{
      {{"hinge", "revolute"},
       {"pin", "revolute"},
       {"slider", "prismatic"},
       {"fixed", "weld"},
       {"rope", "distance"},
       {"spring", "distance"}}};
  std::optional<std::string> best = closest(name, valid);
  for (const auto& [word, type] : words) {
    if (!best && name == word) best = std::string(type);
  }
  r.fail(n->source(), path + ".type",
         fmt::format("unknown joint type \"{}\"{} (valid: {})", name,
                     best ? fmt::format("; did you mean \"{}\"?", *best) : std::string(),
                     joint_type_names()));
}

/// Refuses a joint key the type does not use (naming the types that do), and warns about keys
/// no joint has (with the closest key of this type).
void check_joint_keys(Reader& r, const toml::table& t, const std::string& path, JointType type) {
  const std::span<const std::string_view> own = joint_type_keys(type);
  std::vector<std::string> candidates(joint_common_keys.begin(), joint_common_keys.end());
  candidates.insert(candidates.end(), own.begin(), own.end());
  for (auto&& [key, node] : t) {
    const std::string_view k = key.str();
    if (has_key(joint_common_keys, k) || has_key(own, k)) continue;
    std::string users;
    for (const JointType j : joint_types) {
      if (has_key(joint_type_keys(j), k)) {
        users += (users.empty() ? "" : ", ") + std::string(joint_type_name(j));
      }
    }
    const std::string full = path + "." + std::string(k);
    if (!users.empty()) {
      std::string keys;
      for (const std::string_view o : own) keys += (keys.empty() ? "" : ", ") + std::string(o);
      r.fail(key.source(), full,
             fmt::format("a {} joint does not use `{}` (a key of {} joints); its keys are {}; "
                         "remove it",
                         joint_type_name(type), k, users, keys));
    }
    const std::optional<std::string> best = closest(k, candidates);
    r.warn(key.source(), full,
           fmt::format("unknown key ignored{}",
                       best ? fmt::format(" (did you mean `{}`?)", *best) : std::string()));
  }
}

/// t[key] (body_a or body_b): the index of the body it names, nullopt (the world) when absent.
/// Refused at the key: not a string, no body of that name (find_body), a body without shapes.
std::optional<std::size_t> joint_body(const Reader& r, const toml::table& t,
                                      const std::string& path, std::string_view key,
                                      const Scene& scene, const BodyNames& names) {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  const std::string k = path + "." + std::string(key);
  const std::size_t i = find_body(r, *n, k, names);
  const BodyDef& b = scene.def.bodies[i];
  if (b.shapes.empty()) {
    r.fail(n->source(), k,
           fmt::format("\"{}\" (line {}) has no shapes{}: a joint joins bodies with shapes; give "
                       "it shape = {{ ... }} (see Shapes), or leave `{}` out to join the world",
                       b.name, scene.source.body_lines[i],
                       b.collider ? " (a disc's radius is not one)" : "", key));
  }
  return i;
}

/// An optional number at t[key] that must satisfy ok (`allowed`, e.g. ">= 0 N").
std::optional<double> joint_number(const Reader& r, const toml::table& t, const std::string& path,
                                   std::string_view key, bool (*ok)(double),
                                   std::string_view allowed) {
  const std::string k = path + "." + std::string(key);
  const std::optional<double> v = r.number(t, key, k);
  if (v && ok) r.require(ok(*v), t, key, k, allowed, *v);
  return v;
}

bool non_negative(double v) {
  return v >= 0.0;
}

/// A point [x, y] (m) at t[key] within max_state_magnitude of the origin; nullopt when absent.
std::optional<Vec2> joint_point(const Reader& r, const toml::table& t, const std::string& path,
                                std::string_view key) {
  const std::string k = path + "." + std::string(key);
  const std::optional<Vec2> p = r.vec2(t, key, k);
  if (p) r.require_state(t, key, k, *p, "m");
  return p;
}

/// lower and upper into j: revolute within [-π, π] rad, distance >= 0 m, otherwise within the
/// state range (m); lower <= upper.
void parse_limits(const Reader& r, const toml::table& t, const std::string& path, JointDef& j) {
  for (const std::string_view key : {"lower", "upper"}) {
    const std::string k = path + "." + std::string(key);
    std::optional<double> v = r.number(t, key, k);
    if (!v) continue;
    if (j.type == JointType::revolute) {
      r.require(*v >= -std::numbers::pi && *v <= std::numbers::pi, t, key, k,
                "within [-π, π] rad (the relative angle, wrapped)", *v);
    } else if (j.type == JointType::distance) {
      r.require(*v >= 0.0, t, key, k, ">= 0 m (a distance)", *v);
      r.require_state(t, key, k, *v, "m");
    } else {
      r.require_state(t, key, k, *v, "m");
    }
    (key == "lower" ? j.lower : j.upper) = v;
  }
  if (j.lower && j.upper && *j.lower > *j.upper) {
    r.fail(t.get("upper")->source(), path + ".upper",
           fmt::format("is below lower ({:g}): the limits need lower <= upper (got {:g})", *j.lower,
                       *j.upper));
  }
}

/// frequency (Hz, >= 0; a wheel's > 0 and required), damping_ratio (ζ, >= 0; a warning when
/// it does nothing, without frequency) and target into j.
void parse_spring(Reader& r, const toml::table& t, const std::string& path, JointDef& j) {
  if (j.type == JointType::motor) return;
  const std::optional<double> f =
      joint_number(r, t, path, "frequency", non_negative, ">= 0 Hz (0: no spring)");
  if (j.type == JointType::wheel) {
    if (!f) {
      r.fail_missing(t, path, {"frequency"}, "missing (required for a wheel joint)",
                     "the suspension's frequency in Hz, > 0, e.g. frequency = 4.0");
    }
    r.require(*f > 0.0, t, "frequency", path + ".frequency",
              "> 0 Hz for a wheel joint (its suspension is a spring)", *f);
  }
  j.frequency = f.value_or(0.0);
  if (auto z = joint_number(r, t, path, "damping_ratio", non_negative, ">= 0")) {
    j.damping_ratio = *z;
    if (!(j.frequency > 0.0) && *z != 0.0) {
      r.warn(t.get("damping_ratio")->source(), path + ".damping_ratio",
             "does nothing without frequency > 0 (no spring)");
    }
  }
  if (auto v = r.number(t, "target", path + ".target")) j.target = *v;
}

/// A distance joint's ends: anchor (default A's position) and anchor_b (default B's
/// position); where that end is the world, the key is required. anchor_b equal to anchor
/// (bit for bit) is left unset (JointDef: unset is `anchor`).
void parse_distance_ends(const Reader& r, const toml::table& t, const std::string& path,
                         const Scene& scene, std::optional<std::size_t> a,
                         std::optional<std::size_t> b, JointDef& j) {
  auto end = [&](std::string_view key, std::optional<std::size_t> body, std::string_view which) {
    if (auto p = joint_point(r, t, path, key)) return *p;
    if (!body) {
      r.fail_missing(t, path, {key}, "missing (required where that end is the world)",
                     fmt::format("the joint's end on {} (the world), [x, y] in m", which));
    }
    return scene.def.bodies[*body].body.position;
  };
  j.anchor = end("anchor", a, "A");
  const Vec2 end_b = end("anchor_b", b, "B");
  if (!same_bits(end_b.x, j.anchor.x) || !same_bits(end_b.y, j.anchor.y)) j.anchor_b = end_b;
}

/// A rigid distance joint (no spring, no limit) without `length` holds its ends at their
/// distance: refused when they coincide (a length of 0), at the end key given last.
void check_distance_length(const Reader& r, const toml::table& t, const std::string& path,
                           Precision precision, const JointDef& j) {
  const Vec2 end_b = j.anchor_b.value_or(j.anchor);
  if (j.length || j.lower || j.upper || j.frequency > 0.0 ||
      !same_point(j.anchor, end_b, precision)) {
    return;
  }
  const char* key = t.get("anchor_b") ? "anchor_b" : t.get("anchor") ? "anchor" : nullptr;
  r.fail(key ? t.get(key)->source() : t.source(), path + "." + (key ? key : "anchor_b"),
         fmt::format("both ends are at ({:g}, {:g}) m: a rigid distance joint would hold them "
                     "at a length of 0; move one end (anchor, anchor_b: m, default the bodies' "
                     "positions) or give length > 0 m",
                     end_b.x, end_b.y));
}

/// One [[joint]] table.
JointDef parse_joint(Reader& r, const toml::table& t, const std::string& path, const Scene& scene,
                     const BodyNames& names) {
  JointDef j;
  j.type = parse_joint_type(r, t, path);
  check_joint_keys(r, t, path, j.type);
  const std::optional<std::size_t> a = joint_body(r, t, path, "body_a", scene, names);
  const std::optional<std::size_t> b = joint_body(r, t, path, "body_b", scene, names);
  if (!a && !b) {
    r.fail_missing(t, path, {"body_b", "body_a"}, "missing (required): a joint needs a body",
                   "body_a and body_b name the two bodies (with shapes); leave one out to join "
                   "the other to the world, e.g. body_b = \"door\"");
  }
  if (a && b && *a == *b) {
    r.fail(t.get("body_b")->source(), path + ".body_b",
           fmt::format("\"{}\" is also body_a: a joint joins two different bodies (leave one "
                       "out to join the world)",
                       scene.def.bodies[*a].name));
  }
  if (a) j.body_a = fixstep::defined_entity(*a);
  if (b) j.body_b = fixstep::defined_entity(*b);
  auto moves = [&](std::optional<std::size_t> i) {
    return i && scene.def.bodies[*i].type == BodyType::dynamic;
  };
  if (!moves(a) && !moves(b)) {
    const char* key = b ? "body_b" : "body_a";
    auto who = [&](std::optional<std::size_t> i) {
      return i ? fmt::format("\"{}\" ({})", scene.def.bodies[*i].name,
                             body_type_name(scene.def.bodies[*i].type))
               : std::string("the world");
    };
    r.warn(t.get(key)->source(), path + "." + key,
           fmt::format("does nothing: {} and {} are both immovable", who(a), who(b)));
  }
  if (auto name = r.string(t, "name", path + ".name")) j.name = *name;

  j.length = joint_number(
      r, t, path, "length", [](double v) { return v > 0.0; }, "> 0 m");
  if (j.length) r.require_state(t, "length", path + ".length", *j.length, "m");
  if (j.type == JointType::distance) {
    parse_distance_ends(r, t, path, scene, a, b, j);
  } else if (j.type != JointType::motor) {
    const std::optional<Vec2> anchor = joint_point(r, t, path, "anchor");
    j.anchor = anchor ? *anchor : scene.def.bodies[b ? *b : *a].body.position;
  }
  if (auto axis = r.vec2(t, "axis", path + ".axis")) {
    if (axis->x == 0.0 && axis->y == 0.0) {
      r.fail(t.get("axis")->source(), path + ".axis",
             fmt::format("must be a non-zero vector (got [{}, {}]): the direction B moves along",
                         axis->x, axis->y));
    }
    j.axis = *axis;
  }
  parse_limits(r, t, path, j);
  if (auto v = r.number(t, "motor_speed", path + ".motor_speed")) j.motor_speed = *v;
  j.max_motor_torque =
      joint_number(r, t, path, "max_motor_torque", non_negative, ">= 0 N*m (0: no motor)")
          .value_or(0.0);
  j.max_motor_force =
      joint_number(r, t, path, "max_motor_force", non_negative, ">= 0 N (0: no motor)")
          .value_or(0.0);
  parse_spring(r, t, path, j);
  j.break_force = joint_number(r, t, path, "break_force", non_negative, ">= 0 N");
  j.break_torque = joint_number(r, t, path, "break_torque", non_negative, ">= 0 N*m");
  if (auto v = r.boolean(t, "collide_connected", path + ".collide_connected")) {
    j.collide_connected = *v;
  }
  if (j.type == JointType::distance) check_distance_length(r, t, path, scene.def.precision, j);
  return j;
}

}  // namespace

void parse_joints(Reader& r, const toml::table& doc, Scene& scene, const BodyNames& names) {
  const toml::array* list = r.tables(doc, "joint");
  if (!list) return;
  if (list->size() > max_joints) {
    r.fail(doc.get("joint")->source(), "joint",
           fmt::format("the scene has {} joints; at most {} are allowed (max_joints)", list->size(),
                       max_joints));
  }
  scene.def.joints.reserve(list->size());
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table& t = *list->get(i)->as_table();
    scene.def.joints.push_back(parse_joint(r, t, fmt::format("joint[{}]", i), scene, names));
    scene.source.joint_lines.push_back(t.source().begin.line);
  }
}

std::string joints_text(const WorldDef& def, const std::vector<std::string>& names) {
  std::string out;
  auto it = std::back_inserter(out);
  auto point = [&](std::string_view key, Vec2 v) {
    fmt::format_to(it, "{} = {}\n", key, toml_point(v));
  };
  auto number = [&](std::string_view key, double v) {
    fmt::format_to(it, "{} = {}\n", key, toml_number(v));
  };
  for (std::size_t i = 0; i < def.joints.size(); ++i) {
    const JointDef& j = def.joints[i];
    const std::span<const std::string_view> keys = joint_type_keys(j.type);
    fmt::format_to(it, "\n[[joint]]\ntype = \"{}\"\n", joint_type_name(j.type));
    for (const auto& [key, e] : {std::pair{"body_a", j.body_a}, std::pair{"body_b", j.body_b}}) {
      if (e.is_null()) continue;
      const auto b = fixstep::defined_index(e, names.size());
      if (!b) {
        throw std::invalid_argument(fmt::format(
            "format_scene: joint[{}]: {} is body {}:{}: it must be null (the world) or one of "
            "the {} bodies (a handle WorldDef::add_body returned)",
            i, key, e.index1, e.generation, names.size()));
      }
      fmt::format_to(it, "{} = {}\n", key, toml_string(names[*b]));
    }
    if (!j.name.empty()) fmt::format_to(it, "name = {}\n", toml_string(j.name));
    // Every field that is not JointDef's default; the anchor and the axis always where the type
    // uses them (the loader's defaults differ), and a distance joint's end on B (unset: the
    // anchor, which the loader leaves unset again). A field the type does not use is written
    // too, and the loader refuses it at its key.
    if (has_key(keys, "anchor") || !same_bits(j.anchor.x, 0.0) || !same_bits(j.anchor.y, 0.0)) {
      point("anchor", j.anchor);
    }
    if (j.type == JointType::distance || j.anchor_b)
      point("anchor_b", j.anchor_b.value_or(j.anchor));
    if (has_key(keys, "axis") || !same_bits(j.axis.x, 1.0) || !same_bits(j.axis.y, 0.0)) {
      point("axis", j.axis);
    }
    if (j.length) number("length", *j.length);
    if (j.lower) number("lower", *j.lower);
    if (j.upper) number("upper", *j.upper);
    for (const auto& [key, v] :
         {std::pair{"motor_speed", j.motor_speed},
          std::pair{"max_motor_torque", j.max_motor_torque},
          std::pair{"max_motor_force", j.max_motor_force}, std::pair{"frequency", j.frequency},
          std::pair{"damping_ratio", j.damping_ratio}, std::pair{"target", j.target}}) {
      if (!same_bits(v, 0.0)) number(key, v);
    }
    if (j.break_force) number("break_force", *j.break_force);
    if (j.break_torque) number("break_torque", *j.break_torque);
    if (j.collide_connected) out += "collide_connected = true\n";
  }
  return out;
}

}  // namespace fixstep::scene_detail
