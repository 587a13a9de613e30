// Rolling discs in scene files: `[contacts] rolling = true` and the body keys angle (rad),
// angular_velocity (rad/s) and inertia (kg·m²), which act only when it is on.
#include <fmt/format.h>

#include <string>
#include <string_view>

#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

constexpr std::string_view rolling_keys[] = {"angle", "angular_velocity", "inertia"};

}  // namespace

void parse_rolling_keys(const Reader& r, const toml::table& t, const std::string& path,
                        BodyDef& def) {
  if (auto a = r.number(t, "angle", path + ".angle")) {
    r.require_state(t, "angle", path + ".angle", *a, "rad");
    def.body.angle = *a;
  }
  if (auto w = r.number(t, "angular_velocity", path + ".angular_velocity")) {
    r.require_state(t, "angular_velocity", path + ".angular_velocity", *w, "rad/s");
    def.body.angular_velocity = *w;
  }
  if (const toml::node* n = t.get("inertia"); n && !def.shapes.empty()) {
    // A body with shapes: about its centre of mass, instead of body_mass's (shape.hpp).
    const auto i = r.number(t, "inertia", path + ".inertia");
    r.require(*i > 0.0, t, "inertia", path + ".inertia", "> 0 kg*m^2", *i);
    r.require(divisor_in_range(*i), t, "inertia", path + ".inertia",
              "in [1e-100, 1e100] kg*m^2 (a step divides by it)", *i);
    def.inertia = *i;
  } else if (n) {
    if (!def.collider) {
      r.fail(n->source(), path + ".inertia",
             "needs a radius or a shape: only a disc (a body with a radius) rolls, and only a "
             "body with shapes turns; add radius = ... (m) or shape = { ... }");
    }
    const auto i = r.number(t, "inertia", path + ".inertia");
    // 1/I, r/I and m r²/I turn the disc: a subnormal I made them infinite and the state NaN.
    r.require(*i > 0.0, t, "inertia", path + ".inertia", "> 0 kg*m^2", *i);
    r.require(divisor_in_range(*i), t, "inertia", path + ".inertia",
              "in [1e-100, 1e100] kg*m^2 (a step divides by it)", *i);
    def.collider->inertia = *i;
  }
}

void warn_unused_rolling_keys(Reader& r, const toml::table& doc) {
  auto check = [&](const toml::table* t, const std::string& path) {
    if (!t || t->get("shape")) return;  // a body with shapes turns without rolling
    for (const std::string_view k : rolling_keys) {
      if (const toml::node* n = t->get(k)) {
        r.warn(n->source(), path + "." + std::string(k),
               "ignored: discs turn only with rolling on; add rolling = true to [contacts], or "
               "remove it");
      }
    }
  };
  for_each_body_table(doc, check);
}

}  // namespace fixstep::scene_detail
