// One player's per-tick input (fixstep::TickInput, exactly: every bit of every field) as sent
// over the network: each tick a delta against the tick before, and a run of unchanged ticks in
// one byte. The byte layout and its cost per tick are in docs/NETWORK.md.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/net/net_protocol.hpp"

namespace fixstep::net {

/// Bits of InputDelta::mask: which fields of TickInput a changed tick carries.
enum InputField : std::uint8_t {
  field_push = 1u << 0,     ///< the levels: push.x, push.y (finite) and the axes ([-1, 1])
  field_held = 1u << 1,     ///< held (the game's action bits, any of 32)
  field_edges = 1u << 2,    ///< pressed, released
  field_pointer = 1u << 3,  ///< pointer.x, pointer.y (finite)
  field_drag = 1u << 4,     ///< drag_body
  field_bodies = 1u << 5,   ///< bodies (<= max_net_body_inputs, kinds 0..2, finite values)
};
inline constexpr std::uint8_t all_input_fields = 0x3f;
/// On the wire only, in place of field_pointer: a pointer on the pointer grid, as two zigzag
/// LEB128 varints of grid units (decoded into field_pointer: InputDelta never carries it).
inline constexpr std::uint8_t wire_pointer_grid = 1u << 6;

/// The pointer grid: 2^-pointer_grid_bits m (about 1 mm). A pointer whose coordinates are
/// multiples of it, at most max_pointer_grid_units of it from 0 and not -0.0, goes on the wire
/// as two varints (1–3 bytes each within ±1 km) instead of two doubles (16 bytes); the value
/// decoded is the same double, bit for bit.
inline constexpr int pointer_grid_bits = 10;
inline constexpr std::int64_t max_pointer_grid_units = std::int64_t{1} << 40;

/// `p` with each coordinate rounded to the nearest multiple of the pointer grid (ties to even;
/// -0.0 becomes 0.0); a coordinate beyond max_pointer_grid_units of the grid, or not finite,
/// is returned as it is. Deterministic: scaling by a power of two and rounding to an integer
/// are exact.
[[nodiscard]] Vec2 round_to_pointer_grid(Vec2 p);

/// Whether a and b are the same input bit for bit (0.0 and -0.0 differ), their tick fields
/// aside.
[[nodiscard]] bool same_input(const TickInput& a, const TickInput& b);
/// What is wrong with `in` for the network (PacketError::none when nothing): a non-finite
/// push, pointer or body value, an axis outside [-1, 1], more than
/// max_net_body_inputs body inputs, a body input kind out of range, any joint input (the
/// network does not carry TickInput::joints: a networked game derives its motors in its rules).
[[nodiscard]] PacketError check_input(const TickInput& in);
/// The fields of `in` that differ from `prev` (InputField bits).
[[nodiscard]] std::uint8_t changed_fields(const TickInput& prev, const TickInput& in);
/// `prev` with the fields d.mask names taken from d.fields; tick set to `tick`.
[[nodiscard]] TickInput apply_delta(const InputDelta& d, const TickInput& prev, std::uint64_t tick);

/// Appends the items of `inputs` (consecutive ticks; the first a delta against `prev`) to
/// `out`: a byte 0..127 for 1..128 ticks equal to the one before, or 0x80 | mask followed by
/// the changed fields. Inputs must pass check_input (else std::invalid_argument).
void encode_inputs(std::span<const TickInput> inputs, const TickInput& prev,
                   std::vector<std::uint8_t>& out);
/// Bytes encode_inputs would append.
[[nodiscard]] std::size_t encoded_size(std::span<const TickInput> inputs, const TickInput& prev);

/// Decodes items from `in` until exactly `ticks` ticks are read (1 .. max_run_ticks), into
/// `out` (cleared); `used` gets the bytes read. Errors: too_short (the items end early),
/// bad_field (a change with no field or a reserved bit, a repeat past `ticks`), bad_input
/// (check_input fails on a decoded field). A repeat item's ticks have mask 0.
[[nodiscard]] PacketError decode_inputs(std::span<const std::uint8_t> in, std::uint32_t ticks,
                                        std::vector<InputDelta>& out, std::size_t& used);

}  // namespace fixstep::net
