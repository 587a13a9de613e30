// Writing a WorldDef as a scene file (scene_writer.hpp): every body a [[body]] table, every link
// a [[spring]], every segment a [[segment]] (naming the body that carries it), every joint a
// [[joint]], every number the shortest text that reads back as the same double; the text is
// parsed back and its definition hash (and joints) compared before it is handed out.
#include "fixstep/scene/scene_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/file_write.hpp"
#include "fixstep/scene/scene.hpp"
#include "scene_reader.hpp"
#include "scene_values.hpp"

namespace fixstep {

namespace {

[[noreturn]] void refuse(const std::string& where, const std::string& why) {
  throw std::invalid_argument(fmt::format("format_scene: {}: {}", where, why));
}

using scene_detail::toml_filter_bits;
using scene_detail::toml_number;
using scene_detail::toml_point;
using scene_detail::toml_string;

std::string color_text(Rgba8 c) {
  return scene_detail::toml_color(c);
}

using fixstep::same_bits;  // of doubles (fixstep/core/bits.hpp); of points:
bool same_bits(Vec2 a, Vec2 b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y);
}

/// Every body's name in the file, unique: a non-empty name at its first use as it is, else
/// "body<i>" (empty) or the name with "~2", "~3", ... (the first not taken).
std::vector<std::string> unique_names(const std::vector<BodyDef>& bodies) {
  std::unordered_set<std::string> taken;
  std::vector<bool> keep(bodies.size(), false);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    keep[i] = !bodies[i].name.empty() && taken.insert(bodies[i].name).second;
  }
  std::vector<std::string> names(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (keep[i]) {
      names[i] = bodies[i].name;
      continue;
    }
    const std::string base = bodies[i].name.empty() ? fmt::format("body{}", i) : bodies[i].name;
    names[i] = base;
    for (int k = 2; !taken.insert(names[i]).second; ++k) names[i] = fmt::format("{}~{}", base, k);
  }
  return names;
}

/// A static or kinematic body must hold only what the loader gives such a body, as all of it
/// enters the definition hash.
void check_immovable(const BodyDef& b, const std::string& who) {
  if (b.type == BodyType::dynamic) return;
  const std::string kind = body_type_name(b.type);
  if (!same_bits(b.body.mass, 1.0)) {
    refuse(who, fmt::format("the mass of a {} body ({} kg) cannot be written: a scene gives {} "
                            "bodies no mass (they keep the default 1 kg), and the mass enters "
                            "the definition hash; leave body.mass at 1",
                            kind, b.body.mass, kind));
  }
  auto part = [&](bool present, std::string_view what) {
    if (present) {
      refuse(who, fmt::format("a {} body's {} cannot be written: the loader drops it (it would "
                              "move the body); remove it",
                              kind, what));
    }
  };
  part(b.spring.has_value(), "spring");
  part(b.constant_force.has_value(), "constant force");
  part(b.gravity.has_value(), "gravity");
  part(b.drag.has_value(), "drag");
  const Vec2 v = b.body.velocity;
  if (b.type == BodyType::static_body && (v.x != 0.0 || v.y != 0.0)) {
    refuse(who, fmt::format("a static body's velocity ({}, {}) m/s cannot be written: the loader "
                            "sets it to zero; make the body kinematic or give it none",
                            v.x, v.y));
  }
}

/// The plane's normal as parse_plane normalises it.
Vec2 unit(Vec2 n) {
  const double len = det::hypot(n.x, n.y);
  return Vec2{n.x / len, n.y / len};
}

/// A normal to write for `n` that the loader's normalisation turns into n bit for bit: n itself
/// when it is a fixed point (axis-aligned unit normals are), else one within 2 ulps of it.
Vec2 written_normal(Vec2 n, std::size_t i) {
  if (!std::isfinite(n.x) || !std::isfinite(n.y) || !(det::hypot(n.x, n.y) > 0.0)) {
    return n;  // the loader refuses it, with its message
  }
  if (same_bits(unit(n), n)) return n;
  auto nudge = [](double v, int ulps) {
    for (; ulps > 0; --ulps) v = std::nextafter(v, INFINITY);
    for (; ulps < 0; ++ulps) v = std::nextafter(v, -INFINITY);
    return v;
  };
  for (int a = -2; a <= 2; ++a) {
    for (int b = -2; b <= 2; ++b) {
      const Vec2 c{nudge(n.x, a), nudge(n.y, b)};
      if (same_bits(unit(c), n)) return c;
    }
  }
  const Vec2 u = unit(n);
  refuse(fmt::format("plane[{}].normal", i),
         fmt::format("({}, {}) cannot be written: a scene's normals are normalised when read "
                     "(n/|n| = ({}, {})), which would change the definition hash; give the "
                     "plane a unit normal (axis-aligned ones are always kept)",
                     n.x, n.y, u.x, u.y));
}

void write_world(std::string& out, const WorldDef& def) {
  const WorldSettings& s = def.settings;
  auto it = std::back_inserter(out);
  fmt::format_to(it, "[world]\ndt = {}\nintegrator = \"{}\"\nprecision = \"{}\"\nsubsteps = {}\n",
                 toml_number(s.dt), integrator_name(s.integrator), precision_name(def.precision),
                 s.substeps);
  if (!s.flush_denormals) out += "flush_denormals = false\n";
  if (def.allow_unstable) out += "allow_unstable = true\n";
  if (s.seed > std::uint64_t{std::numeric_limits<std::int64_t>::max()}) {
    throw std::invalid_argument(fmt::format(
        "world.seed: {} is above 2^63 - 1, the largest TOML integer; a scene file cannot hold it",
        s.seed));
  }
  if (s.seed != 0) fmt::format_to(it, "seed = {}\n", s.seed);
  if (s.damping_split != DampingSplit::per_stage) {
    out += fmt::format("damping_split = \"{}\"\n", damping_split_name(s.damping_split));
  }
  if (s.contacts) {
    const ContactSettings& c = *s.contacts;
    fmt::format_to(it, "\n[contacts]\nrestitution = {}\nfriction = {}\n",
                   toml_number(c.restitution), toml_number(c.friction));
    if (!same_bits(c.restitution_threshold, ContactSettings::default_restitution_threshold)) {
      fmt::format_to(it, "restitution_threshold = {}\n", toml_number(c.restitution_threshold));
    }
    if (c.velocity_iterations != ContactSettings::default_velocity_iterations) {
      fmt::format_to(it, "velocity_iterations = {}\n", c.velocity_iterations);
    }
    if (c.position_iterations != ContactSettings::default_position_iterations) {
      fmt::format_to(it, "position_iterations = {}\n", c.position_iterations);
    }
    if (c.rolling) out += "rolling = true\n";
    if (c.sleep) {  // sleep_speed and sleep_time act (and are hashed) only with sleep on
      out += "sleep = true\n";
      if (!same_bits(c.sleep_speed, ContactSettings::default_sleep_speed)) {
        fmt::format_to(it, "sleep_speed = {}\n", toml_number(c.sleep_speed));
      }
      if (!same_bits(c.sleep_time, ContactSettings::default_sleep_time)) {
        fmt::format_to(it, "sleep_time = {}\n", toml_number(c.sleep_time));
      }
    }
  }
}

/// The disc and drawing keys: radius (the collider's), its contact keys, then draw_radius
/// when the drawn radius is not the one the loader would give, and color.
void write_looks(std::string& out, const BodyDef& b) {
  auto it = std::back_inserter(out);
  if (const std::optional<Collider>& c = b.collider) {
    fmt::format_to(it, "radius = {}\n", toml_number(c->radius));
    if (!c->collide) out += "collide = false\n";
    if (c->restitution) fmt::format_to(it, "restitution = {}\n", toml_number(*c->restitution));
    if (c->friction) fmt::format_to(it, "friction = {}\n", toml_number(*c->friction));
    if (c->sensor) out += "sensor = true\n";
    const CollisionFilter f = c->filter, none{};
    if (f.category != none.category)
      fmt::format_to(it, "category = {}\n", toml_filter_bits(f.category));
    if (f.mask != none.mask) fmt::format_to(it, "mask = {}\n", toml_filter_bits(f.mask));
    if (f.group != none.group) fmt::format_to(it, "group = {}\n", f.group);
    if (c->inertia) fmt::format_to(it, "inertia = {}\n", toml_number(*c->inertia));
  }
  if (const std::optional<Appearance>& a = b.appearance) {
    const double drawn = b.collider ? b.collider->radius : Appearance{}.radius;
    if (!same_bits(a->radius, drawn))
      fmt::format_to(it, "draw_radius = {}\n", toml_number(a->radius));
    fmt::format_to(it, "color = {}\n", color_text(a->color));
    if (!a->visible) out += "visible = false\n";
    if (!a->trail) out += "trail = false\n";
    if (!same_bits(a->trail_time, default_trail_time)) {
      fmt::format_to(it, "trail_time = {}\n", toml_number(a->trail_time));
    }
    if (!a->sprite.empty()) fmt::format_to(it, "sprite = {}\n", toml_string(a->sprite));
    if (!a->sprite.empty() && a->sprite_size.x > 0.0 && a->sprite_size.y > 0.0) {
      fmt::format_to(it, "sprite_size = {}\n", toml_point(a->sprite_size));
    }
  }
}

void write_body(std::string& out, const BodyDef& b, const std::string& name) {
  auto it = std::back_inserter(out);
  fmt::format_to(it, "\n[[body]]\nname = {}\n", toml_string(name));
  if (b.type != BodyType::dynamic) fmt::format_to(it, "type = \"{}\"\n", body_type_name(b.type));
  if (b.type == BodyType::dynamic) fmt::format_to(it, "mass = {}\n", toml_number(b.body.mass));
  fmt::format_to(it, "position = {}\n", toml_point(b.body.position));
  if (!same_bits(b.body.velocity, Vec2{})) {
    fmt::format_to(it, "velocity = {}\n", toml_point(b.body.velocity));
  }
  if (b.body.angle != 0.0) fmt::format_to(it, "angle = {}\n", toml_number(b.body.angle));
  if (b.body.angular_velocity != 0.0) {
    fmt::format_to(it, "angular_velocity = {}\n", toml_number(b.body.angular_velocity));
  }
  if (const std::optional<SpringDamper>& s = b.spring) {
    fmt::format_to(it,
                   "spring = {{ anchor = {}, stiffness = {}, damping = {}, rest_length = {} }}\n",
                   toml_point(s->anchor), toml_number(s->stiffness), toml_number(s->damping),
                   toml_number(s->rest_length));
  }
  if (b.constant_force) fmt::format_to(it, "force = {}\n", toml_point(b.constant_force->force));
  if (b.gravity) fmt::format_to(it, "gravity = {}\n", toml_point(b.gravity->acceleration));
  if (b.drag) fmt::format_to(it, "drag = {}\n", toml_number(b.drag->coefficient));
  write_looks(out, b);
  out += scene_detail::mover_text(b);
  out += scene_detail::shapes_text(b);  // last: [[body.shape]] tables end the body's keys
}

/// "body[i]" for the handle WorldDef::add_body gives its i-th body, else "body S:G" (slot and
/// generation, 1-based slot as in recordings).
std::string body_label(Entity e) {
  if (!e.is_null() && e.generation == 1) return fmt::format("body[{}]", e.slot());
  return fmt::format("body {}:{}", e.index1, e.generation);
}

void write_links(std::string& out, const WorldDef& def, const std::vector<std::string>& names) {
  auto it = std::back_inserter(out);
  for (std::size_t i = 0; i < def.links.size(); ++i) {
    const LinkDef& d = def.links[i];
    const auto a = fixstep::defined_index(d.body_a, names.size());
    const auto b = fixstep::defined_index(d.body_b, names.size());
    if (!a || !b || *a == *b) {
      refuse(fmt::format("link[{}]", i),
             fmt::format("joins {} and {}: each must be one of the {} bodies (a handle "
                         "WorldDef::add_body returned), and they must differ",
                         body_label(d.body_a), body_label(d.body_b), names.size()));
    }
    const fixstep::IndexLink l{*a, *b, d.spring};
    fmt::format_to(it,
                   "\n[[spring]]\nbodies = [{}, {}]\nstiffness = {}\ndamping = {}\nrest_length = "
                   "{}\n",
                   toml_string(names[l.body_a]), toml_string(names[l.body_b]),
                   toml_number(l.spring.stiffness), toml_number(l.spring.damping),
                   toml_number(l.spring.rest_length));
  }
}

void write_planes(std::string& out, const WorldDef& def) {
  auto it = std::back_inserter(out);
  for (std::size_t i = 0; i < def.planes.size(); ++i) {
    const PlaneDef& p = def.planes[i];
    fmt::format_to(it, "\n[[plane]]\nnormal = {}\noffset = {}\nrestitution = {}\nfriction = {}\n",
                   toml_point(written_normal(p.normal, i)), toml_number(p.offset),
                   toml_number(p.restitution), toml_number(p.friction));
  }
}

/// Every segment a [[segment]] table, polylines' ghost vertices as prev and next, one_way when
/// true, and the kinematic body carrying it (each segment of a carried polyline) as `body`, by
/// its name.
void write_segments(std::string& out, const WorldDef& def, const std::vector<std::string>& names) {
  auto it = std::back_inserter(out);
  for (std::size_t i = 0; i < def.segments.size(); ++i) {
    const SegmentDef& s = def.segments[i];
    fmt::format_to(it, "\n[[segment]]\na = {}\nb = {}\nrestitution = {}\nfriction = {}\n",
                   toml_point(s.a), toml_point(s.b), toml_number(s.restitution),
                   toml_number(s.friction));
    if (s.prev) fmt::format_to(it, "prev = {}\n", toml_point(*s.prev));
    if (s.next) fmt::format_to(it, "next = {}\n", toml_point(*s.next));
    if (s.color != Rgba8{0, 0, 0, 0}) fmt::format_to(it, "color = {}\n", color_text(s.color));
    if (!same_bits(s.width, 0.0)) fmt::format_to(it, "width = {}\n", toml_number(s.width));
    if (s.one_way) out += "one_way = true\n";
    if (s.body.is_null()) continue;
    const auto b = fixstep::defined_index(s.body, names.size());
    if (!b) {
      refuse(fmt::format("segment[{}]", i),
             fmt::format("is carried by {}: it must be one of the {} bodies (a handle "
                         "WorldDef::add_body returned)",
                         body_label(s.body), names.size()));
    }
    if (def.bodies[*b].type != BodyType::kinematic) {
      refuse(fmt::format("segment[{}]", i),
             fmt::format("is carried by body[{}] {}, a {} body: only a kinematic body can carry "
                         "segments",
                         *b, toml_string(names[*b]), body_type_name(def.bodies[*b].type)));
    }
    fmt::format_to(it, "body = {}\n", toml_string(names[*b]));
  }
}

/// def's joints as the loader gives them back: a distance joint's anchor_b equal to its anchor
/// (bit for bit) unset, as unset means the anchor.
std::vector<JointDef> reloaded_joints(const WorldDef& def) {
  std::vector<JointDef> joints = def.joints;
  for (JointDef& j : joints) {
    if (j.type == JointType::distance && j.anchor_b && same_bits(*j.anchor_b, j.anchor)) {
      j.anchor_b.reset();
    }
  }
  return joints;
}

/// The text must load (else the loader's message) and give def's definition hash and joints.
void check_reloads(const std::string& text, const WorldDef& def) {
  WorldDef back;
  try {
    back = parse_scene(text, "<scene text>").def;
  } catch (const SceneError& e) {
    throw std::invalid_argument(fmt::format(
        "format_scene: the world does not load back from its scene text: {}", e.what()));
  }
  const std::uint64_t want = definition_hash(def), got = definition_hash(back);
  if (got != want) {
    throw std::logic_error(fmt::format(
        "format_scene: the scene text loads back with definition hash {:016x}, not the world's "
        "{:016x} (a bug of the scene writer)",
        got, want));
  }
  if (back.joints != reloaded_joints(def)) {
    throw std::logic_error(
        "format_scene: the scene text loads back with other joints than the world's (a bug of "
        "the scene writer)");
  }
}

}  // namespace

std::string format_scene(const WorldDef& def) {
  std::string out =
      "# Written by fixstep::write_scene: every body a [[body]] table, every link a [[spring]].\n";
  write_world(out, def);
  const std::vector<std::string> names = unique_names(def.bodies);
  for (std::size_t i = 0; i < def.bodies.size(); ++i) {
    check_immovable(def.bodies[i], fmt::format("body[{}] {}", i, toml_string(names[i])));
    write_body(out, def.bodies[i], names[i]);
  }
  write_links(out, def, names);
  write_planes(out, def);
  write_segments(out, def, names);
  out += scene_detail::joints_text(def, names);
  if (out.size() > max_scene_bytes) {
    refuse("the world",
           fmt::format("its scene would be {} bytes, more than the {} a scene file may have ({} "
                       "bodies, {} links, {} planes, {} joints)",
                       out.size(), max_scene_bytes, def.bodies.size(), def.links.size(),
                       def.planes.size(), def.joints.size()));
  }
  check_reloads(out, def);
  return out;
}

void write_scene(const std::filesystem::path& file, const WorldDef& def) {
  write_file_atomically(file, format_scene(def));
}

std::string write_scene_beside(const std::filesystem::path& recording_file, const WorldDef& def) {
  std::filesystem::path scene = recording_file;
  scene.replace_extension(".scene.toml");
  write_scene(scene, def);
  return scene.filename().string();
}

}  // namespace fixstep
