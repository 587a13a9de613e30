// fixstep::net's costs (docs/NETWORK.md, docs/PERFORMANCE.md "Networking"), in four tables:
//  1. bandwidth per player at 60 ticks/s: a two-player lockstep match on billiards.toml paced
//     at 60 frames/s through the link conditioner (round trip 0, 50, 150 ms; the input delay
//     above the round trip, so it never stalls), for each send interval and play (bench/
//     net_runs.hpp: idle, typical, busy): the joiner's bytes on the wire (UDP payloads with
//     ENet's headers, acknowledgements and pings, plus 28 bytes of IPv4 and UDP headers per
//     datagram; ENet's host counters) from tick 60 to the end, over the wall time they took;
//  1b. the same with 8 players (lockstep, the default send interval, round trip 0 and 50 ms):
//     the first joiner's upload (its own input, to the host) and download (the others');
//  2. lockstep stalls and rollback re-simulation against one-way latency (0, 50, 150, 500 ms,
//     2 s) and loss (0, 5, 25 %): matches paced at 200 ticks/s with the latency scaled by
//     60/200, so a round trip is as many ticks as at 60 ticks/s (ENet's own timers and the
//     resend margin are not scaled; the send interval is); stall share of the match's wall time,
//     ticks per second at 60 ticks/s, rollbacks and re-simulated ticks;
//  3. the longest rollback that fits a 16.7 ms frame: restore + re-simulation on the ball pit
//     (assets/scenes/ball_pit.toml, 1000 discs, settled 400 ticks) and the shipped games'
//     levels (airhockey, slingshot, peggle), median of repeats, less the frame's own two ticks (the
//     confirmed world's and the shown world's).
// Tables 1, 1b and 2 run all their matches side by side from one thread. Byte counts do not depend
// on the machine; the times do: time on an idle machine.
//
//   build/bench/bin/bench_net [--quick] [--only bandwidth|players|latency|rollback]
//                             [--report FILE]
//     (--quick: shorter matches, about a minute; --only: one table)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "net_runs.hpp"
#ifdef FIXSTEP_BENCH_GAMES
#include "airhockey/game.hpp"
#include "peggle/game.hpp"
#include "slingshot/game.hpp"
#endif

using namespace fixstep;
using bench::NetCase;
using bench::NetResult;
using bench::Play;

namespace {

std::string out;  // the report
template <typename... Args>
void emit(fmt::format_string<Args...> f, Args&&... args) {
  const std::string line = fmt::format(f, std::forward<Args>(args)...);
  out += line;
  std::fputs(line.c_str(), stdout);
  std::fflush(stdout);
}

NetCase base_case(std::uint64_t ticks) {
  NetCase c;
  const Scene& scene = []() -> const Scene& {
    static const Scene s = load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/billiards.toml");
    return s;
  }();
  c.settings.match_ticks = ticks;
  c.settings.peer_timeout_ms = 20000;
  c.settings.handshake_timeout_ms = 20000;
  c.settings.adapt_to_round_trip = false;  // the delays and windows each table gives
  c.settings.scene_name = scene.file;
  c.settings.scene_text = scene.text;
  return c;
}

/// A lockstep bandwidth case: `players` playing `play` through a link of round trip `rtt` ms,
/// sending every `interval` ms, with an input delay above the round trip and a send interval
/// each way (so that no peer ever waits for input).
NetCase bandwidth_case(std::uint64_t ticks, std::uint8_t players, std::uint32_t interval,
                       double rtt, Play play) {
  NetCase c = base_case(ticks);
  c.settings.players = players;
  c.settings.send_interval_ms = interval;
  c.settings.input_delay = static_cast<std::uint16_t>(3 + (rtt + 2.0 * interval) / (1000.0 / 60.0));
  c.link.latency_ms = rtt / 2.0;
  c.link.seed = 7;
  c.play = play;
  return c;
}

void bandwidth(bool quick) {
  const std::uint64_t ticks = quick ? 240 : 900;
  const std::vector<std::uint32_t> intervals = {0, 17, 33, 50, 67};
  const std::vector<double> rtts = {0.0, 50.0, 150.0};
  const std::vector<Play> plays = {Play::idle, Play::typical, Play::busy};
  std::vector<NetCase> cases;
  for (std::uint32_t interval : intervals) {
    for (double rtt : rtts) {
      for (Play play : plays) cases.push_back(bandwidth_case(ticks, 2, interval, rtt, play));
    }
  }
  const std::vector<NetResult> results = bench::run_cases(cases, quick ? 30000 : 60000);
  emit("\n### Bandwidth per player at 60 ticks/s (two players, lockstep)\n\n");
  emit(
      "default send interval: {} ms. kbit/s: the joiner's upload on the wire (IPv4 + UDP + ENet "
      "+ fixstep bytes); received is the same link's other direction.\n\n",
      net::MatchSettings{}.send_interval_ms);
  emit(
      "| send interval | RTT | play | input delay | kbit/s sent | kbit/s received | datagrams/s | "
      "bytes/datagram | fixstep bytes/tick | ticks/s | ok |\n");
  emit("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const NetCase& c = cases[i];
    const NetResult& r = results[i];
    const double s = std::max(r.seconds, 1e-9);
    emit(
        "| {} ms | {:.0f} ms | {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {} "
        "|\n",
        c.settings.send_interval_ms, 2.0 * c.link.latency_ms, bench::play_name(c.play),
        c.settings.input_delay, 8.0 * r.wire_sent / s / 1000.0, 8.0 * r.wire_received / s / 1000.0,
        r.datagrams / s, r.datagrams ? double(r.wire_sent) / r.datagrams : 0.0,
        r.ticks ? double(r.payload_sent) / r.ticks : 0.0, r.ticks / s,
        r.finished && r.same_recording ? "yes" : "NO: " + r.error);
  }
}

void eight_players(bool quick) {
  const std::uint64_t ticks = quick ? 240 : 900;
  const std::vector<double> rtts = {0.0, 50.0};
  const std::vector<Play> plays = {Play::idle, Play::typical, Play::busy};
  const std::uint32_t interval = net::MatchSettings{}.send_interval_ms;
  std::vector<NetCase> cases;
  for (double rtt : rtts) {
    for (Play play : plays) cases.push_back(bandwidth_case(ticks, 8, interval, rtt, play));
  }
  const std::vector<NetResult> results = bench::run_cases(cases, quick ? 30000 : 60000);
  emit(
      "\n### Bandwidth per player with 8 players at 60 ticks/s (lockstep, default send "
      "interval)\n\n");
  emit(
      "send interval {} ms; every player plays the same way. A joiner sends only its own input, "
      "to the host (a star); it receives the other seven players' from the host. kbit/s: the "
      "first joiner's, on the wire, as above.\n\n",
      interval);
  emit(
      "| RTT | play | input delay | kbit/s sent | kbit/s received | datagrams/s | fixstep "
      "bytes/tick "
      "sent | ticks/s | ok |\n");
  emit("|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const NetCase& c = cases[i];
    const NetResult& r = results[i];
    const double s = std::max(r.seconds, 1e-9);
    emit("| {:.0f} ms | {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {} |\n",
         2.0 * c.link.latency_ms, bench::play_name(c.play), c.settings.input_delay,
         8.0 * r.wire_sent / s / 1000.0, 8.0 * r.wire_received / s / 1000.0, r.datagrams / s,
         r.ticks ? double(r.payload_sent) / r.ticks : 0.0, r.ticks / s,
         r.finished && r.same_recording ? "yes" : "NO: " + r.error);
  }
}

void latency(bool quick) {
  const std::uint64_t ticks = quick ? 60 : 240;
  constexpr double pace_hz = 200.0, scale = 60.0 / pace_hz;
  const std::vector<double> latencies = {0.0, 50.0, 150.0, 500.0, 2000.0};
  const std::vector<double> losses = {0.0, 0.05, 0.25};
  std::vector<NetCase> cases;
  for (int rollback = 0; rollback < 2; ++rollback) {
    for (double l : latencies) {
      for (double loss : losses) {
        NetCase c = base_case(ticks);
        c.settings.input_delay = rollback ? 2 : 6;
        c.settings.max_rollback = rollback ? 16 : 0;
        // The send interval is time too: as many ticks as the default's at 60 ticks/s.
        c.settings.send_interval_ms =
            static_cast<std::uint32_t>(net::MatchSettings{}.send_interval_ms * scale);
        c.frame_ms = 1000.0 / pace_hz;
        c.measure_from = 10;  // after the handshake
        c.link.latency_ms = l * scale;
        c.link.loss = loss;
        c.link.seed = 11;
        c.play = Play::typical;
        cases.push_back(c);
      }
    }
  }
  const std::vector<NetResult> results = bench::run_cases(cases, quick ? 90000 : 240000);
  emit("\n### Stalls and rollbacks against latency and loss ({} ticks, typical play)\n\n", ticks);
  emit(
      "lockstep: input delay 6 ticks; rollback: input delay 2, max_rollback 16. Paced at {:.0f} "
      "ticks/s with the latency scaled by {:.2f}; times below are scaled back to 60 ticks/s. "
      "Send interval scaled too. Counted from tick 10 (after the handshake); stalled: the "
      "share of the match's wall time a lockstep peer waited; a rollback peer counts stalls "
      "(max_rollback ahead) and waits (time sync) per advance(). The joiner's counts.\n\n",
      pace_hz, scale);
  emit(
      "| kind | latency (one way) | loss | ticks/s (of 60) | stalled (lockstep) | stalls / waits | "
      "rollbacks | re-simulated ticks/s | longest rollback | ok |\n");
  emit("|---|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const NetCase& c = cases[i];
    const NetResult& r = results[i];
    const net::MatchStats& j = r.joiner;
    const double played_s = r.seconds / scale;  // from tick 10 on, at 60 ticks/s
    const double rate = r.ticks / std::max(played_s, 1e-9);
    const double stalled = j.stalled_ms / std::max(r.elapsed_ms, 1e-9);
    emit("| {} | {:.0f} ms | {:.0f} % | {:.1f} | {:.0f} % | {} / {} | {} | {:.1f} | {} | {} |\n",
         c.settings.max_rollback ? "rollback" : "lockstep", c.link.latency_ms / scale,
         100.0 * c.link.loss, rate, 100.0 * stalled, j.stalls, j.waits, j.rollbacks,
         j.rolled_back_ticks / std::max(played_s, 1e-9), j.max_rolled_back,
         r.finished && r.same_recording ? "yes" : "NO: " + r.error);
  }
}

struct Level {
  std::string name;
  WorldDef def;
  int settle;  ///< ticks stepped before the snapshot
};

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void longest_rollback(bool quick) {
  std::vector<Level> levels;
  levels.push_back({"ball_pit.toml (1000 discs)",
                    load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/ball_pit.toml").def, 400});
#ifdef FIXSTEP_BENCH_GAMES
  levels.push_back({"airhockey (the two-player demo)", airhockey::make_level(), 60});
  levels.push_back({"slingshot", slingshot::make_level(), 60});
  levels.push_back({"peggle", peggle::make_level(), 60});
#endif
  const int resim = 30, reps = quick ? 5 : 21;
  emit("\n### The longest rollback that fits a 16.7 ms frame\n\n");
  emit(
      "restore + {} ticks re-simulated, median of {}. A rollback peer's frame: a restore, the "
      "ticks re-simulated, the frame's own tick, and a restore that confirms it (the confirmed "
      "world takes the shown world's state: MatchStats::confirmed_from_shown); fits: (16.7 ms - "
      "2 restores) / tick - 1. A frame of 8: that frame measured whole, 8 ticks rolled back, "
      "with the snapshot the peer saves before each tick.\n\n",
      resim, reps);
  emit(
      "| level | bodies | tick (ms) | restore (ms) | re-simulation (ticks/s) | longest rollback "
      "(ticks) | a frame of 8 (ms) |\n|---|---|---|---|---|---|---|\n");
  for (const Level& level : levels) {
    World world(level.def);
    for (int t = 0; t < level.settle; ++t) world.step(TickInput{world.tick()});
    WorldSnapshot snap;
    world.save(snap);
    std::vector<double> restores, ticks, frames;
    World confirmed(level.def);
    WorldSnapshot shown_state;
    std::vector<WorldSnapshot> frame_states(9);
    for (int k = 0; k < reps; ++k) {
      auto t0 = std::chrono::steady_clock::now();
      world.restore(snap);
      restores.push_back(ms_since(t0));
      t0 = std::chrono::steady_clock::now();
      for (int t = 0; t < resim; ++t) world.step(TickInput{world.tick()});
      ticks.push_back(ms_since(t0) / resim);
      // A frame of 8: restore, 8 re-simulated ticks and the frame's own, each after a snapshot
      // of its start (a rollback peer keeps one per shown tick), the confirmed world's restore
      // from the shown world's state.
      t0 = std::chrono::steady_clock::now();
      world.restore(snap);
      for (int t = 0; t < 9; ++t) {
        world.save(frame_states[static_cast<std::size_t>(t)]);
        world.step(TickInput{world.tick()});
      }
      world.save(shown_state);
      confirmed.restore(shown_state);
      frames.push_back(ms_since(t0));
    }
    std::sort(restores.begin(), restores.end());
    std::sort(ticks.begin(), ticks.end());
    std::sort(frames.begin(), frames.end());
    const double restore = restores[restores.size() / 2], tick = ticks[ticks.size() / 2];
    const double fits = std::max(0.0, std::floor((1000.0 / 60.0 - 2.0 * restore) / tick) - 1.0);
    emit("| {} | {} | {:.3f} | {:.3f} | {:.0f} | {:.0f} | {:.2f} |\n", level.name,
         world.bodies().size(), tick, restore, 1000.0 / tick, fits, frames[frames.size() / 2]);
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string report, only;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--report" && i + 1 < argc) {
      report = argv[++i];
    } else if (a == "--only" && i + 1 < argc &&
               (std::string_view(argv[i + 1]) == "bandwidth" ||
                std::string_view(argv[i + 1]) == "players" ||
                std::string_view(argv[i + 1]) == "latency" ||
                std::string_view(argv[i + 1]) == "rollback")) {
      only = argv[++i];
    } else {
      std::fprintf(stderr,
                   "bench_net: unknown option `%s` or value (usage: bench_net [--quick] [--only "
                   "bandwidth|players|latency|rollback] [--report FILE])\n",
                   argv[i]);
      return 2;
    }
  }
  emit("## Networking (bench_net{})\n", quick ? " --quick" : "");
  if (only.empty() || only == "bandwidth") bandwidth(quick);
  if (only.empty() || only == "players") eight_players(quick);
  if (only.empty() || only == "latency") latency(quick);
  if (only.empty() || only == "rollback") longest_rollback(quick);
  if (!report.empty()) {
    std::ofstream f(report);
    f << out;
    if (!f) {
      std::fprintf(stderr, "bench_net: cannot write `%s`\n", report.c_str());
      return 1;
    }
  }
  return 0;
}
