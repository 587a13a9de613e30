// state_fields, first_difference and describe (state_difference.hpp): the hash's input, field by
// field, read from the kernel in the order World::state_hash() mixes it.
#include "fixstep/core/state_difference.hpp"

#include <fmt/format.h>

#include <array>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/fnv1a.hpp"
#include "fixstep/core/random.hpp"
#include "world_state.hpp"

namespace fixstep {

StateFields state_fields(const World& world) {
  StateFields out;
  out.tick = world.tick();
  out.precision = world.precision();
  world.visit([&out](const auto& w) {
    const std::size_t n = w.body_count();
    out.bodies.resize(n);
    // The hash's optional parts are there when their arrays are (world_energy.cpp).
    out.rolling = !w.angle().empty();
    out.sleep = !w.islands().empty();
    for (std::size_t j = 0; j < n; ++j) {
      BodyState& b = out.bodies[j];
      b.x = w.x()[j], b.y = w.y()[j], b.vx = w.vx()[j], b.vy = w.vy()[j];
      if (out.rolling) b.theta = w.angle()[j], b.omega = w.angular_velocity()[j];
      if (out.sleep) b.sleep_ticks = w.still_ticks()[j], b.island = w.islands()[j];
    }
  });
  if (const Random& random = world.random(); random.draws() > 0) out.random_state = random.state();
  return out;
}

std::uint64_t state_hash(const StateFields& fields) {
  // As WorldKernel::state_hash (world_energy.cpp) and World::state_hash (world.cpp) mix them.
  std::uint64_t h = fnv1a_basis;
  auto mix_bytes = [&h](std::uint64_t bits, std::size_t bytes) {
    for (std::size_t i = 0; i < bytes; ++i) h = fnv1a_byte(h, (bits >> (8 * i)) & 0xffu);
  };
  const bool f32 = fields.precision == Precision::f32;
  auto mix = [&](double v) {
    if (f32) {
      mix_bytes(bits_of(static_cast<float>(v)), sizeof(float));
    } else {
      mix_bytes(bits_of(v), sizeof(double));
    }
  };
  for (const BodyState& b : fields.bodies) mix(b.x), mix(b.y), mix(b.vx), mix(b.vy);
  if (fields.rolling) {
    for (const BodyState& b : fields.bodies) mix(b.theta), mix(b.omega);
  }
  if (fields.sleep) {
    for (const BodyState& b : fields.bodies) {
      mix_bytes(b.sleep_ticks, sizeof(std::uint32_t)), mix_bytes(b.island, sizeof(std::uint32_t));
    }
  }
  if (fields.random_state) mix_bytes(*fields.random_state, sizeof(std::uint64_t));
  return h;
}

namespace {

struct RealField {
  const char* name;
  double BodyState::*value;
};
constexpr std::array<RealField, 4> motion_fields{
    {{"x", &BodyState::x}, {"y", &BodyState::y}, {"vx", &BodyState::vx}, {"vy", &BodyState::vy}}};
constexpr std::array<RealField, 2> turning_fields{
    {{"theta", &BodyState::theta}, {"omega", &BodyState::omega}}};

struct CountField {
  const char* name;
  std::uint32_t BodyState::*value;
};
constexpr std::array<CountField, 2> sleep_fields{
    {{"sleep_ticks", &BodyState::sleep_ticks}, {"island", &BodyState::island}}};

/// The bits a state holds for `value`: the double's, or in an f32 world the float's.
std::uint64_t stored_bits(double value, bool f32) {
  return f32 ? bits_of(static_cast<float>(value)) : bits_of(value);
}

StateDifference difference(const StateFields& ours, std::size_t body, const char* field) {
  StateDifference d;
  d.tick = ours.tick;
  d.body = body;
  d.field = field;
  d.f32 = ours.precision == Precision::f32;
  return d;
}

StateDifference counts_differ(const StateFields& ours, const char* field, std::uint64_t a,
                              std::uint64_t b) {
  StateDifference d = difference(ours, no_body, field);
  d.ours = static_cast<double>(a), d.theirs = static_cast<double>(b);
  d.bits_ours = a, d.bits_theirs = b;
  return d;
}

/// The first field of one body that differs, in the hash's order.
std::optional<StateDifference> body_difference(const StateFields& ours, const StateFields& theirs,
                                               std::size_t j) {
  const BodyState& a = ours.bodies[j];
  const BodyState& b = theirs.bodies[j];
  const bool f32 = ours.precision == Precision::f32;
  auto real = [&](const RealField& f) -> std::optional<StateDifference> {
    if (bits_of(a.*f.value) == bits_of(b.*f.value)) return std::nullopt;
    StateDifference d = difference(ours, j, f.name);
    d.ours = a.*f.value, d.theirs = b.*f.value;
    d.bits_ours = stored_bits(d.ours, f32), d.bits_theirs = stored_bits(d.theirs, f32);
    return d;
  };
  for (const RealField& f : motion_fields) {
    if (auto d = real(f)) return d;
  }
  if (ours.rolling) {
    for (const RealField& f : turning_fields) {
      if (auto d = real(f)) return d;
    }
  }
  if (ours.sleep) {
    for (const CountField& f : sleep_fields) {
      if (a.*f.value == b.*f.value) continue;
      StateDifference d = counts_differ(ours, f.name, a.*f.value, b.*f.value);
      d.body = j;
      return d;
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<StateDifference> first_difference(const StateFields& ours,
                                                const StateFields& theirs) {
  if (ours.bodies.size() != theirs.bodies.size()) {
    return counts_differ(ours, "bodies", ours.bodies.size(), theirs.bodies.size());
  }
  if (ours.rolling != theirs.rolling) {
    return counts_differ(ours, "rolling", ours.rolling, theirs.rolling);
  }
  if (ours.sleep != theirs.sleep) return counts_differ(ours, "sleep", ours.sleep, theirs.sleep);
  for (std::size_t j = 0; j < ours.bodies.size(); ++j) {
    if (auto d = body_difference(ours, theirs, j)) return d;
  }
  if (ours.random_state != theirs.random_state) {
    const std::uint64_t a = ours.random_state.value_or(0), b = theirs.random_state.value_or(0);
    StateDifference d = counts_differ(ours, "random", a, b);
    d.ours = static_cast<double>(a & ((std::uint64_t{1} << 53) - 1));
    d.theirs = static_cast<double>(b & ((std::uint64_t{1} << 53) - 1));
    d.drawn_ours = ours.random_state.has_value();
    d.drawn_theirs = theirs.random_state.has_value();
    return d;
  }
  return std::nullopt;
}

const char* unit_of(const std::string& field) {
  if (field == "x" || field == "y") return "m";
  if (field == "vx" || field == "vy") return "m/s";
  if (field == "theta") return "rad";
  if (field == "omega") return "rad/s";
  if (field == "sleep_ticks") return "ticks";
  return "";
}

namespace {

std::string body_text(std::size_t body, const World* names) {
  if (names && body < names->body_count()) {
    const std::string& name = names->name(names->bodies()[body]);
    if (!name.empty()) return fmt::format("body {} (\"{}\")", body, name);
  }
  return fmt::format("body {}", body);
}

std::string bits_text(const StateDifference& d) {
  const int digits = d.f32 ? 8 : 16;
  return fmt::format("bits 0x{:0{}x} against 0x{:0{}x}", d.bits_ours, digits, d.bits_theirs,
                     digits);
}

}  // namespace

std::string describe(const StateDifference& d, const World* names) {
  const std::string at = fmt::format("at tick {}", d.tick);
  if (d.field == "bodies") {
    return fmt::format("the body counts differ {}: {} against {}", at, d.bits_ours, d.bits_theirs);
  }
  if (d.field == "rolling" || d.field == "sleep") {
    return fmt::format("{} {}: {} against {}", d.field == "rolling" ? "rolling discs" : "sleeping",
                       at, d.bits_ours ? "on" : "off", d.bits_theirs ? "on" : "off");
  }
  if (d.field == "random") {
    auto state = [](std::uint64_t bits, bool drawn) {
      return drawn ? fmt::format("0x{:016x}", bits) : std::string("not drawn from");
    };
    return fmt::format("the random generator's state {}: {} against {}", at,
                       state(d.bits_ours, d.drawn_ours), state(d.bits_theirs, d.drawn_theirs));
  }
  const std::string unit = unit_of(d.field);
  const std::string suffix = unit.empty() ? "" : " " + unit;
  if (d.field == "sleep_ticks" || d.field == "island") {
    return fmt::format("{} {}: {} against {}{} {}", body_text(d.body, names), d.field, d.bits_ours,
                       d.bits_theirs, suffix, at);
  }
  return fmt::format("{} {}: {} against {}{} ({}) {}", body_text(d.body, names), d.field, d.ours,
                     d.theirs, suffix, bits_text(d), at);
}

}  // namespace fixstep
