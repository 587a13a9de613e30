// bench_net's matches: scripted plays, and many matches (host, link conditioner, joiners: the
// settings' players - 1) run side by side from one thread, each paced at its own frame rate,
// with the first joiner's byte counts taken between a start tick and the end.
#pragma once

#include <chrono>
#include <cstdint>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/net/link_conditioner.hpp>
#include <fixstep/net/match_peer.hpp>
#include <fixstep/scene/scene.hpp>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace fixstep::bench {

/// What a player does each tick.
enum class Play : std::uint8_t {
  idle,     ///< nothing: every tick's input empty
  typical,  ///< a click (left button) of 6 ticks every 20; the pointer moving half the time
            ///< (30 ticks of every 60, a drag); an impulse on the player's disc every 60 ticks
  busy,     ///< the button toggled every 6 ticks; the pointer moving every tick
};

inline const char* play_name(Play p) {
  return p == Play::idle ? "idle" : p == Play::typical ? "typical" : "busy";
}

/// Player `slot`'s input of `tick` in `play`, with pressed and released from the held bits.
inline TickInput play_input(Play play, const World& world, std::uint8_t slot, std::uint64_t tick) {
  TickInput in;
  if (play == Play::idle) return in;
  auto held = [&](std::uint64_t t) -> std::uint32_t {
    const bool down = play == Play::typical ? (t + slot * 7) % 20 < 6 : (t / 6) % 2 == 1;
    return down ? std::uint32_t{button_left} : 0u;
  };
  in.held = held(tick);
  const std::uint32_t before = tick > 0 ? held(tick - 1) : 0u;
  in.pressed = in.held & ~before;
  in.released = before & ~in.held;
  // The pointer, in metres: moving (a new value every tick) or kept.
  const bool moving = play == Play::busy || (tick + slot * 13) % 60 < 30;
  const std::uint64_t step = moving ? tick : (tick / 60) * 60;
  in.pointer = {0.5 + 0.013 * static_cast<double>(step % 97),
                -0.2 + 0.007 * static_cast<double>(step % 61)};
  const auto bodies = world.bodies();
  if (play == Play::typical && tick % 60 == slot * 11u % 60u && !bodies.empty()) {
    in.bodies.push_back({bodies[slot % bodies.size()], BodyInputKind::impulse, {0.003, -0.001}});
  }
  return in;
}

/// One match to run.
struct NetCase {
  net::MatchSettings settings;  ///< both peers' (match_ticks set)
  net::LinkSettings link;       ///< the conditioner between them, each direction
  Play play = Play::idle;
  double frame_ms = 1000.0 / 60.0;  ///< one input and one advance() per frame
  std::uint64_t measure_from = 60;  ///< the counts are taken from this confirmed tick on
};

/// What a match gave: the (first) joiner's counts between measure_from and the end, and the
/// host's and that joiner's final stats.
struct NetResult {
  bool finished = false;
  std::string error;
  bool same_recording = false;
  std::uint64_t ticks = 0;      ///< ticks counted (from measure_from)
  double seconds = 0.0;         ///< wall time they took
  double elapsed_ms = 0.0;      ///< the whole match, wall
  std::uint64_t wire_sent = 0;  ///< the joiner's bytes on the wire, IP and UDP headers in
  std::uint64_t datagrams = 0;  ///< the joiner's datagrams sent
  std::uint64_t wire_received = 0;
  std::uint64_t payload_sent = 0;  ///< the joiner's fixstep packets' bytes (no headers below)
  net::MatchStats host, joiner;
};

namespace detail {

struct Running {
  const NetCase* c = nullptr;
  std::unique_ptr<net::MatchPeer> host, joiner;
  std::vector<std::unique_ptr<net::MatchPeer>> others;  ///< the other joiners (players > 2)
  std::unique_ptr<net::LinkConditioner> link;
  double next_frame = 0.0, started = 0.0, mark_time = -1.0;
  net::MatchStats mark{};
  std::uint64_t mark_tick = 0;
  bool done = false;
  NetResult result;
};

inline double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

inline void frame(net::MatchPeer& p, Play play) {
  if (p.wants_input()) p.add_input(play_input(play, p.world(), p.slot(), p.next_input_tick()));
  (void)p.advance();
}

inline void finish(Running& r, double now) {
  r.done = true;
  NetResult& out = r.result;
  const net::MatchStats& j = r.joiner->stats();
  out.finished = r.host->state() == net::MatchState::finished &&
                 r.joiner->state() == net::MatchState::finished;
  for (const auto& o : r.others) {
    out.finished = out.finished && o->state() == net::MatchState::finished;
  }
  out.error = !r.host->error().empty() ? r.host->error() : r.joiner->error();
  for (const auto& o : r.others) {
    if (out.error.empty()) out.error = o->error();
  }
  out.host = r.host->stats();
  out.joiner = j;
  out.elapsed_ms = now - r.started;
  if (out.finished) {
    const std::string host = format_recording(r.host->recording());
    out.same_recording = host == format_recording(r.joiner->recording());
    for (const auto& o : r.others) {
      out.same_recording = out.same_recording && host == format_recording(o->recording());
    }
  }
  if (r.mark_time >= 0.0) {
    out.ticks = r.joiner->world().tick() - r.mark_tick;
    out.seconds = (now - r.mark_time) / 1000.0;
    out.wire_sent = j.wire_bytes_sent - r.mark.wire_bytes_sent;
    out.datagrams = j.wire_datagrams_sent - r.mark.wire_datagrams_sent;
    out.wire_received = j.wire_bytes_received - r.mark.wire_bytes_received;
    out.payload_sent = j.bytes_sent - r.mark.bytes_sent;
  }
}

}  // namespace detail

/// Runs every case at once (one thread, each at its own pace) until all are finished or
/// failed, or `deadline_ms` passes (those still playing are reported unfinished).
inline std::vector<NetResult> run_cases(const std::vector<NetCase>& cases, double deadline_ms) {
  std::vector<detail::Running> runs(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    detail::Running& r = runs[i];
    r.c = &cases[i];
    const WorldDef def = load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/billiards.toml").def;
    r.host = std::make_unique<net::MatchPeer>(
        net::MatchPeer::host(def, cases[i].settings, {"127.0.0.1", 0}));
    r.link = std::make_unique<net::LinkConditioner>(net::Address{"127.0.0.1", r.host->port()},
                                                    cases[i].link);
    net::MatchSettings joining = cases[i].settings;
    joining.token = r.host->token();
    r.joiner = std::make_unique<net::MatchPeer>(
        net::MatchPeer::join(def, joining, {"127.0.0.1", r.link->port()}));
    for (int k = 2; k < cases[i].settings.players; ++k) {
      r.others.push_back(std::make_unique<net::MatchPeer>(
          net::MatchPeer::join(def, joining, {"127.0.0.1", r.link->port()})));
    }
    r.started = r.next_frame = detail::now_ms();
  }
  const double start = detail::now_ms();
  for (;;) {
    bool all_done = true;
    for (detail::Running& r : runs) {
      if (r.done) continue;
      all_done = false;
      r.link->pump();
      r.host->poll(0);
      r.joiner->poll(0);
      for (auto& o : r.others) o->poll(0);
      double now = detail::now_ms();
      if (now >= r.next_frame) {
        r.next_frame += r.c->frame_ms;
        detail::frame(*r.host, r.c->play);
        detail::frame(*r.joiner, r.c->play);
        for (auto& o : r.others) detail::frame(*o, r.c->play);
      }
      now = detail::now_ms();
      if (r.mark_time < 0.0 && r.joiner->world().tick() >= r.c->measure_from) {
        r.mark_time = now;
        r.mark = r.joiner->stats();
        r.mark_tick = r.joiner->world().tick();
      }
      const auto over = [](net::MatchState s) {
        return s == net::MatchState::finished || s == net::MatchState::failed ||
               s == net::MatchState::desynced;
      };
      bool others_over = true, others_failed = false;
      for (const auto& o : r.others) {
        others_over = others_over && over(o->state());
        others_failed = others_failed || o->state() == net::MatchState::failed ||
                        o->state() == net::MatchState::desynced;
      }
      if ((over(r.host->state()) && over(r.joiner->state()) && others_over) ||
          r.host->state() == net::MatchState::failed ||
          r.joiner->state() == net::MatchState::failed ||
          r.joiner->state() == net::MatchState::desynced || others_failed ||
          now - start > deadline_ms) {
        detail::finish(r, now);
      }
    }
    if (all_done) break;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  std::vector<NetResult> out;
  for (detail::Running& r : runs) out.push_back(std::move(r.result));
  return out;
}

}  // namespace fixstep::bench
