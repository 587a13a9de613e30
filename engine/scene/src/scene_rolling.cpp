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
  if (auto a = r.number(t, "angle", path + ".angle")) def.body.angle = *a;
  if (auto w = r.number(t, "angular_velocity", path + ".angular_velocity")) {
    def.body.angular_velocity = *w;
  }
  if (const toml::node* n = t.get("inertia")) {
    if (!def.collider) {
      r.fail(n->source(), path + ".inertia",
             "needs a radius: only a disc (a body with a radius) rolls; add radius = ... (m)");
    }
    const auto i = r.number(t, "inertia", path + ".inertia");
    r.require(*i > 0.0, t, "inertia", path + ".inertia", "> 0 kg*m^2", *i);
    def.collider->inertia = *i;
  }
}

void warn_unused_rolling_keys(Reader& r, const toml::table& doc) {
  auto check = [&](const toml::table* t, const std::string& path) {
    if (!t) return;
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
