// fixstep::net: per-tick input as deltas and runs (fixstep/net/net_input_codec.hpp).
#include <array>
#include <bit>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "byte_io.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/net/net_input_codec.hpp"

namespace fixstep::net {

namespace {

bool finite(Vec2 v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}
/// The axes' bits: bit i set for a non-zero axis i (the wire carries only those).
std::uint8_t axis_bits(const TickInput& in) {
  std::uint8_t bits = 0;
  for (std::size_t i = 0; i < max_axes; ++i) {
    if (in.axes[i] != 0.0 || std::signbit(in.axes[i])) bits |= static_cast<std::uint8_t>(1u << i);
  }
  return bits;
}

/// A coordinate's grid units when it is on the pointer grid (round_to_pointer_grid's
/// values), else nothing.
std::optional<std::int64_t> grid_units(double v) {
  if (!std::isfinite(v) || (std::signbit(v) && v == 0.0)) return std::nullopt;
  const double scaled = std::ldexp(v, pointer_grid_bits);
  if (std::fabs(scaled) > static_cast<double>(max_pointer_grid_units)) return std::nullopt;
  if (std::trunc(scaled) != scaled) return std::nullopt;
  return static_cast<std::int64_t>(scaled);
}

std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}

std::int64_t unzigzag(std::uint64_t u) {
  return static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1u);
}

std::size_t varint_size(std::uint64_t v) {
  std::size_t n = 1;
  for (; v >= 0x80u; v >>= 7) ++n;
  return n;
}

/// Grid units of both coordinates of p, when both are on the grid.
std::optional<std::array<std::int64_t, 2>> pointer_units(Vec2 p) {
  const auto x = grid_units(p.x), y = grid_units(p.y);
  if (!x || !y) return std::nullopt;
  return std::array<std::int64_t, 2>{*x, *y};
}

std::size_t pointer_size(Vec2 p) {
  const auto units = pointer_units(p);
  if (!units) return 16;
  return varint_size(zigzag((*units)[0])) + varint_size(zigzag((*units)[1]));
}

/// Bytes of the fields `mask` names in `in`.
std::size_t fields_size(std::uint8_t mask, const TickInput& in) {
  std::size_t n = 1;
  if (mask & field_push) n += 17 + 8 * static_cast<std::size_t>(std::popcount(axis_bits(in)));
  if (mask & field_held) n += varint_size(in.held);
  if (mask & field_edges) n += varint_size(in.pressed) + varint_size(in.released);
  if (mask & field_pointer) n += pointer_size(in.pointer);
  if (mask & field_drag) n += 8;
  if (mask & field_bodies) n += 1 + 25 * in.bodies.size();
  return n;
}

void write_entity(detail::ByteWriter& w, Entity e) {
  w.u32(e.index1);
  w.u32(e.generation);
}

Entity read_entity(detail::ByteReader& r) {
  Entity e;
  e.index1 = r.u32();
  e.generation = r.u32();
  return e;
}

void write_fields(detail::ByteWriter& w, std::uint8_t mask, const TickInput& in) {
  const auto units = (mask & field_pointer) ? pointer_units(in.pointer) : std::nullopt;
  const std::uint8_t wire_mask =
      units ? static_cast<std::uint8_t>((mask & ~field_pointer) | wire_pointer_grid) : mask;
  w.u8(static_cast<std::uint8_t>(0x80u | wire_mask));
  if (mask & field_push) {  // the levels: push, then the non-zero axes
    w.f64(in.push.x);
    w.f64(in.push.y);
    const std::uint8_t axes = axis_bits(in);
    w.u8(axes);
    for (std::size_t i = 0; i < max_axes; ++i) {
      if ((axes >> i) & 1u) w.f64(in.axes[i]);
    }
  }
  if (mask & field_held) w.varint(in.held);
  if (mask & field_edges) {
    w.varint(in.pressed);
    w.varint(in.released);
  }
  if (units) {
    w.varint(zigzag((*units)[0]));
    w.varint(zigzag((*units)[1]));
  } else if (mask & field_pointer) {
    w.f64(in.pointer.x);
    w.f64(in.pointer.y);
  }
  if (mask & field_drag) write_entity(w, in.drag_body);
  if (mask & field_bodies) {
    w.u8(static_cast<std::uint8_t>(in.bodies.size()));
    for (const BodyInput& b : in.bodies) {
      write_entity(w, b.body);
      w.u8(static_cast<std::uint8_t>(b.kind));
      w.f64(b.value.x);
      w.f64(b.value.y);
    }
  }
}

/// One coordinate on the pointer grid: bad_input beyond max_pointer_grid_units.
double read_grid_coordinate(detail::ByteReader& r, bool& in_range) {
  const std::int64_t units = unzigzag(r.varint(9));
  if (units > max_pointer_grid_units || units < -max_pointer_grid_units) in_range = false;
  return std::ldexp(static_cast<double>(units), -pointer_grid_bits);
}

/// Reads the fields of `wire_mask` into d.fields (a pointer on the grid into field_pointer);
/// bad_input for a value check_input refuses.
PacketError read_fields(detail::ByteReader& r, std::uint8_t wire_mask, InputDelta& d) {
  TickInput& in = d.fields;
  bool in_range = true;
  if (d.mask & field_push) {
    in.push = {r.f64(), r.f64()};
    const std::uint8_t axes = r.u8();
    if ((axes >> max_axes) != 0) return PacketError::bad_input;
    for (std::size_t i = 0; i < max_axes; ++i) {
      if ((axes >> i) & 1u) in.axes[i] = r.f64();
    }
  }
  auto bits = [&](std::uint32_t& out) {
    const std::uint64_t v = r.varint(5);
    if (v > 0xffffffffu) in_range = false;
    out = static_cast<std::uint32_t>(v);
  };
  if (d.mask & field_held) bits(in.held);
  if (d.mask & field_edges) {
    bits(in.pressed);
    bits(in.released);
  }
  if (d.mask & field_pointer) in.pointer = {r.f64(), r.f64()};
  if (wire_mask & wire_pointer_grid) {
    in.pointer.x = read_grid_coordinate(r, in_range);
    in.pointer.y = read_grid_coordinate(r, in_range);
    d.mask |= field_pointer;
  }
  if (d.mask & field_drag) in.drag_body = read_entity(r);
  if (d.mask & field_bodies) {
    const std::uint8_t count = r.u8();
    if (count > max_net_body_inputs) return PacketError::bad_input;
    in.bodies.resize(count);
    for (BodyInput& b : in.bodies) {
      b.body = read_entity(r);
      const std::uint8_t kind = r.u8();
      if (kind > static_cast<std::uint8_t>(last_body_input_kind)) return PacketError::bad_input;
      b.kind = static_cast<BodyInputKind>(kind);
      b.value = {r.f64(), r.f64()};
    }
  }
  if (!r.ok()) return PacketError::too_short;
  if (!in_range) return PacketError::bad_input;
  return check_input(in);
}

}  // namespace

Vec2 round_to_pointer_grid(Vec2 p) {
  auto round = [](double v) {
    const double scaled = std::ldexp(v, pointer_grid_bits);
    if (!std::isfinite(v) || std::fabs(scaled) > static_cast<double>(max_pointer_grid_units)) {
      return v;
    }
    return std::ldexp(std::nearbyint(scaled), -pointer_grid_bits) + 0.0;  // + 0.0: no -0.0
  };
  return {round(p.x), round(p.y)};
}

bool same_input(const TickInput& a, const TickInput& b) {
  return changed_fields(a, b) == 0;
}

PacketError check_input(const TickInput& in) {
  if (!finite(in.push) || !finite(in.pointer)) return PacketError::bad_input;
  for (const double a : in.axes) {
    if (!(a >= -1.0 && a <= 1.0)) return PacketError::bad_input;
  }
  if (in.bodies.size() > max_net_body_inputs) return PacketError::bad_input;
  if (!in.joints.empty()) return PacketError::bad_input;  // not carried: the rules' to derive
  for (const BodyInput& b : in.bodies) {
    if (!finite(b.value) || b.kind > last_body_input_kind) return PacketError::bad_input;
  }
  return PacketError::none;
}

std::uint8_t changed_fields(const TickInput& prev, const TickInput& in) {
  // Bitwise comparisons of the doubles: -0.0 and 0.0 are different inputs to a replay's hash.
  auto bits_differ = [](Vec2 a, Vec2 b) {
    return std::bit_cast<std::uint64_t>(a.x) != std::bit_cast<std::uint64_t>(b.x) ||
           std::bit_cast<std::uint64_t>(a.y) != std::bit_cast<std::uint64_t>(b.y);
  };
  auto bodies_differ = [&](const std::vector<BodyInput>& a, const std::vector<BodyInput>& b) {
    if (a.size() != b.size()) return true;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].body != b[i].body || a[i].kind != b[i].kind || bits_differ(a[i].value, b[i].value)) {
        return true;
      }
    }
    return false;
  };
  std::uint8_t mask = 0;
  bool axes_differ = false;
  for (std::size_t i = 0; i < max_axes; ++i) {
    axes_differ |= bits_differ({prev.axes[i], 0.0}, {in.axes[i], 0.0});
  }
  if (bits_differ(prev.push, in.push) || axes_differ) mask |= field_push;
  if (prev.held != in.held) mask |= field_held;
  if (prev.pressed != in.pressed || prev.released != in.released) mask |= field_edges;
  if (bits_differ(prev.pointer, in.pointer)) mask |= field_pointer;
  if (prev.drag_body != in.drag_body) mask |= field_drag;
  if (bodies_differ(prev.bodies, in.bodies)) mask |= field_bodies;
  return mask;
}

TickInput apply_delta(const InputDelta& d, const TickInput& prev, std::uint64_t tick) {
  TickInput in = prev;
  in.tick = tick;
  if (d.mask & field_push) in.push = d.fields.push, in.axes = d.fields.axes;
  if (d.mask & field_held) in.held = d.fields.held;
  if (d.mask & field_edges) {
    in.pressed = d.fields.pressed;
    in.released = d.fields.released;
  }
  if (d.mask & field_pointer) in.pointer = d.fields.pointer;
  if (d.mask & field_drag) in.drag_body = d.fields.drag_body;
  if (d.mask & field_bodies) in.bodies = d.fields.bodies;
  return in;
}

void encode_inputs(std::span<const TickInput> inputs, const TickInput& prev,
                   std::vector<std::uint8_t>& out) {
  detail::ByteWriter w(out);
  const TickInput* before = &prev;
  std::size_t repeats = 0;
  auto flush = [&] {
    while (repeats > 0) {
      const std::size_t n = repeats < 128 ? repeats : 128;
      w.u8(static_cast<std::uint8_t>(n - 1));
      repeats -= n;
    }
  };
  for (const TickInput& in : inputs) {
    if (check_input(in) != PacketError::none) {
      throw std::invalid_argument(
          in.joints.empty()
              ? "net::encode_inputs: an input the network refuses (check_input)"
              : "net::encode_inputs: a tick's joint inputs are not sent over the network: set a "
                "networked game's motors from its rules (from the buttons every peer has)");
    }
    const std::uint8_t mask = changed_fields(*before, in);
    if (mask == 0) {
      ++repeats;
    } else {
      flush();
      write_fields(w, mask, in);
    }
    before = &in;
  }
  flush();
}

std::size_t encoded_size(std::span<const TickInput> inputs, const TickInput& prev) {
  std::size_t n = 0, repeats = 0;
  const TickInput* before = &prev;
  for (const TickInput& in : inputs) {
    const std::uint8_t mask = changed_fields(*before, in);
    if (mask == 0) {
      ++repeats;
    } else {
      n += (repeats + 127) / 128 + fields_size(mask, in);
      repeats = 0;
    }
    before = &in;
  }
  return n + (repeats + 127) / 128;
}

PacketError decode_inputs(std::span<const std::uint8_t> in, std::uint32_t ticks,
                          std::vector<InputDelta>& out, std::size_t& used) {
  out.clear();
  used = 0;
  if (ticks == 0 || ticks > max_run_ticks) return PacketError::bad_tick_range;
  detail::ByteReader r(in);
  while (out.size() < ticks) {
    const std::uint8_t item = r.u8();
    if (!r.ok()) return PacketError::too_short;
    if ((item & 0x80u) == 0) {
      const std::size_t n = std::size_t{item} + 1;
      if (n > ticks - out.size()) return PacketError::bad_field;
      out.resize(out.size() + n);  // mask 0: the tick before, repeated
      continue;
    }
    InputDelta d;
    const auto wire_mask = static_cast<std::uint8_t>(item & 0x7fu);
    d.mask = static_cast<std::uint8_t>(wire_mask & all_input_fields);
    if (wire_mask == 0) return PacketError::bad_field;
    if ((wire_mask & wire_pointer_grid) && (wire_mask & field_pointer)) {
      return PacketError::bad_field;  // the pointer twice
    }
    if (const PacketError e = read_fields(r, wire_mask, d); e != PacketError::none) return e;
    out.push_back(std::move(d));
  }
  used = r.position();
  return PacketError::none;
}

}  // namespace fixstep::net
