// A body's `mover = { ... }` (BodyDef::mover, fixstep/core/mover.hpp): read with its checks at
// its keys, and written back.
#include <fmt/format.h>

#include <string>
#include <string_view>

#include "fixstep/core/mover.hpp"
#include "scene_reader.hpp"
#include "scene_values.hpp"

namespace fixstep::scene_detail {

namespace {

constexpr std::string_view mover_keys[] = {"max_floor_angle", "step_height", "snap_distance",
                                           "push_force", "skin"};

/// The mover table's key a mover_problem message starts with.
std::string_view mover_key_of(std::string_view message) {
  const std::string_view word = message.substr(0, message.find(' '));
  for (const std::string_view k : mover_keys) {
    if (word == k) return k;
  }
  return mover_keys[0];
}

}  // namespace

void parse_body_mover(Reader& r, const toml::table& t, const std::string& path, BodyDef& def) {
  const std::string mp = path + ".mover";
  const toml::table* m = r.table(t, "mover", mp);
  if (!m) return;
  r.check_keys(*m, mp, {"max_floor_angle", "step_height", "snap_distance", "push_force", "skin"});
  MoverDef md;
  auto read = [&](std::string_view key, double& field) {
    if (auto v = r.number(*m, key, mp + "." + std::string(key))) field = *v;
  };
  read("max_floor_angle", md.max_floor_angle);
  read("step_height", md.step_height);
  read("snap_distance", md.snap_distance);
  read("push_force", md.push_force);
  read("skin", md.skin);
  auto at = [&](std::string_view key) -> const toml::node& {
    const toml::node* n = m->get(key);
    return n ? *n : *t.get("mover");
  };
  if (auto problem = mover_problem(md)) {
    const std::string_view key = mover_key_of(*problem);
    r.fail(at(key).source(), mp + "." + std::string(key), *problem);
  }
  const toml::node& whole = *t.get("mover");
  if (def.type != BodyType::kinematic) {
    r.fail(whole.source(), mp, "a mover is a kinematic body: add type = \"kinematic\" to the body");
  }
  if (def.shapes.size() != 1 || def.shapes[0].kind != ShapeKind::capsule) {
    r.fail(whole.source(), mp,
           "a mover carries exactly one shape, a capsule: shape = { capsule = [[0, -0.5], [0, "
           "0.5]], radius = 0.3 }");
  }
  if (def.body.angle != 0.0 || def.body.angular_velocity != 0.0) {
    r.fail(whole.source(), mp, "a mover never turns: remove the body's angle and angular_velocity");
  }
  const double radius = def.shapes[0].radius;
  if (!(md.step_height < radius)) {
    r.fail(at("step_height").source(), mp + ".step_height",
           fmt::format("must be below the capsule radius {} m (got {}): a step is climbed on the "
                       "capsule's round bottom",
                       radius, md.step_height));
  }
  if (!(md.skin < 0.5 * radius)) {
    r.fail(at("skin").source(), mp + ".skin",
           fmt::format("must be below half the capsule radius {} m (got {})", radius, md.skin));
  }
  def.mover = md;
}

std::string mover_text(const BodyDef& b) {
  if (!b.mover) return {};
  const MoverDef& m = *b.mover;
  return fmt::format(
      "mover = {{ max_floor_angle = {}, step_height = {}, snap_distance = {}, push_force = {}, "
      "skin = {} }}\n",
      toml_number(m.max_floor_angle), toml_number(m.step_height), toml_number(m.snap_distance),
      toml_number(m.push_force), toml_number(m.skin));
}

}  // namespace fixstep::scene_detail
