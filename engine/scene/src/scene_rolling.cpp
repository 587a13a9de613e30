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
  auto check = [&](const toml::node* node, const std::string& path) {
    const toml::table* t = node ? node->as_table() : nullptr;
    if (!t) return;
    for (const std::string_view k : rolling_keys) {
      if (const toml::node* n = t->get(k)) {
        r.warn(n->source(), path + "." + std::string(k),
               "ignored: discs turn only with rolling on; add rolling = true to [contacts], or "
               "remove it");
      }
    }
  };
  auto each = [&](std::string_view list, auto&& visit) {
    const toml::array* a = doc.get(list) ? doc.get(list)->as_array() : nullptr;
    for (std::size_t i = 0; a && i < a->size(); ++i) visit(a->get(i), i);
  };
  each("body", [&](const toml::node* t, std::size_t i) { check(t, fmt::format("body[{}]", i)); });
  for (const std::string_view generator : {"chain", "grid"}) {
    each(generator, [&](const toml::node* t, std::size_t i) {
      const toml::table* table = t->as_table();
      check(table ? table->get("body") : nullptr, fmt::format("{}[{}].body", generator, i));
    });
  }
}

}  // namespace fixstep::scene_detail
