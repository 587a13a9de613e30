// Scene files, part two: springs between bodies ([[spring]]) and the frequency form of
// springs. See README "Scene format".
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

/// The unordered pair {a, b} as one key.
std::uint64_t pair_key(std::size_t a, std::size_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
}

/// Where link l came from, for a warning: "spring[2] (line 14)".
std::string link_origin(const Scene& scene, std::size_t l) {
  const std::string key = l < scene.source.link_keys.size() && !scene.source.link_keys[l].empty()
                              ? scene.source.link_keys[l]
                              : fmt::format("link[{}]", l);
  const std::size_t line = l < scene.source.link_lines.size() ? scene.source.link_lines[l] : 0;
  return line ? fmt::format("{} (line {})", key, line) : key;
}

}  // namespace

std::size_t find_body(const Reader& r, const toml::node& e, const std::string& key,
                      const BodyNames& names) {
  if (!e.is_string()) {
    r.fail(e.source(), key, fmt::format("expected a body name (a string), found {}", found(e)));
  }
  const std::string name(e.as_string()->get());
  if (const auto it = names.index.find(name); it != names.index.end()) return it->second;
  std::vector<std::string> candidates;
  candidates.reserve(names.index.size());
  for (const auto& [n, i] : names.index) candidates.push_back(n);
  std::sort(candidates.begin(), candidates.end());  // ties: the first in name order
  std::string hint;
  if (const auto best = closest(name, candidates))
    hint = fmt::format("did you mean \"{}\"?", *best);
  for (const auto& [prefix, text] : names.generators) {
    if (name.rfind(prefix + "[", 0) == 0) hint += (hint.empty() ? "" : " ") + text;
  }
  r.fail(e.source(), key,
         fmt::format("no body named \"{}\"{}", name, hint.empty() ? "" : " (" + hint + ")"));
}

SpringSpec parse_spring_spec(const Reader& r, const toml::table& t, const std::string& path,
                             bool with_rest_length) {
  SpringSpec s;
  s.path = path;
  const toml::node* k = t.get("stiffness");
  const toml::node* b = t.get("damping");
  const toml::node* f = t.get("frequency");
  const toml::node* z = t.get("damping_ratio");
  if ((k || b) && (f || z)) {
    const std::string direct = k ? "stiffness" : "damping",
                      modal = f ? "frequency" : "damping_ratio";
    r.fail((f ? f : z)->source(), path + "." + modal,
           fmt::format("`{}` and `{}` both given: a spring takes stiffness and damping (N/m, "
                       "N*s/m) or frequency and damping_ratio (Hz, dimensionless), not both",
                       direct, modal));
  }
  if (f || z) {
    s.by_frequency = true;
    if (!f) {
      r.fail_missing(t, path, {"frequency"}, "missing (required with damping_ratio)",
                     "the natural frequency in Hz that damping_ratio ζ goes with, e.g. "
                     "frequency = 2.0; or give stiffness and damping instead");
    }
    s.frequency_node = f;
    s.frequency = r.number_node(*f, path + ".frequency");
    r.require(s.frequency > 0.0, t, "frequency", path + ".frequency", "> 0 Hz", s.frequency);
    if (z) {
      s.damping_ratio = r.number_node(*z, path + ".damping_ratio");
      r.require(s.damping_ratio >= 0.0, t, "damping_ratio", path + ".damping_ratio", ">= 0",
                s.damping_ratio);
    }
  } else {
    if (!k) {
      r.fail_missing(t, path, {"stiffness", "frequency"},
                     "missing (required): give stiffness (N/m) or frequency (Hz)");
    }
    s.stiffness = r.number_node(*k, path + ".stiffness");
    r.require(s.stiffness >= 0.0, t, "stiffness", path + ".stiffness", ">= 0 N/m", s.stiffness);
    if (b) {
      s.damping = r.number_node(*b, path + ".damping");
      r.require(s.damping >= 0.0, t, "damping", path + ".damping", ">= 0 N*s/m", s.damping);
    }
  }
  if (with_rest_length) {
    if (auto l = r.number(t, "rest_length", path + ".rest_length")) {
      r.require(*l >= 0.0, t, "rest_length", path + ".rest_length", ">= 0 m", *l);
      r.require_state(t, "rest_length", path + ".rest_length", *l, "m");
      s.rest_length = *l;
    }
  }
  return s;
}

LinkSpring resolve_spring(const Reader& r, const SpringSpec& spec, double mass, double rest,
                          Precision precision) {
  LinkSpring out{spec.stiffness, spec.damping, spec.rest_length.value_or(rest)};
  if (!spec.by_frequency) return out;
  const std::string key = spec.path + ".frequency";
  try {
    const LinkSpring k = spring_from_frequency(spec.frequency, spec.damping_ratio, mass);
    out.stiffness = k.stiffness;
    out.damping = k.damping;
  } catch (const std::invalid_argument& e) {
    r.fail(spec.frequency_node->source(), key,
           fmt::format("cannot be converted with mass {:g} kg: {}", mass, e.what()));
  }
  const bool fits =
      representable(out.stiffness, precision) && representable(out.damping, precision);
  if (!fits || !within_coefficient(out.stiffness) || !within_coefficient(out.damping)) {
    r.fail(spec.frequency_node->source(), key,
           fmt::format("gives k = m (2πf)² = {:g} N/m and b = 2 m ζ (2πf) = {:g} N*s/m with "
                       "m = {:g} kg, beyond {}; use a lower frequency{}",
                       out.stiffness, out.damping, mass,
                       fits ? std::string("1e100, the largest coefficient a step holds")
                            : fmt::format("the range of {}", precision_text(precision)),
                       precision == Precision::f32 ? " or precision = \"f64\" in [world]" : ""));
  }
  return out;
}

void parse_springs(Reader& r, const toml::table& doc, Scene& scene, const BodyNames& names) {
  const toml::array* list = r.tables(doc, "spring");
  if (!list) return;
  if (scene.def.links.size() + list->size() > max_scene_links) {
    r.fail(doc.get("spring")->source(), "spring",
           fmt::format("the scene would have {} links; at most {} are allowed",
                       scene.def.links.size() + list->size(), max_scene_links));
  }
  // The first link of each pair of bodies (generated links included, in either order): a second
  // one is allowed, as the forces of both add, but is most likely a mistake.
  std::unordered_map<std::uint64_t, std::size_t> first_link;
  for (std::size_t l = 0; l < scene.def.links.size(); ++l) {
    first_link.emplace(pair_key(scene.def.links[l].body_a.slot(), scene.def.links[l].body_b.slot()),
                       l);
  }
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table& t = *list->get(i)->as_table();
    const std::string path = fmt::format("spring[{}]", i);
    r.check_keys(t, path,
                 {"bodies", "stiffness", "damping", "rest_length", "frequency", "damping_ratio"});
    const toml::node* n = t.get("bodies");
    if (!n) {
      r.fail_missing(t, path, {"bodies"}, "missing (required)",
                     "the names of the two bodies, e.g. bodies = [\"a\", \"b\"]");
    }
    const toml::array* pair = n->as_array();
    if (!pair || pair->size() != 2) {
      r.fail(n->source(), path + ".bodies",
             pair ? fmt::format("expected [\"a\", \"b\"] (2 body names), found {}",
                                elements(pair->size()))
                  : fmt::format("expected [\"a\", \"b\"] (2 body names), found {}", found(*n)));
    }
    const std::size_t a = find_body(r, *pair->get(0), path + ".bodies[0]", names);
    const std::size_t b = find_body(r, *pair->get(1), path + ".bodies[1]", names);
    const BodyDef &da = scene.def.bodies[a], &db = scene.def.bodies[b];
    if (a == b) {
      r.fail(pair->get(1)->source(), path + ".bodies[1]",
             fmt::format("\"{}\" twice: a spring joins two different bodies", da.name));
    }
    const SpringSpec spec = parse_spring_spec(r, t, path, true);
    // The frequency form acts on the pair's reduced mass m_a m_b / (m_a + m_b), on the dynamic
    // body's mass alone when the other end is static or kinematic (an immovable anchor).
    const bool move_a = da.type == BodyType::dynamic, move_b = db.type == BodyType::dynamic;
    if (!move_a && !move_b) {
      r.warn(n->source(), path + ".bodies",
             fmt::format("does nothing: \"{}\" ({}) and \"{}\" ({}) are both immovable", da.name,
                         body_type_name(da.type), db.name, body_type_name(db.type)));
    }
    const double mass = move_a && move_b ? reduced_mass(da.body.mass, db.body.mass)
                        : move_a         ? da.body.mass
                                         : db.body.mass;
    const LinkSpring spring = resolve_spring(r, spec, mass, 0.0, scene.def.precision);
    if (spring.rest_length > 0.0 &&
        same_point(da.body.position, db.body.position, scene.def.precision)) {
      r.fail(t.get("rest_length")->source(), path + ".rest_length",
             fmt::format("\"{}\" and \"{}\" both start at ({:g}, {:g}) m, so the direction of a "
                         "spring with rest length {:g} m is undefined; move one of them or use "
                         "rest_length = 0",
                         da.name, db.name, da.body.position.x, da.body.position.y,
                         spring.rest_length));
    }
    if (const auto [it, fresh] = first_link.emplace(pair_key(a, b), scene.def.links.size());
        !fresh) {
      r.warn(n->source(), path + ".bodies",
             fmt::format("\"{}\" and \"{}\" are already joined by {}: both links act (their "
                         "forces add); remove one, or merge them into one spring",
                         da.name, db.name, link_origin(scene, it->second)));
    }
    scene.def.links.push_back(
        LinkDef{fixstep::defined_entity(a), fixstep::defined_entity(b), spring});
    scene.source.link_lines.push_back(t.source().begin.line);
    scene.source.link_keys.push_back(path);
  }
}

}  // namespace fixstep::scene_detail
