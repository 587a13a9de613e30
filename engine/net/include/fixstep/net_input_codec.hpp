// One player's per-tick input (fixstep::TickInput, exactly: every bit of every field) as sent
// over the network: each tick a delta against the tick before, and a run of unchanged ticks in
// one byte. The byte layout and its cost per tick are in docs/NETWORK.md.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/input.hpp"
#include "fixstep/net_protocol.hpp"

namespace fixstep::net {

/// Bits of InputDelta::mask: which fields of TickInput a changed tick carries.
enum InputField : std::uint8_t {
  field_push = 1u << 0,     ///< push.x, push.y (finite)
  field_held = 1u << 1,     ///< held (bits of all_buttons only)
  field_edges = 1u << 2,    ///< pressed, released (bits of all_buttons only)
  field_pointer = 1u << 3,  ///< pointer.x, pointer.y (finite)
  field_drag = 1u << 4,     ///< drag_body
  field_bodies = 1u << 5,   ///< bodies (<= max_net_body_inputs, kinds 0..2, finite values)
};
inline constexpr std::uint8_t all_input_fields = 0x3f;

/// Whether a and b are the same input bit for bit (0.0 and -0.0 differ), their tick fields
/// aside.
[[nodiscard]] bool same_input(const TickInput& a, const TickInput& b);
/// What is wrong with `in` for the network (PacketError::none when nothing): a non-finite
/// push, pointer or body value, a button bit outside all_buttons, more than
/// max_net_body_inputs body inputs, a body input kind out of range.
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
