// libFuzzer target: arbitrary bytes as a fixstep::net packet, decoded by a 2-player and an
// 8-player receiver and by one before its handshake. A clean refusal is a PacketError; a
// packet that decodes must encode back to bytes that decode to the same message, and its input
// runs must apply (apply_delta) to inputs the network accepts (check_input). Anything else, a
// crash or a sanitizer report is a finding. Built with the asan and fuzz presets; run as in
// docs/ROBUSTNESS.md, "Fuzzing".
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fixstep/core/input.hpp>
#include <fixstep/net/net_input_codec.hpp>
#include <fixstep/net/net_packet.hpp>
#include <span>
#include <vector>

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_packet: FINDING: %s\n", what);
  std::abort();
}

using namespace fixstep;

/// The run's inputs applied from an empty input (the receiver's base, here).
std::vector<TickInput> applied(const net::InputRun& run) {
  std::vector<TickInput> out;
  TickInput prev{};
  for (std::size_t i = 0; i < run.deltas.size(); ++i) {
    prev = net::apply_delta(run.deltas[i], prev, run.first_tick + i);
    if (net::check_input(prev) != net::PacketError::none) finding("a decoded input is refused");
    out.push_back(prev);
  }
  return out;
}

void reencode(const net::Packet& p, const net::DecodeContext& ctx) {
  std::vector<std::uint8_t> bytes;
  const net::Header& h = p.header;
  switch (h.kind) {
    case net::MessageKind::handshake_request:
      net::encode_handshake_request(h, p.request, bytes);
      break;
    case net::MessageKind::handshake_accept:
      net::encode_handshake_accept(h, p.accept, bytes);
      break;
    case net::MessageKind::state_hash:
      net::encode_state_hash(h, p.hash, bytes);
      break;
    case net::MessageKind::disconnect:
      net::encode_disconnect(h, p.disconnect, bytes);
      break;
    case net::MessageKind::tick_hashes:
      net::encode_tick_hashes(h, p.tick_hashes, bytes);
      break;
    case net::MessageKind::body_states:
      net::encode_body_states(h, p.body_states, bytes);
      break;
    case net::MessageKind::inputs: {
      std::vector<std::vector<TickInput>> inputs;
      for (const net::InputRun& run : p.inputs.runs) inputs.push_back(applied(run));
      std::vector<net::RunToSend> runs;
      const TickInput empty{};
      for (std::size_t i = 0; i < inputs.size(); ++i) {
        runs.push_back({p.inputs.runs[i].player, inputs[i], &empty});
      }
      if (net::inputs_packet_size(ctx.players, runs) > net::max_packet_bytes) {
        return;  // the sender's deltas were shorter than the encoder's minimal ones
      }
      net::encode_inputs_message(h, ctx.players, p.inputs.next_needed, runs, bytes);
      net::Packet again;
      if (net::decode_packet(bytes, ctx, again) != net::PacketError::none) {
        finding("an inputs message re-encoded does not decode");
      }
      for (std::size_t i = 0; i < inputs.size(); ++i) {
        const std::vector<TickInput> back = applied(again.inputs.runs.at(i));
        for (std::size_t t = 0; t < back.size(); ++t) {
          if (!net::same_input(back[t], inputs[i][t])) finding("an input changed on re-encoding");
        }
      }
      return;
    }
  }
  net::Packet again;
  if (net::decode_packet(bytes, ctx, again) != net::PacketError::none) {
    finding("a message re-encoded does not decode");
  }
  if (again.header.sequence != h.sequence || again.header.slot != h.slot ||
      again.hash.hash != p.hash.hash || again.accept.definition_hash != p.accept.definition_hash ||
      again.request.nonce != p.request.nonce || again.tick_hashes.hashes != p.tick_hashes.hashes ||
      again.body_states.bodies.size() != p.body_states.bodies.size() ||
      again.body_states.random_state != p.body_states.random_state ||
      again.body_states.reproduced != p.body_states.reproduced) {
    finding("a message re-encoded decodes to another");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  net::DecodeContext contexts[3];
  contexts[1].players = 2;
  contexts[1].own_slot = 0;
  contexts[1].next_needed = {10, 10};
  contexts[2].players = 8;
  contexts[2].own_slot = 3;
  contexts[2].next_needed = {0, 1, 2, 300, 4, 5, 6, 1000};
  for (const net::DecodeContext& ctx : contexts) {
    net::Packet p;
    if (net::decode_packet(bytes, ctx, p) == net::PacketError::none) reencode(p, ctx);
  }
  return 0;
}
