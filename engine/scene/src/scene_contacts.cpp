// Scene files, part four: bodies that touch. The [contacts] table, a body's type (dynamic,
// static, kinematic) and its disc keys (collide, restitution, friction), and the discs that
// overlap where they start. See README "Scene format".
#include <array>
#include <cmath>

#include "fixstep/core/components.hpp"
#include "fixstep/core/disc_overlap.hpp"
#include "fixstep/core/world_settings.hpp"
#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

/// Why a static or kinematic body ignores what would move it, for warnings.
std::string_view never_moves(BodyType type) {
  return type == BodyType::static_body ? "a static body never moves"
                                       : "a kinematic body moves only at its velocity";
}

/// The coefficients shared by [contacts] and a body: restitution e in [0, 1] and friction
/// μ >= 0, nullopt when absent.
std::optional<double> restitution(const Reader& r, const toml::table& t, const std::string& path) {
  const std::string key = path.empty() ? "restitution" : path + ".restitution";
  const std::optional<double> e = r.number(t, "restitution", key);
  if (e) r.require(*e >= 0.0 && *e <= 1.0, t, "restitution", key, "in [0, 1]", *e);
  return e;
}

std::optional<double> friction(const Reader& r, const toml::table& t, const std::string& path) {
  const std::string key = path.empty() ? "friction" : path + ".friction";
  const std::optional<double> mu = r.number(t, "friction", key);
  if (mu) r.require(*mu >= 0.0, t, "friction", key, ">= 0", *mu);
  return mu;
}

/// Without [contacts]: a warning at each restitution, friction, category, mask and group of a
/// [[body]] or a generator's body template, which act only between discs and so do nothing,
/// and an error at a sensor = true (a sensor that could never report).
void warn_unused_disc_keys(Reader& r, const toml::table& doc) {
  auto check = [&](const toml::table* t, const std::string& path) {
    if (!t) return;
    if (const toml::node* n = t->get("sensor"); n && n->value_or(false)) {
      r.fail(n->source(), path + ".sensor",
             "needs a [contacts] table: sensors see discs through disc contacts, and without "
             "them a sensor would never report anything; add [contacts]");
    }
    for (const std::string_view k : {"restitution", "friction", "category", "mask", "group"}) {
      if (const toml::node* n = t->get(k)) {
        r.warn(n->source(), path + "." + std::string(k),
               fmt::format("ignored: it acts only in disc-disc contacts, and without a "
                           "[contacts] table discs never collide{}; add [contacts] to make "
                           "discs collide, or remove it",
                           k == "restitution" || k == "friction"
                               ? fmt::format(" ([[plane]]s use their own {})", k)
                               : std::string(" (planes have no filter)")));
      }
    }
  };
  for_each_body_table(doc, check);
}

/// sleep (boolean), sleep_speed (m/s, > 0) and sleep_time (s, >= 0 and under 1e9 ticks of dt,
/// as the World refuses otherwise) of [contacts] into c; sleep_speed and sleep_time without
/// sleep = true are read and checked but warned about: they do nothing.
void parse_sleep_keys(Reader& r, const toml::table& t, double dt, ContactSettings& c) {
  if (auto v = r.boolean(t, "sleep", "contacts.sleep")) c.sleep = *v;
  if (auto v = r.number(t, "sleep_speed", "contacts.sleep_speed")) {
    r.require(*v > 0.0, t, "sleep_speed", "contacts.sleep_speed", "> 0 m/s", *v);
    c.sleep_speed = *v;
  }
  if (auto v = r.number(t, "sleep_time", "contacts.sleep_time")) {
    r.require(*v >= 0.0, t, "sleep_time", "contacts.sleep_time", ">= 0 s", *v);
    const double ticks = std::ceil(*v / dt);  // as the World counts them (world_sleep.cpp)
    if (!(ticks < 1e9)) {
      r.fail(t.get("sleep_time")->source(), "contacts.sleep_time",
             fmt::format("must be under 1e9 ticks of dt = {:g} s (got {:g} s, {:g} ticks); give "
                         "a shorter sleep_time",
                         dt, *v, ticks));
    }
    c.sleep_time = *v;
  }
  if (c.sleep) return;
  for (const std::string_view k : {"sleep_speed", "sleep_time"}) {
    if (const toml::node* n = t.get(k)) {
      r.warn(n->source(), "contacts." + std::string(k),
             "ignored: islands fall asleep only with sleep on; add sleep = true to [contacts], "
             "or remove it");
    }
  }
}

}  // namespace

BodyType parse_body_type(const Reader& r, const toml::table& t, const std::string& path) {
  const std::optional<std::string> name = r.string(t, "type", path + ".type");
  if (!name) return BodyType::dynamic;
  constexpr std::array types{BodyType::dynamic, BodyType::static_body, BodyType::kinematic};
  std::vector<std::string> valid;
  for (const BodyType type : types) {
    if (*name == body_type_name(type)) return type;
    valid.emplace_back(body_type_name(type));
  }
  const std::optional<std::string> best = closest(*name, valid);
  r.fail(t.get("type")->source(), path + ".type",
         fmt::format("unknown body type \"{}\"{} (valid: dynamic, static, kinematic)", *name,
                     best ? fmt::format("; did you mean \"{}\"?", *best) : std::string()));
}

void parse_body_mass(Reader& r, const toml::table& t, const std::string& path, BodyDef& def) {
  if (def.type == BodyType::dynamic) {
    if (!t.get("mass") && shapes_give_density(t)) return;  // the densities give the mass
    def.body.mass = r.required_number(t, path, "mass", "the mass in kg, e.g. mass = 1.0");
    r.require(def.body.mass > 0.0, t, "mass", path + ".mass", "> 0 kg", def.body.mass);
    r.require(divisor_in_range(def.body.mass), t, "mass", path + ".mass",
              "in [1e-100, 1e100] kg (a step divides by it)", def.body.mass);
    return;
  }
  if (r.number(t, "mass", path + ".mass")) {
    r.warn(t.get("mass")->source(), path + ".mass",
           fmt::format("ignored: a {} body has no mass ({}; it pushes others as an infinite "
                       "mass would)",
                       body_type_name(def.type), never_moves(def.type)));
  }
}

/// t[key] as filter bits: an integer whose 64-bit two's complement is the bit set (-1: every
/// category; hexadecimal allowed), nullopt when absent.
std::optional<std::uint64_t> filter_bits(const Reader& r, const toml::table& t,
                                         std::string_view key, const std::string& path) {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  const std::int64_t v = r.integer_node(*n, path, std::numeric_limits<std::int64_t>::min(),
                                        std::numeric_limits<std::int64_t>::max());
  return static_cast<std::uint64_t>(v);
}

/// sensor, category, mask and group of t into c.
void parse_filter_keys(const Reader& r, const toml::table& t, const std::string& path,
                       Collider& c) {
  if (auto v = r.boolean(t, "sensor", path + ".sensor")) c.sensor = *v;
  if (auto bits = filter_bits(r, t, "category", path + ".category")) c.filter.category = *bits;
  if (auto bits = filter_bits(r, t, "mask", path + ".mask")) c.filter.mask = *bits;
  if (const toml::node* n = t.get("group")) {
    c.filter.group = static_cast<std::int32_t>(
        r.integer_node(*n, path + ".group", std::numeric_limits<std::int32_t>::min(),
                       std::numeric_limits<std::int32_t>::max(),
                       " (positive: the group always collides, negative: never)"));
  }
}

void parse_disc_keys(const Reader& r, const toml::table& t, const std::string& path, BodyDef& def) {
  for (const std::string_view k :
       {"collide", "restitution", "friction", "sensor", "category", "mask", "group"}) {
    if (t.get(k) && !def.collider && !def.shapes.empty()) {
      r.fail(t.get(k)->source(), path + "." + std::string(k),
             fmt::format("a body with shapes gives it in each shape table; move it into "
                         "shape = {{ ..., {} = ... }}",
                         k));
    }
    if (t.get(k) && !def.collider) {
      r.fail(t.get(k)->source(), path + "." + std::string(k),
             "needs a radius: only a disc (a body with a radius) takes part in contacts; add "
             "radius = ... (m)");
    }
  }
  if (!def.collider) return;
  if (auto v = r.boolean(t, "collide", path + ".collide")) def.collider->collide = *v;
  def.collider->restitution = restitution(r, t, path);
  def.collider->friction = friction(r, t, path);
  parse_filter_keys(r, t, path, *def.collider);
}

void drop_moving_parts(Reader& r, const toml::table& t, const std::string& path, BodyDef& def) {
  if (def.type == BodyType::dynamic) return;
  auto drop = [&](std::string_view key, bool present, const auto& reset) {
    if (!present) return;
    r.warn(t.get(key)->source(), path + "." + std::string(key),
           fmt::format("ignored: {}", never_moves(def.type)));
    reset();
  };
  drop("spring", def.spring.has_value(), [&] { def.spring.reset(); });
  drop("gravity", def.gravity.has_value(), [&] { def.gravity.reset(); });
  drop("force", def.constant_force.has_value(), [&] { def.constant_force.reset(); });
  drop("drag", def.drag.has_value(), [&] { def.drag.reset(); });
  const Vec2 v = def.body.velocity;
  if (def.type == BodyType::static_body && (v.x != 0.0 || v.y != 0.0)) {
    r.warn(t.get("velocity")->source(), path + ".velocity",
           fmt::format("set to [0, 0]: a static body never moves (got [{:g}, {:g}] m/s; "
                       "type = \"kinematic\" moves at its velocity)",
                       v.x, v.y));
    def.body.velocity = Vec2{};
  }
}

void parse_contacts(Reader& r, const toml::table& doc, Scene& scene) {
  const toml::table* t = r.table(doc, "contacts", "contacts");
  if (!t) {
    warn_unused_disc_keys(r, doc);
    warn_unused_rolling_keys(r, doc);
    return;
  }
  r.check_keys(*t, "contacts",
               {"restitution", "friction", "restitution_threshold", "velocity_iterations",
                "position_iterations", "rolling", "sleep", "sleep_speed", "sleep_time"});
  ContactSettings contacts;
  contacts.restitution = restitution(r, *t, "contacts").value_or(0.0);
  contacts.friction = friction(r, *t, "contacts").value_or(0.0);
  if (auto v = r.number(*t, "restitution_threshold", "contacts.restitution_threshold")) {
    r.require(*v >= 0.0, *t, "restitution_threshold", "contacts.restitution_threshold", ">= 0 m/s",
              *v);
    contacts.restitution_threshold = *v;
  }
  constexpr int most = ContactSettings::max_iterations;
  if (const toml::node* n = t->get("velocity_iterations")) {
    contacts.velocity_iterations =
        static_cast<int>(r.integer_node(*n, "contacts.velocity_iterations", 1, most));
  }
  if (const toml::node* n = t->get("position_iterations")) {
    contacts.position_iterations =
        static_cast<int>(r.integer_node(*n, "contacts.position_iterations", 0, most));
  }
  if (auto v = r.boolean(*t, "rolling", "contacts.rolling")) contacts.rolling = *v;
  if (!contacts.rolling) warn_unused_rolling_keys(r, doc);
  parse_sleep_keys(r, *t, scene.def.settings.dt, contacts);
  scene.def.settings.contacts = contacts;
  const bool discs =
      std::any_of(scene.def.bodies.begin(), scene.def.bodies.end(),
                  [](const BodyDef& b) { return b.collider.has_value() || !b.shapes.empty(); });
  if (!discs) {
    r.warn(t->source(), "contacts",
           "no body has a radius, so there are no discs to collide: give bodies a radius (m) "
           "in [[body]] or a generator's body template");
  }
}

void check_start_overlap(const Scene& scene, const BodyNames& names) {
  if (!scene.def.settings.contacts) return;
  std::optional<std::pair<std::size_t, std::size_t>> pair;
  try {
    pair = first_disc_overlap(scene.def.bodies, scene.def.links);
  } catch (const std::invalid_argument& e) {
    throw SceneError(scene.file, 0, 0, "contacts", e.what());  // the loader checks first
  }
  if (!pair) return;
  const auto [a, b] = *pair;
  const std::size_t la = scene.source.body_lines[a], lb = scene.source.body_lines[b];
  const std::size_t later = lb >= la ? b : a;
  // The key of the later body: body[i] for a [[body]] table, else its generator's table.
  std::string key = fmt::format("body[{}]", later);
  for (const auto& [first, path] : names.generated) {
    if (later >= first) key = path;
  }
  const BodyDef &da = scene.def.bodies[a], &db = scene.def.bodies[b];
  const double reach = da.collider->radius + db.collider->radius;
  const double apart = reach - disc_overlap_depth(da, db);
  throw SceneError(
      scene.file, scene.source.body_lines[later], 0, key,
      fmt::format("discs \"{}\" (line {}) and \"{}\" (line {}) overlap by {:.6g} m where they "
                  "start (centres {:.6g} m apart, radii {:g} + {:g} m), and [contacts] would "
                  "push them apart at once; move them apart, set collide = false on one, or "
                  "join them by a [[spring]] (linked bodies never collide)",
                  da.name, la, db.name, lb, reach - apart, apart, da.collider->radius,
                  db.collider->radius));
}

}  // namespace fixstep::scene_detail
