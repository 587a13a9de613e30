// fixstep::net's packets: hand-built bytes decoded, every check refusing what it must with its
// typed error, the encoders giving the same bytes, input runs exact and cheap when unchanged.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "fixstep/core/input.hpp"
#include "fixstep/net/net_input_codec.hpp"
#include "fixstep/net/net_packet.hpp"
#include "net_bytes.hpp"

namespace fixstep::net_test {
namespace {

using net::PacketError;

net::DecodeContext two_players() {
  net::DecodeContext ctx;
  ctx.players = 2;
  ctx.own_slot = 0;
  ctx.next_needed = {10, 10};
  return ctx;
}

PacketError decode(const Bytes& b, const net::DecodeContext& ctx, net::Packet& p) {
  return net::decode_packet(b.v, ctx, p);
}

PacketError decode(const Bytes& b, const net::DecodeContext& ctx = two_players()) {
  net::Packet p;
  return decode(b, ctx, p);
}

Bytes request(std::uint8_t flags = 0, std::uint32_t nonce = 77) {
  Bytes b;
  b.header(1, 0xff, 5).u8(flags).u32(nonce).u64(0xfeedf00d).zeros(64 - 25);
  return b;
}

TEST(NetPacket, HandshakeRequestDecodesAndIsPaddedTo64Bytes) {
  net::Packet p;
  ASSERT_EQ(decode(request(1, 1234), {}, p), PacketError::none);
  EXPECT_EQ(p.header.kind, net::MessageKind::handshake_request);
  EXPECT_EQ(p.header.sequence, 5u);
  EXPECT_TRUE(p.request.spectator);
  EXPECT_EQ(p.request.nonce, 1234u);
  EXPECT_EQ(p.request.definition_hash, 0xfeedf00du);
  std::vector<std::uint8_t> encoded;
  net::encode_handshake_request(
      {.sequence = 5}, {.spectator = true, .nonce = 1234, .definition_hash = 0xfeedf00d}, encoded);
  EXPECT_EQ(encoded, request(1, 1234).v);
}

TEST(NetPacket, HandshakeRequestRefusals) {
  Bytes short_one = request();
  short_one.v.pop_back();
  EXPECT_EQ(decode(short_one, {}), PacketError::too_short);
  Bytes longer = request();
  longer.u8(0);
  EXPECT_EQ(decode(longer, {}), PacketError::trailing_bytes);
  Bytes padding = request();
  padding.v[40] = 1;
  EXPECT_EQ(decode(padding, {}), PacketError::bad_field);
  EXPECT_EQ(decode(request(2), {}), PacketError::bad_field);  // reserved flag bit
  Bytes slotted = request();
  slotted.v[6] = 1;  // a request from a peer that claims a slot
  EXPECT_EQ(decode(slotted, {}), PacketError::bad_slot);
}

TEST(NetPacket, HeaderRefusalsInOrder) {
  EXPECT_EQ(decode(Bytes{{'F', 'X', 'S'}}), PacketError::too_short);
  Bytes big = request();
  big.zeros(1200);
  EXPECT_EQ(decode(big), PacketError::too_long);
  Bytes foreign = request();
  foreign.v[0] = 'G';
  EXPECT_EQ(decode(foreign), PacketError::bad_protocol_id);
  for (std::uint8_t version :
       {std::uint8_t{net::protocol_version - 1}, std::uint8_t{net::protocol_version + 1}}) {
    Bytes other;
    other.header(1, 0xff, 0, version).zeros(52);
    EXPECT_EQ(decode(other), PacketError::bad_version) << int{version};
  }
  for (int kind : {0, 8, 255}) {
    Bytes k;
    k.header(static_cast<std::uint8_t>(kind), 0, 0).zeros(20);
    EXPECT_EQ(decode(k), PacketError::bad_kind) << kind;
  }
  Bytes reserved = request();
  reserved.v[7] = 1;
  EXPECT_EQ(decode(reserved), PacketError::bad_field);
}

Bytes accept(std::uint8_t players, std::uint8_t slot, std::uint16_t hash_every = 10,
             std::uint8_t flags = 1) {
  Bytes b;
  b.header(2, 0, 1).u32(77).u8(players).u8(slot).u16(3).u16(hash_every).u8(flags).u64(0xabcdef);
  return b;
}

TEST(NetPacket, HandshakeAcceptIsNoLargerThanTheRequest) {
  net::Packet p;
  ASSERT_EQ(decode(accept(4, 3), {}, p), PacketError::none);
  EXPECT_EQ(p.accept.players, 4);
  EXPECT_EQ(p.accept.your_slot, 3);
  EXPECT_EQ(p.accept.input_delay, 3);
  EXPECT_EQ(p.accept.hash_every, 10);
  EXPECT_TRUE(p.accept.host_rollback);
  EXPECT_EQ(p.accept.definition_hash, 0xabcdefu);
  EXPECT_LE(accept(4, 3).v.size(), request().v.size());
  std::vector<std::uint8_t> encoded;
  net::encode_handshake_accept({.slot = 0, .sequence = 1}, p.accept, encoded);
  EXPECT_EQ(encoded, accept(4, 3).v);
  EXPECT_EQ(decode(accept(1, 1), {}), PacketError::bad_field);
  EXPECT_EQ(decode(accept(9, 1), {}), PacketError::bad_field);
  EXPECT_EQ(decode(accept(4, 1, 0), {}), PacketError::bad_field);
  EXPECT_EQ(decode(accept(4, 4), {}), PacketError::bad_slot);
  EXPECT_EQ(decode(accept(4, 0), {}), PacketError::bad_slot);
  ASSERT_EQ(decode(accept(4, 0x81), {}, p), PacketError::none);      // a spectator
  ASSERT_EQ(decode(accept(4, 3, 10, 0), {}, p), PacketError::none);  // a lockstep host
  EXPECT_FALSE(p.accept.host_rollback);
  EXPECT_EQ(decode(accept(4, 3, 10, 2), {}), PacketError::bad_field);  // an unknown flag
}

/// An inputs packet from slot 1 of a 2-player match: acks (10, 9), one run of player 1.
Bytes inputs_header(std::uint32_t ack0 = 10, std::uint32_t ack1 = 9, std::uint8_t runs = 1) {
  Bytes b;
  b.header(3, 1, 40).u8(2).u32(ack0).u32(ack1).u8(runs);
  return b;
}

TEST(NetPacket, InputsRunOfRepeatsAndChanges) {
  // Player 1, ticks 8..12: tick 8 holds `left`, 9..11 repeat it, tick 12 moves the pointer
  // (off the pointer grid: two doubles).
  Bytes b = inputs_header();
  Bytes items;
  items.u8(0x80 | 0x02).u8(1).u8(2).u8(0x80 | 0x08).f64(0.1).f64(-2.0);  // held: a varint
  b.u8(1).u32(8).u16(5).u16(items.v.size());
  b.v.insert(b.v.end(), items.v.begin(), items.v.end());
  net::Packet p;
  ASSERT_EQ(decode(b, two_players(), p), PacketError::none);
  EXPECT_EQ(p.inputs.next_needed[0], 10u);
  EXPECT_EQ(p.inputs.next_needed[1], 9u);
  ASSERT_EQ(p.inputs.runs.size(), 1u);
  const net::InputRun& run = p.inputs.runs[0];
  EXPECT_EQ(run.player, 1);
  EXPECT_EQ(run.first_tick, 8u);
  ASSERT_EQ(run.deltas.size(), 5u);
  TickInput prev{};
  std::vector<TickInput> ticks;
  for (std::size_t i = 0; i < 5; ++i) {
    prev = net::apply_delta(run.deltas[i], prev, 8 + i);
    ticks.push_back(prev);
  }
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(ticks[i].held, button_left) << i;
    EXPECT_EQ(ticks[i].pointer.x, 0.0) << i;
  }
  EXPECT_EQ(ticks[4].held, button_left);
  EXPECT_EQ(ticks[4].pointer.x, 0.1);
  EXPECT_EQ(ticks[4].pointer.y, -2.0);
  EXPECT_EQ(ticks[4].tick, 12u);
  // The encoder writes the same bytes.
  std::vector<std::uint8_t> encoded;
  const TickInput empty{};
  const net::RunToSend send{1, ticks, &empty};
  net::encode_inputs_message({.slot = 1, .sequence = 40}, 2, {10, 9}, {&send, 1}, encoded);
  EXPECT_EQ(encoded, b.v);
  EXPECT_EQ(net::inputs_packet_size(2, {&send, 1}), b.v.size());
}

Bytes one_run(std::uint8_t player, std::uint32_t first, std::uint16_t ticks, const Bytes& items,
              std::int64_t claimed_bytes = -1) {
  Bytes b = inputs_header();
  b.u8(player).u32(first).u16(ticks).u16(claimed_bytes < 0 ? items.v.size() : claimed_bytes);
  b.v.insert(b.v.end(), items.v.begin(), items.v.end());
  return b;
}

TEST(NetPacket, InputsRefusals) {
  Bytes one_tick;
  one_tick.u8(0);  // 1 tick, same as before
  EXPECT_EQ(decode(one_run(1, 10, 1, one_tick)), PacketError::none);
  EXPECT_EQ(decode(one_run(2, 10, 1, one_tick)), PacketError::bad_slot);  // player 2 of 2
  // A run after a gap (ticks in flight or lost) decodes (the session skips it), up to
  // max_gap_ticks after the receiver's next needed tick (10 here), not beyond.
  EXPECT_EQ(decode(one_run(1, 11, 1, one_tick)), PacketError::none);
  EXPECT_EQ(decode(one_run(1, 10 + net::max_gap_ticks, 1, one_tick)), PacketError::none);
  EXPECT_EQ(decode(one_run(1, 11 + net::max_gap_ticks, 1, one_tick)), PacketError::bad_tick_range);
  EXPECT_EQ(decode(one_run(1, 10, 0, one_tick)), PacketError::bad_tick_range);
  EXPECT_EQ(decode(one_run(1, 10, 257, one_tick)), PacketError::bad_tick_range);
  EXPECT_EQ(decode(one_run(1, 10, 2, one_tick)), PacketError::too_short);  // 1 tick of 2
  Bytes repeat_past;
  repeat_past.u8(5);
  EXPECT_EQ(decode(one_run(1, 10, 2, repeat_past)), PacketError::bad_field);
  EXPECT_EQ(decode(one_run(1, 10, 1, one_tick, 2)), PacketError::too_short);
  Bytes extra = one_run(1, 10, 1, one_tick);
  extra.u8(0);
  EXPECT_EQ(decode(extra), PacketError::trailing_bytes);
  Bytes no_field;
  no_field.u8(0x80);
  EXPECT_EQ(decode(one_run(1, 10, 1, no_field)), PacketError::bad_field);
  Bytes reserved;
  reserved.u8(0xc8).zeros(16);  // the pointer both exact and on the grid
  EXPECT_EQ(decode(one_run(1, 10, 1, reserved)), PacketError::bad_field);
  // Acknowledging more of the receiver's (slot 0) ticks than it has.
  Bytes future = inputs_header(11, 9, 0);
  EXPECT_EQ(decode(future), PacketError::bad_tick_range);
  Bytes wrong_players;
  wrong_players.header(3, 1, 0).u8(3).u32(0).u32(0).u32(0).u8(0);
  EXPECT_EQ(decode(wrong_players), PacketError::bad_field);
  // Not before the handshake, nor from a slot that is no one's.
  EXPECT_EQ(decode(inputs_header(0, 0, 0), net::DecodeContext{}), PacketError::unexpected);
  Bytes from_nobody;
  from_nobody.header(3, 5, 0).u8(2).u32(0).u32(0).u8(0);
  EXPECT_EQ(decode(from_nobody), PacketError::bad_slot);
  // The same player twice.
  Bytes twice = inputs_header(10, 9, 2);
  for (int i = 0; i < 2; ++i) twice.u8(1).u32(10).u16(1).u16(1).u8(0);
  EXPECT_EQ(decode(twice), PacketError::bad_field);
}

TEST(NetPacket, InputRangesRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Bytes push_nan;
  push_nan.u8(0x81).f64(nan).f64(0.0).u8(0);
  EXPECT_EQ(decode(one_run(1, 10, 1, push_nan)), PacketError::bad_input);
  Bytes pointer_inf;
  pointer_inf.u8(0x88).f64(0.0).f64(-inf);
  EXPECT_EQ(decode(one_run(1, 10, 1, pointer_inf)), PacketError::bad_input);
  Bytes axis_out;  // the levels: push (0, 0), axis 0 at 1.5
  axis_out.u8(0x81).f64(0.0).f64(0.0).u8(1).f64(1.5);
  EXPECT_EQ(decode(one_run(1, 10, 1, axis_out)), PacketError::bad_input);
  Bytes held_over_32_bits;  // a varint of 2^32
  held_over_32_bits.u8(0x82).u8(0x80).u8(0x80).u8(0x80).u8(0x80).u8(0x10);
  EXPECT_EQ(decode(one_run(1, 10, 1, held_over_32_bits)), PacketError::bad_input);
  Bytes edge_over_32_bits;
  edge_over_32_bits.u8(0x84).u8(0).u8(0x80).u8(0x80).u8(0x80).u8(0x80).u8(0x10);
  EXPECT_EQ(decode(one_run(1, 10, 1, edge_over_32_bits)), PacketError::bad_input);
  Bytes too_many_bodies;
  too_many_bodies.u8(0xa0).u8(17);
  EXPECT_EQ(decode(one_run(1, 10, 1, too_many_bodies)), PacketError::bad_input);
  // Kinds beyond the last (target_angle, 6) are refused; every kind up to it decodes.
  for (const int kind : {static_cast<int>(last_body_input_kind) + 1, 255}) {
    Bytes bad_kind;
    bad_kind.u8(0xa0).u8(1).u32(1).u32(0).u8(static_cast<std::uint8_t>(kind)).f64(1.0).f64(1.0);
    EXPECT_EQ(decode(one_run(1, 10, 1, bad_kind)), PacketError::bad_input) << kind;
  }
  net::Packet p;
  for (int kind = 0; kind <= static_cast<int>(last_body_input_kind); ++kind) {
    Bytes body_ok;
    body_ok.u8(0xa0).u8(1).u32(1).u32(0).u8(static_cast<std::uint8_t>(kind)).f64(1.0).f64(0.0);
    ASSERT_EQ(decode(one_run(1, 10, 1, body_ok), two_players(), p), PacketError::none) << kind;
    ASSERT_EQ(p.inputs.runs[0].deltas[0].fields.bodies.size(), 1u);
    EXPECT_EQ(p.inputs.runs[0].deltas[0].fields.bodies[0].kind, static_cast<BodyInputKind>(kind));
  }
  Bytes body_short;
  body_short.u8(0xa0).u8(1).u32(1).u32(0).u8(2).f64(1.0);
  EXPECT_EQ(decode(one_run(1, 10, 1, body_short)), PacketError::too_short);
}

TEST(NetPacket, StateHashAndDisconnect) {
  Bytes h;
  h.header(4, 1, 3).u8(1).u32(120).u64(0x0123456789abcdefull);
  net::Packet p;
  ASSERT_EQ(decode(h, two_players(), p), PacketError::none);
  EXPECT_EQ(p.hash.player, 1);
  EXPECT_EQ(p.hash.tick, 120u);
  EXPECT_EQ(p.hash.hash, 0x0123456789abcdefull);
  std::vector<std::uint8_t> encoded;
  net::encode_state_hash({.slot = 1, .sequence = 3}, p.hash, encoded);
  EXPECT_EQ(encoded, h.v);
  Bytes other;
  other.header(4, 1, 3).u8(2).u32(120).u64(0);
  EXPECT_EQ(decode(other), PacketError::bad_slot);
  EXPECT_EQ(decode(h, net::DecodeContext{}), PacketError::unexpected);
  Bytes d;
  d.header(5, 1, 0).u8(3);
  ASSERT_EQ(decode(d, {}, p), PacketError::none);
  EXPECT_EQ(p.disconnect.reason, net::DisconnectReason::desync);
  Bytes late;
  late.header(5, 1, 0).u8(6);
  ASSERT_EQ(decode(late, {}, p), PacketError::none);
  EXPECT_EQ(p.disconnect.reason, net::DisconnectReason::too_late);
  for (const std::uint8_t reason : {0, 7, 9}) {
    Bytes bad_reason;
    bad_reason.header(5, 1, 0).u8(reason);
    EXPECT_EQ(decode(bad_reason), PacketError::bad_field) << int(reason);
  }
}

// After a desync: a window's hashes, and a state body by body; hand-built bytes decode to them,
// the encoders write those bytes, and every bound is refused.
TEST(NetPacket, DesyncLocatingMessages) {
  Bytes th;
  th.header(6, 1, 4).u8(1).u32(61).u8(2).u64(11).u64(0xffffffffffffffffull);
  net::Packet p;
  ASSERT_EQ(decode(th, two_players(), p), PacketError::none);
  EXPECT_EQ(p.tick_hashes.first_tick, 61u);
  EXPECT_EQ(p.tick_hashes.hashes, (std::vector<std::uint64_t>{11, 0xffffffffffffffffull}));
  std::vector<std::uint8_t> encoded;
  net::encode_tick_hashes({.slot = 1, .sequence = 4}, p.tick_hashes, encoded);
  EXPECT_EQ(encoded, th.v);
  Bytes none, many, short_by_one;
  none.header(6, 1, 4).u8(1).u32(61).u8(0);
  EXPECT_EQ(decode(none), PacketError::bad_field);
  many.header(6, 1, 4).u8(1).u32(61).u8(129).zeros(129 * 8);
  EXPECT_EQ(decode(many), PacketError::bad_field);
  short_by_one.header(6, 1, 4).u8(1).u32(61).u8(2).u64(11);
  EXPECT_EQ(decode(short_by_one), PacketError::too_short);
  Bytes stranger;
  stranger.header(6, 1, 4).u8(5).u32(61).u8(1).u64(1);
  EXPECT_EQ(decode(stranger), PacketError::bad_slot);

  Bytes bs;
  bs.header(7, 0, 9).u8(0).u32(96).u32(20).u32(18).u8(2).u8(4 | 8).u64(77);
  for (int b = 0; b < 2; ++b) {
    bs.f64(1.0 + b).f64(-0.0).f64(3.5).f64(4.0).f64(0.0).f64(0.0).u32(0).u32(0);
  }
  ASSERT_EQ(decode(bs, two_players(), p), PacketError::none);
  const net::BodyStatesMessage& m = p.body_states;
  EXPECT_EQ(m.tick, 96u);
  EXPECT_EQ(m.body_count, 20u);
  EXPECT_EQ(m.first, 18u);
  EXPECT_TRUE(m.drawn);
  EXPECT_FALSE(m.reproduced);
  EXPECT_FALSE(m.rolling);
  ASSERT_EQ(m.bodies.size(), 2u);
  EXPECT_EQ(m.bodies[1].x, 2.0);
  EXPECT_TRUE(std::signbit(m.bodies[0].y));
  net::encode_body_states({.slot = 0, .sequence = 9}, m, encoded);
  EXPECT_EQ(encoded, bs.v);
  Bytes past_count, flag, over_limit;
  past_count.header(7, 0, 9).u8(0).u32(96).u32(19).u32(18).u8(2).u8(0).u64(0).zeros(2 * 56);
  EXPECT_EQ(decode(past_count), PacketError::bad_field);
  flag.header(7, 0, 9).u8(0).u32(96).u32(20).u32(0).u8(1).u8(16).u64(0).zeros(56);
  EXPECT_EQ(decode(flag), PacketError::bad_field);
  over_limit.header(7, 0, 9).u8(0).u32(96).u32(net::max_state_bodies + 1).u32(0).u8(1).u8(0);
  over_limit.u64(0).zeros(56);
  EXPECT_EQ(decode(over_limit), PacketError::bad_field);
  EXPECT_EQ(decode(bs, net::DecodeContext{}), PacketError::unexpected);
  EXPECT_THROW(net::encode_body_states({}, net::BodyStatesMessage{}, encoded),
               std::invalid_argument);
  EXPECT_THROW(net::encode_tick_hashes({}, net::TickHashesMessage{}, encoded),
               std::invalid_argument);
}

TEST(NetInputCodec, RoundTripsEveryFieldBitForBit) {
  std::vector<TickInput> ticks(250);
  for (std::size_t t = 0; t < ticks.size(); ++t) {
    TickInput& in = ticks[t];
    in.tick = 40 + t;
    if (t > 0) in = ticks[t - 1], in.tick = 40 + t;
    if (t % 50 == 7) in.push = {-0.0, 3.25 * static_cast<double>(t)};
    if (t % 70 == 3) in.held ^= button_action | button_pointer_primary;
    in.pressed = (t % 90 == 1) ? std::uint32_t{button_up} : 0u;
    if (t % 13 == 0) in.pointer = {std::nextafter(1.0, 2.0), -1e-300};
    if (t == 100) in.drag_body = {7, 2};
    if (t % 40 == 5) {
      in.bodies = {{{3, 1}, BodyInputKind::impulse, {1.0, -1.0}}};
    }
    if (t % 40 == 25) {  // the angular kinds: one number in x, bit for bit (-0.0 too)
      in.bodies = {{{3, 1}, BodyInputKind::torque, {5.0, 0.0}},
                   {{3, 1}, BodyInputKind::angular_impulse, {-1.0 / 3, 0.0}},
                   {{4, 2}, BodyInputKind::angular_velocity, {-0.0, 0.0}},
                   {{4, 2}, BodyInputKind::target_angle, {1e-300, 0.0}}};
    }
  }
  const TickInput prev{};
  std::vector<std::uint8_t> bytes;
  net::encode_inputs(ticks, prev, bytes);
  EXPECT_EQ(bytes.size(), net::encoded_size(ticks, prev));
  std::vector<net::InputDelta> deltas;
  std::size_t used = 0;
  ASSERT_EQ(net::decode_inputs(bytes, 250, deltas, used), PacketError::none);
  EXPECT_EQ(used, bytes.size());
  TickInput at = prev;
  std::size_t angular = 0;
  for (std::size_t t = 0; t < 250; ++t) {
    at = net::apply_delta(deltas[t], at, 40 + t);
    EXPECT_TRUE(net::same_input(at, ticks[t])) << t;
    EXPECT_EQ(std::signbit(at.push.x), std::signbit(ticks[t].push.x)) << t;
    EXPECT_EQ(at.bodies, ticks[t].bodies) << t;
    for (const BodyInput& b : at.bodies) angular += b.kind >= BodyInputKind::torque;
  }
  EXPECT_GT(angular, 0u);
}

TEST(NetInputCodec, EveryActionBitAndTheAxesRoundTripBitForBit) {
  std::vector<TickInput> ticks(40);
  for (std::size_t t = 0; t < ticks.size(); ++t) {
    TickInput& in = ticks[t];
    in.held = t < 20 ? 0x80000001u << (t % 2) : 0x7fu;
    in.pressed = t == 3 ? 0xffffffffu : 0u;
    in.released = t == 4 ? 0x80000000u : 0u;
    in.axes = {t * 0.025, t % 5 == 0 ? -0.0 : -1.0, 1.0 / 3.0, t == 7 ? 1e-300 : 0.0};
  }
  std::vector<std::uint8_t> bytes;
  net::encode_inputs(ticks, TickInput{}, bytes);
  EXPECT_EQ(bytes.size(), net::encoded_size(ticks, TickInput{}));
  std::vector<net::InputDelta> deltas;
  std::size_t used = 0;
  ASSERT_EQ(net::decode_inputs(bytes, 40, deltas, used), PacketError::none);
  TickInput at{};
  for (std::size_t t = 0; t < ticks.size(); ++t) {
    at = net::apply_delta(deltas[t], at, t);
    EXPECT_TRUE(net::same_input(at, ticks[t])) << t;
    EXPECT_EQ(at.held, ticks[t].held) << t;
    EXPECT_EQ(std::signbit(at.axes[1]), std::signbit(ticks[t].axes[1])) << t;
  }
  // An axis outside [-1, 1] is no input.
  TickInput bad{};
  bad.axes[0] = 1.5;
  EXPECT_EQ(net::check_input(bad), PacketError::bad_input);
  // A byte of axes naming an axis past max_axes: refused.
  Bytes items;
  items.u8(0x80 | net::field_push).f64(0.0).f64(0.0).u8(0x10).f64(0.5);
  ASSERT_EQ(net::decode_inputs(items.v, 1, deltas, used), PacketError::bad_input);
}

TEST(NetInputCodec, UnchangedTicksCostOneBytePer128) {
  std::vector<TickInput> ticks(1000);
  TickInput prev{};
  prev.held = button_left;
  prev.pointer = {1.0, 2.0};
  for (auto& t : ticks) t = prev;
  EXPECT_EQ(net::encoded_size(ticks, prev), 8u);  // ceil(1000 / 128)
  ticks[500].held = 0;  // a release and back: two changes of 2 bytes (mask, held as a varint)
  EXPECT_EQ(net::encoded_size(ticks, prev), 4u + 2u + 2u + 4u);
  std::vector<std::uint8_t> bytes;
  net::encode_inputs(std::span(ticks).first(256), prev, bytes);
  EXPECT_EQ(bytes, (std::vector<std::uint8_t>{127, 127}));
}

/// Bytes of one changed tick whose pointer is on the grid (0x80 | wire_pointer_grid, then two
/// zigzag varints).
std::size_t grid_pointer_tick_bytes(Vec2 p) {
  TickInput in{};
  in.pointer = p;
  return net::encoded_size({&in, 1}, TickInput{});
}

TEST(NetInputCodec, PointerOnTheGridGoesAsVarintsOfGridUnits) {
  // (0.5, -2.0) m = (512, -2048) grid units of 2^-10 m; zigzag 1024 and 4095.
  Bytes items;
  items.u8(0x80 | 0x40).u8(0x80).u8(0x08).u8(0xff).u8(0x1f);
  std::vector<net::InputDelta> deltas;
  std::size_t used = 0;
  ASSERT_EQ(net::decode_inputs(items.v, 1, deltas, used), PacketError::none);
  EXPECT_EQ(used, 5u);
  ASSERT_EQ(deltas.size(), 1u);
  EXPECT_EQ(deltas[0].mask, net::field_pointer);  // the wire bit is never seen past decoding
  EXPECT_EQ(deltas[0].fields.pointer.x, 0.5);
  EXPECT_EQ(deltas[0].fields.pointer.y, -2.0);
  TickInput in{};
  in.pointer = {0.5, -2.0};
  std::vector<std::uint8_t> bytes;
  net::encode_inputs({&in, 1}, TickInput{}, bytes);
  EXPECT_EQ(bytes, items.v);
  // Sizes: 1 + 1 + 1 for a grid unit or less each way; 1 + 16 off the grid, for -0.0 (a
  // varint has no negative zero) and beyond 2^40 units.
  EXPECT_EQ(grid_pointer_tick_bytes({0x1p-10, -0x1p-10}), 3u);
  EXPECT_EQ(grid_pointer_tick_bytes({20.0, -20.0}), 7u);  // 20480 units: 3-byte varints
  EXPECT_EQ(grid_pointer_tick_bytes({0x1p-11, 0.0}), 17u);
  EXPECT_EQ(grid_pointer_tick_bytes({-0.0, 1.0}), 17u);
  EXPECT_EQ(grid_pointer_tick_bytes({0x1p30, -0x1p30}), 13u);  // 2^40 units: 6 bytes each
  EXPECT_EQ(grid_pointer_tick_bytes({0x1p30 + 0x1p-10, 0.0}), 17u);
}

TEST(NetInputCodec, GridPointersRoundTripBitForBit) {
  // 10 x 10 pairs, each as it is and rounded: 200 ticks (a run holds at most 256).
  const double values[] = {0.0,    -0.0,    0x1p-10, -0x1p-10,         1.0 / 3.0,
                           0x1p30, -0x1p30, 1e300,   0x1p30 + 0x1p-10, -123.4560546875};
  std::vector<TickInput> ticks;
  for (double x : values) {
    for (double y : values) {
      TickInput in{};
      in.tick = ticks.size();
      in.pointer = {x, y};
      ticks.push_back(in);
      in.pointer = net::round_to_pointer_grid({x, y});
      ticks.push_back(in);
    }
  }
  const TickInput prev{};
  std::vector<std::uint8_t> bytes;
  net::encode_inputs(ticks, prev, bytes);
  EXPECT_EQ(bytes.size(), net::encoded_size(ticks, prev));
  std::vector<net::InputDelta> deltas;
  std::size_t used = 0;
  ASSERT_EQ(net::decode_inputs(bytes, static_cast<std::uint32_t>(ticks.size()), deltas, used),
            PacketError::none);
  EXPECT_EQ(used, bytes.size());
  TickInput at = prev;
  for (std::size_t t = 0; t < ticks.size(); ++t) {
    at = net::apply_delta(deltas[t], at, t);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(at.pointer.x),
              std::bit_cast<std::uint64_t>(ticks[t].pointer.x))
        << t;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(at.pointer.y),
              std::bit_cast<std::uint64_t>(ticks[t].pointer.y))
        << t;
  }
}

TEST(NetInputCodec, RoundToPointerGrid) {
  const auto round = [](double v) { return net::round_to_pointer_grid({v, 0.0}).x; };
  EXPECT_EQ(round(1.0), 1.0);
  EXPECT_EQ(round(0.3), 307.0 / 1024.0);    // 307.2 units
  EXPECT_EQ(round(-0.3), -307.0 / 1024.0);  // symmetric
  EXPECT_EQ(round(0x1p-11), 0.0);           // half a unit: ties to even
  EXPECT_EQ(round(3 * 0x1p-11), 2 * 0x1p-10);
  EXPECT_FALSE(std::signbit(round(-0.0)));
  EXPECT_FALSE(std::signbit(round(-0x1p-12)));
  EXPECT_EQ(round(1e300), 1e300);  // beyond the grid's range: as it is
  EXPECT_TRUE(std::isnan(round(std::numeric_limits<double>::quiet_NaN())));
  // Every rounded value goes compact.
  for (double v = -50.0; v < 50.0; v += 0.0137) {
    EXPECT_LE(grid_pointer_tick_bytes(net::round_to_pointer_grid({v, -v})), 7u) << v;
  }
}

TEST(NetInputCodec, GridPointerRefusals) {
  std::vector<net::InputDelta> deltas;
  std::size_t used = 0;
  Bytes beyond;  // 2^40 + 1 units: zigzag 2^41 + 2
  beyond.u8(0x80 | 0x40).u8(0x82).u8(0x80).u8(0x80).u8(0x80).u8(0x80).u8(0x40).u8(0x00);
  EXPECT_EQ(net::decode_inputs(beyond.v, 1, deltas, used), PacketError::bad_input);
  Bytes overlong;  // a varint of 10 bytes
  overlong.u8(0x80 | 0x40).zeros(0);
  for (int i = 0; i < 9; ++i) overlong.u8(0x80);
  overlong.u8(0x00).u8(0x00);
  EXPECT_NE(net::decode_inputs(overlong.v, 1, deltas, used), PacketError::none);
  Bytes cut;  // the second varint missing
  cut.u8(0x80 | 0x40).u8(0x02);
  EXPECT_EQ(net::decode_inputs(cut.v, 1, deltas, used), PacketError::too_short);
}

TEST(NetInputCodec, EncoderRefusesWhatTheDecoderWould) {
  TickInput bad{};
  bad.axes[2] = std::numeric_limits<double>::infinity();  // a game's action bits all go
  std::vector<std::uint8_t> bytes;
  EXPECT_THROW(net::encode_inputs({&bad, 1}, TickInput{}, bytes), std::invalid_argument);
  EXPECT_EQ(net::check_input(bad), PacketError::bad_input);
  TickInput turn{};
  turn.bodies = {{{1, 1}, BodyInputKind::target_angle, {0.5, 0.0}}};
  EXPECT_EQ(net::check_input(turn), PacketError::none);
  turn.bodies[0].kind = static_cast<BodyInputKind>(static_cast<int>(last_body_input_kind) + 1);
  EXPECT_EQ(net::check_input(turn), PacketError::bad_input);
  EXPECT_THROW(net::encode_inputs({&turn, 1}, TickInput{}, bytes), std::invalid_argument);
  turn.bodies[0] = {{1, 1}, BodyInputKind::torque, {std::numeric_limits<double>::quiet_NaN(), 0.0}};
  EXPECT_EQ(net::check_input(turn), PacketError::bad_input);
  // Joint inputs are not carried (a match's merge derives them on every peer): refused, with
  // the reason, rather than dropped into a desync.
  TickInput motor{};
  motor.joints = {{{1, 1}, JointInputKind::motor_speed, {1.0, 0.0}}};
  EXPECT_EQ(net::check_input(motor), PacketError::bad_input);
  try {
    net::encode_inputs({&motor, 1}, TickInput{}, bytes);
    ADD_FAILURE() << "a joint input was encoded";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint inputs are not sent"), std::string::npos);
  }
}

/// The fuzz target's seeds (tests/fuzz/packet_corpus) are packets one of its receivers takes.
TEST(NetPacket, FuzzSeedsDecode) {
  net::DecodeContext eight;
  eight.players = 8;
  eight.own_slot = 3;
  eight.next_needed = {0, 1, 2, 300, 4, 5, 6, 1000};
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(FIXSTEP_SOURCE_DIR) / "tests/fuzz/packet_corpus")) {
    std::ifstream in(entry.path(), std::ios::binary);
    Bytes b;
    b.v.assign(std::istreambuf_iterator<char>(in), {});
    net::Packet p;
    const bool any = decode(b, {}, p) == PacketError::none ||
                     decode(b, two_players(), p) == PacketError::none ||
                     decode(b, eight, p) == PacketError::none;
    EXPECT_TRUE(any) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 7);
}

}  // namespace
}  // namespace fixstep::net_test
