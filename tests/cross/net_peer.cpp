// One peer of a scripted two-player lockstep match over loopback, for the cross-architecture
// match (.ci/cross: an x86-64 host and an aarch64 joiner under qemu-aarch64, and the other way
// round): both play a disc scene with scripted inputs per slot (impulses on the player's own
// disc, the pointer moving, a button held in spells), paced at 200 ticks/s, and print
//   net_peer: slot S finished N ticks, state hash HHHHHHHHHHHHHHHH
// and write the recording; the two peers' lines' hashes and their recordings must be equal.
//
//   net_peer --host PORT [options]        listens on 127.0.0.1:PORT (player 0)
//   net_peer --join PORT --token T [options]  joins the match at 127.0.0.1:PORT (player 1)
//   options: --token T (the match's token, 32 hex digits: a host without one makes one and
//            prints "net_peer: token T"; a joiner must give the host's)
//            --scene FILE (a scene file; default billiards.toml of the source tree)
//            --ticks N (1 .. 100000, default 600)  --record FILE  --deadline-s S (1 .. 3600,
//            default 60: the match must finish within it)
// Exit status: 0 finished; 1 failed, desynced or past the deadline (the reason on stderr);
// 2 a bad command line or scene (the flag or the scene's file, line and key on stderr).
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/standard_output.hpp"
#include "fixstep/net/match_peer.hpp"
#include "fixstep/net/net_gate.hpp"
#include "fixstep/scene/scene.hpp"

using namespace fixstep;

namespace {

struct Options {
  bool host = false;
  std::uint16_t port = 0;
  std::string scene = FIXSTEP_SOURCE_DIR "/assets/scenes/billiards.toml";
  std::uint64_t ticks = 600;
  std::string record;
  std::string token;
  double deadline_s = 60.0;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::uint64_t number(std::string_view flag, const std::string& text, std::uint64_t lo,
                     std::uint64_t hi) {
  std::size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || text[0] == '-' || v < lo || v > hi) {
    throw UsageError(fmt::format("{}: `{}` is not a whole number in {} .. {}", flag, text, lo, hi));
  }
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  bool role = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view flag = argv[i];
    if (i + 1 >= argc) throw UsageError(fmt::format("{}: a value is missing", flag));
    const std::string value = argv[++i];
    if (flag == "--host" || flag == "--join") {
      if (role) throw UsageError("give one of --host and --join, once");
      role = true;
      o.host = flag == "--host";
      o.port = static_cast<std::uint16_t>(number(flag, value, 1, 65535));
    } else if (flag == "--scene") {
      o.scene = value;
    } else if (flag == "--ticks") {
      o.ticks = number(flag, value, 1, 100000);
    } else if (flag == "--record") {
      o.record = value;
    } else if (flag == "--token") {
      if (!net::parse_token(value)) {
        throw UsageError(fmt::format("--token: `{}` is not 32 hexadecimal digits", value));
      }
      o.token = value;
    } else if (flag == "--deadline-s") {
      o.deadline_s = static_cast<double>(number(flag, value, 1, 3600));
    } else {
      throw UsageError(fmt::format("unknown option `{}`", flag));
    }
  }
  if (!role) throw UsageError("give --host PORT or --join PORT");
  if (!o.host && o.token.empty()) {
    throw UsageError("--join needs --token T (the 32 hexadecimal digits the host printed)");
  }
  return o;
}

/// Player `slot`'s input of `tick`: an impulse on its own disc every 25 ticks, the pointer
/// moving every tick, the left button held in spells of 40 ticks (pressed and released too).
TickInput scripted(const World& world, std::uint8_t slot, std::uint64_t tick) {
  TickInput in;
  const auto bodies = world.bodies();
  if (tick % 25 == slot * 7u % 25u && !bodies.empty()) {
    const double s = 1.0 + slot;
    in.bodies.push_back({bodies[slot % bodies.size()],
                         BodyInputKind::impulse,
                         {0.002 * s, -0.001 * s * static_cast<double>(tick % 3)}});
  }
  auto held = [&](std::uint64_t t) { return ((t / 40) + slot) % 3 == 0 ? button_left : 0u; };
  in.held = held(tick);
  const std::uint32_t before = tick > 0 ? held(tick - 1) : 0u;
  in.pressed = in.held & ~before;
  in.released = before & ~in.held;
  in.pointer = {0.1 * slot + 0.001 * static_cast<double>(tick),
                0.02 * static_cast<double>(tick % 50)};
  return in;
}

bool done(net::MatchState s) {
  return s != net::MatchState::connecting && s != net::MatchState::playing;
}

int play(const Options& o) {
  const Scene scene = load_scene(o.scene);
  net::MatchSettings s;
  s.players = 2;
  s.input_delay = 8;
  s.adapt_to_round_trip = false;  // both peers at the delay given
  s.hash_every = 30;
  s.match_ticks = o.ticks;
  s.peer_timeout_ms = 10000;  // an emulated peer starts slowly
  s.handshake_timeout_ms = 10000;
  s.scene_name = scene.file;
  s.scene_text = scene.text;
  s.token = o.token;
  const WorldDef def = scene.def;
  net::MatchPeer peer = o.host ? net::MatchPeer::host(def, s, {"127.0.0.1", o.port})
                               : net::MatchPeer::join(def, s, {"127.0.0.1", o.port});
  if (o.host && o.token.empty()) {
    std::printf("net_peer: token %s\n", peer.token().c_str());
    std::fflush(stdout);
  }
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const auto deadline = start + std::chrono::duration_cast<clock::duration>(
                                    std::chrono::duration<double>(o.deadline_s));
  auto next_frame = start;
  while (!done(peer.state()) && clock::now() < deadline) {
    peer.poll(1);
    if (clock::now() < next_frame) continue;
    next_frame += std::chrono::milliseconds(5);  // 200 ticks/s
    if (peer.wants_input())
      peer.add_input(scripted(peer.world(), peer.slot(), peer.next_input_tick()));
    (void)peer.advance();
  }
  // The other peer may still need our last inputs and hashes: serve it a while.
  const auto linger = clock::now() + std::chrono::milliseconds(1500);
  while (peer.state() == net::MatchState::finished && clock::now() < linger) peer.poll(5);
  if (peer.state() != net::MatchState::finished) {
    const std::string why = done(peer.state())
                                ? peer.error()
                                : fmt::format("not finished within {} s (at tick {})", o.deadline_s,
                                              peer.world().tick());
    std::fprintf(stderr, "net_peer: %s\n", why.c_str());
    peer.leave();  // the other peer stops at once, not after its timeout
    return 1;
  }
  const Recording rec = peer.recording();
  if (!o.record.empty()) write_recording(o.record, rec);
  fmt::print("net_peer: slot {} finished {} ticks, state hash {:016x} ({} hashes compared)\n",
             peer.slot(), peer.world().tick(), peer.world().state_hash(),
             peer.stats().hashes_compared);
  peer.leave();
  return 0;
}

int run_peer(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "net_peer: %s\n", e.what());
    return 2;
  }
  try {
    return play(o);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "net_peer: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "net_peer: %s\n", e.what());
    return 1;
  }
}
}  // namespace

int main(int argc, char** argv) {
  // Its result line is what .ci/cross compares: a closed or full standard output is an error.
  return with_results_on_standard_output("net_peer", [&] { return run_peer(argc, argv); });
}
