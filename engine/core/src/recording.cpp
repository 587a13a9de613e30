// Recordings in memory: the definition hash, the Recorder and replay. Their text and files are
// fixstep::io's (recording_format.cpp, recording_file.cpp there).
#include "fixstep/core/recording.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <type_traits>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/fnv1a.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/work_progress.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

/// FNV-1a, 64-bit (Fowler, Noll, Vo), fed the bytes of plain values.
class Fnv1a {
 public:
  template <class T>
  void add(T value) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    if constexpr (std::is_same_v<T, double>) {
      add_bits(bits_of(value));
    } else {
      add_bits(static_cast<std::uint64_t>(value));
    }
  }
  void add(Vec2 v) { add(v.x), add(v.y); }
  template <class T, class F>
  void add_optional(const std::optional<T>& o, F&& fields) {
    add(o.has_value());
    if (o) fields(*o);
  }
  [[nodiscard]] std::uint64_t value() const { return hash_; }

 private:
  void add_bits(std::uint64_t bits) {
    for (int i = 0; i < 8; ++i) hash_ = fnv1a_byte(hash_, (bits >> (8 * i)) & 0xffu);
  }
  std::uint64_t hash_ = fnv1a_basis;
};

void hash_shape(Fnv1a& h, const ShapeDef& s) {
  h.add(s.kind), h.add(s.radius), h.add(s.half_extents), h.add(s.count);
  for (int i = 0; i < s.count && i < max_polygon_vertices; ++i) h.add(s.vertices[i]);
  h.add(s.offset), h.add(s.angle);
  h.add_optional(s.density, [&](double d) { h.add(d); });
  h.add_optional(s.friction, [&](double mu) { h.add(mu); });
  h.add_optional(s.restitution, [&](double e) { h.add(e); });
  h.add(s.filter.category), h.add(s.filter.mask), h.add(s.filter.group), h.add(s.sensor);
  if (s.rolling_resistance != 0.0) h.add(std::uint64_t{0x4011}), h.add(s.rolling_resistance);
  if (s.one_way) h.add(std::uint64_t{0x0e1a});  // absent: the hash from before one-way shapes
}

void hash_body(Fnv1a& h, const BodyDef& b) {
  h.add(b.body.mass), h.add(b.body.position), h.add(b.body.velocity);
  h.add_optional(b.spring, [&](const SpringDamper& s) {
    h.add(s.anchor), h.add(s.stiffness), h.add(s.damping), h.add(s.rest_length);
  });
  h.add_optional(b.constant_force, [&](const ConstantForce& f) { h.add(f.force); });
  h.add_optional(b.gravity, [&](const Gravity& g) { h.add(g.acceleration); });
  h.add_optional(b.drag, [&](const LinearDrag& d) { h.add(d.coefficient); });
  h.add_optional(b.collider, [&](const Collider& c) {
    h.add(c.radius);
    // What body contacts added (#19) enters only when set, so older definitions keep their
    // hashes and recordings.
    if (c.restitution || c.friction || !c.collide) {
      h.add_optional(c.restitution, [&](double e) { h.add(e); });
      h.add_optional(c.friction, [&](double mu) { h.add(mu); });
      h.add(c.collide);
    }
    // Sensors and filters likewise: only when set.
    if (c.sensor) h.add(c.sensor);
    if (c.filter != CollisionFilter{}) {
      h.add(c.filter.category), h.add(c.filter.mask), h.add(c.filter.group);
    }
    if (c.inertia) h.add(*c.inertia);  // rolling discs' given inertia: only when set
  });
  // A rolling disc's start angle and spin: only when not 0 (older definitions keep their hash).
  if (b.body.angle != 0.0 || b.body.angular_velocity != 0.0) {
    h.add(b.body.angle), h.add(b.body.angular_velocity);
  }
  if (b.type != BodyType::dynamic) h.add(b.type);
  // Shapes: only when the body has some (older definitions keep their hash).
  if (!b.shapes.empty()) {
    h.add(b.shapes.size());
    for (const ShapeDef& s : b.shapes) hash_shape(h, s);
    h.add_optional(b.inertia, [&](double i) { h.add(i); });
  }
  // A mover: only when the body is one (older definitions keep their hash).
  if (b.mover) {
    const MoverDef& m = *b.mover;
    h.add(std::uint64_t{0x307e5}), h.add(m.max_floor_angle), h.add(m.step_height);
    h.add(m.snap_distance), h.add(m.push_force), h.add(m.skin);
  }
}

/// Each joint's every field, its bodies by their places in def.bodies (the world: 0, a body
/// i + 1), a distance joint's second anchor as World makes it (unset: the anchor).
void hash_joints(Fnv1a& h, const WorldDef& def) {
  h.add(std::uint64_t{0x701e7}), h.add(def.joints.size());
  auto place = [&](Entity e) {
    if (e.is_null()) return std::uint64_t{0};
    return std::uint64_t{1} +
           std::uint64_t{fixstep::defined_index(e, def.bodies.size()).value_or(def.bodies.size())};
  };
  for (const JointDef& j : def.joints) {
    h.add(j.type), h.add(place(j.body_a)), h.add(place(j.body_b));
    h.add(j.anchor), h.add(j.anchor_b.value_or(j.anchor)), h.add(j.axis);
    h.add_optional(j.length, [&](double v) { h.add(v); });
    h.add_optional(j.lower, [&](double v) { h.add(v); });
    h.add_optional(j.upper, [&](double v) { h.add(v); });
    h.add(j.motor_speed), h.add(j.max_motor_torque), h.add(j.max_motor_force);
    h.add(j.frequency), h.add(j.damping_ratio), h.add(j.target);
    h.add_optional(j.break_force, [&](double v) { h.add(v); });
    h.add_optional(j.break_torque, [&](double v) { h.add(v); });
    h.add(j.collide_connected);
    h.add(j.name.size());
    for (const char c : j.name) h.add(static_cast<std::uint8_t>(c));
  }
}

}  // namespace

std::uint64_t definition_hash(const WorldDef& def) {
  Fnv1a h;
  h.add(def.precision);
  h.add(def.settings.dt), h.add(def.settings.integrator), h.add(def.settings.substeps);
  h.add(def.settings.flush_denormals);
  // A non-default damping split enters only when set: older recordings keep their hash.
  if (def.settings.damping_split != DampingSplit::per_stage) h.add(def.settings.damping_split);
  h.add(def.bodies.size());
  for (const BodyDef& b : def.bodies) hash_body(h, b);
  h.add(def.links.size());
  for (const LinkDef& l : def.links) {  // each end by its place in def.bodies
    h.add(static_cast<std::size_t>(l.body_a.slot())),
        h.add(static_cast<std::size_t>(l.body_b.slot()));
    h.add(l.spring.stiffness), h.add(l.spring.damping), h.add(l.spring.rest_length);
  }
  h.add(def.planes.size());
  for (const PlaneDef& p : def.planes) {
    h.add(p.normal), h.add(p.offset), h.add(p.restitution), h.add(p.friction);
  }
  if (def.settings.contacts) {  // absent: the hash of a world from before contacts
    const ContactSettings& c = *def.settings.contacts;
    h.add(c.restitution), h.add(c.friction);
    // The solver's iterations when not the defaults (absent: the hash from before them).
    if (c.velocity_iterations != ContactSettings::default_velocity_iterations ||
        c.position_iterations != ContactSettings::default_position_iterations) {
      h.add(c.velocity_iterations), h.add(c.position_iterations);
    }
    if (c.rolling) h.add(c.rolling);  // absent: the hash from before rolling discs
    // absent at its default: the hash from before the setting
    if (c.restitution_threshold != ContactSettings::default_restitution_threshold) {
      h.add(std::uint64_t{0x7e5}), h.add(c.restitution_threshold);
    }
    if (c.sleep) h.add(c.sleep), h.add(c.sleep_speed), h.add(c.sleep_time);  // absent: before
  }
  if (def.settings.seed != 0) {  // 0: the hash from before seeds (both seedings agree on it)
    h.add(def.settings.seed);
    // Mixed seeding: a term of its own, so that a world of an older recording, seeded as it
    // was (pcg32_srandom), keeps the hash it was recorded with.
    if (def.settings.seeding == Seeding::splitmix) h.add(std::uint64_t{0x5eed});
  }
  if (!def.segments.empty()) {  // absent: the hash of a world from before segments
    h.add(def.segments.size());
    for (const SegmentDef& s : def.segments) {
      h.add(s.a), h.add(s.b), h.add(s.restitution), h.add(s.friction);
      h.add(s.prev.has_value()), h.add(s.prev.value_or(Vec2{}));
      h.add(s.next.has_value()), h.add(s.next.value_or(Vec2{}));
      // The carrying body's place in the definition (absent: a static segment, as before).
      if (!s.body.is_null()) {
        h.add(std::uint64_t{1} +
              std::uint64_t{
                  fixstep::defined_index(s.body, def.bodies.size()).value_or(def.bodies.size())});
      }
      if (s.one_way) h.add(std::uint64_t{0x0e1a});  // absent: a two-sided segment, as before
    }
  }
  if (!def.joints.empty()) hash_joints(h, def);  // absent: the hash from before joints
  return h.value();
}

TickInput Recording::input_at(std::uint64_t tick) const {
  TickInput in{};
  if (tick < ticks) {
    const auto after =
        std::upper_bound(inputs.begin(), inputs.end(), tick,
                         [](std::uint64_t t, const TickInput& change) { return t < change.tick; });
    if (after != inputs.begin()) in = *(after - 1);
  }
  in.tick = tick;
  return in;
}

Recorder::Recorder(const WorldDef& def, std::string scene, std::uint64_t hash_every,
                   std::string scene_text) {
  if (hash_every == 0 || hash_every > max_hash_every) {  // the reader refuses more
    throw std::invalid_argument(
        fmt::format("Recorder: hash_every must be 1 .. {} (got {})", max_hash_every, hash_every));
  }
  rec_.scene = std::move(scene);
  if (scene_text.size() > max_recording_scene_bytes) {
    throw std::invalid_argument(
        fmt::format("Recorder: a scene_text of {} bytes; a recording embeds at most {} bytes",
                    scene_text.size(), max_recording_scene_bytes));
  }
  const auto control = std::find_if(rec_.scene.begin(), rec_.scene.end(),
                                    [](unsigned char c) { return c < 0x20 || c == 0x7f; });
  if (control != rec_.scene.end()) {
    // the text format keeps the name on one line (recording_file.hpp): refused now, not at the end
    throw std::invalid_argument(fmt::format(
        "Recorder: the scene name holds a control character (0x{:02x} at byte {} of {}), and a "
        "recording stores the name on one line",
        static_cast<unsigned char>(*control), control - rec_.scene.begin(), rec_.scene.size()));
  }
  rec_.scene_text = std::move(scene_text);
  rec_.definition_hash = definition_hash(def);
  rec_.settings = recorded_settings(def);
  rec_.hash_every = hash_every;
  rec_.version = recording_version_of(rec_);
}

void Recorder::record(const TickInput& input, const World& after_the_tick) {
  const std::uint64_t tick = rec_.ticks;
  if (after_the_tick.tick() != tick + 1) {
    throw std::invalid_argument(fmt::format(
        "Recorder::record: the simulation is at tick {}, the recording expects tick {} (after "
        "a rewind, call truncate first)",
        after_the_tick.tick(), tick + 1));
  }
  TickInput in = input;
  in.tick = tick;
  const bool same = !rec_.inputs.empty() && [&] {
    TickInput last = rec_.inputs.back();
    last.tick = tick;
    return last == in;
  }();
  if (!same) rec_.inputs.push_back(in);
  rec_.ticks = tick + 1;
  if (rec_.ticks % rec_.hash_every == 0) {
    rec_.hashes.emplace_back(rec_.ticks, after_the_tick.state_hash());
  }
}

void Recorder::truncate(std::uint64_t ticks) {
  if (ticks > rec_.ticks) {
    throw std::invalid_argument(
        fmt::format("Recorder::truncate: {} ticks requested, only {} recorded", ticks, rec_.ticks));
  }
  std::erase_if(rec_.inputs, [&](const TickInput& in) { return in.tick >= ticks; });
  std::erase_if(rec_.hashes, [&](const auto& h) { return h.first > ticks; });
  rec_.ticks = ticks;
}

Recording Recorder::finish(const World& sim) {
  if (sim.tick() != rec_.ticks) {
    throw std::invalid_argument(
        fmt::format("Recorder::finish: the simulation is at tick {}, the recording has {} ticks",
                    sim.tick(), rec_.ticks));
  }
  rec_.final_hash = sim.state_hash();
  return take();
}

Recording Recorder::finish_at_last_hash(std::uint64_t initial_hash) {
  const auto [ticks, hash] = rec_.hashes.empty()
                                 ? std::pair<std::uint64_t, std::uint64_t>{0, initial_hash}
                                 : rec_.hashes.back();
  truncate(ticks);
  rec_.final_hash = hash;
  return take();
}

std::string rules_name_fault(std::string_view name) {
  if (name.empty()) return "is empty";
  if (name.size() > max_rules_name_bytes) {
    return fmt::format("is {} bytes long (at most {})", name.size(), max_rules_name_bytes);
  }
  for (const char c : name) {
    if (!is_rules_name_char(c)) {
      return fmt::format("holds byte 0x{:02x}; use letters, digits, '.', '_' and '-'",
                         static_cast<unsigned char>(c));
    }
  }
  return {};
}

void Recorder::set_rules(std::string name, std::uint32_t version) {
  if (const std::string fault = rules_name_fault(name); !fault.empty()) {
    throw std::invalid_argument("Recorder::set_rules: the rules name " + fault);
  }
  if (version == 0) throw std::invalid_argument("Recorder::set_rules: the version must be >= 1");
  rec_.rules_name = std::move(name);
  rec_.rules_version = version;
  rec_.version = recording_version_of(rec_);
}

Recording Recorder::take() {
  Recording out = std::move(rec_);
  rec_ = Recording{};
  rec_.scene = out.scene;
  rec_.scene_text = out.scene_text;
  rec_.rules_name = out.rules_name;
  rec_.rules_version = out.rules_version;
  rec_.version = out.version;
  rec_.definition_hash = out.definition_hash;
  rec_.settings = out.settings;
  rec_.hash_every = out.hash_every;
  return out;
}

ReplayReport replay(World& sim, const Recording& rec, const TickRules& rules) {
  if (rules.attach) rules.attach(sim);
  if (sim.tick() != 0) {
    throw std::invalid_argument(
        fmt::format("replay: the simulation is at tick {}, not at its start", sim.tick()));
  }
  ReplayReport report;
  std::size_t next_change = 0, next_hash = 0;
  TickInput in{};
  auto mismatch = [&](std::uint64_t tick, std::uint64_t expected) {
    report.mismatch = ReplayReport::Mismatch{
        tick, next_hash > 0 ? rec.hashes[next_hash - 1].first : 0, expected, sim.state_hash()};
  };
  for (std::uint64_t t = 0; t < rec.ticks; ++t) {
    if (next_change < rec.inputs.size() && rec.inputs[next_change].tick == t) {
      in = rec.inputs[next_change++];
    }
    in.tick = t;
    rules.tick(sim, in);
    report.ticks = t + 1;
    if (report.ticks % 1024 == 0) report_work_progress("replay", "tick", report.ticks, rec.ticks);
    if (next_hash < rec.hashes.size() && rec.hashes[next_hash].first == t + 1) {
      if (sim.state_hash() != rec.hashes[next_hash].second) {
        mismatch(t + 1, rec.hashes[next_hash].second);
        break;
      }
      ++report.verified, ++next_hash;
    }
  }
  if (!report.mismatch) {
    if (sim.state_hash() == rec.final_hash) {
      ++report.verified;
    } else {
      mismatch(rec.ticks, rec.final_hash);
    }
  }
  report.final_hash = sim.state_hash();
  return report;
}

int recording_version_of(const Recording& rec) {
  if (rec.settings.seeding == Seeding::splitmix) return recording_version;
  return rec.rules_name.empty() ? recording_version_without_rules : recording_version_with_rules;
}

RecordedSettings recorded_settings(const WorldDef& def) {
  return {.integrator = def.settings.integrator,
          .precision = def.precision,
          .dt = def.settings.dt,
          .substeps = def.settings.substeps,
          .damping_split = def.settings.damping_split,
          // Seed 0: the same generator either way (mix_seed(0) = 0); recorded as the older
          // seeding so that its recording keeps the older version.
          .seeding = def.settings.seed == 0 ? Seeding::pcg32_srandom : def.settings.seeding};
}

void apply_settings(WorldDef& def, const RecordedSettings& settings) {
  def.precision = settings.precision;
  def.settings.dt = settings.dt;
  def.settings.integrator = settings.integrator;
  def.settings.substeps = settings.substeps;
  if (settings.damping_split) def.settings.damping_split = *settings.damping_split;
  def.settings.seeding = settings.seeding;
}

}  // namespace fixstep
