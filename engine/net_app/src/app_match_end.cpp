// fixstep::net_app: how a peer's match ends (app_match_end.hpp).
#include "app_match_end.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <fixstep/io/stop_signal.hpp>
#include <fixstep/net/desync_recording.hpp>

namespace fixstep::net::detail {

namespace {

/// After the last tick, a peer keeps answering this long (ms), so that the other gets what it
/// still lacks (resent inputs, the last hash) before this one leaves.
constexpr int linger_ms = 600;

}  // namespace

/// Where a match without --record streams its recording, in the working directory, to keep it
/// if the match desyncs (moved then to NAME-desync-pSLOT-tTICK.rec; else never published).
std::string desync_file(const std::string& program) {
  return fmt::format(".{}-desync.{}.rec", program, static_cast<long>(getpid()));
}

/// Keeps the match answering after its end until every other peer has acknowledged every input
/// it needs from this one (MatchPeer::settled: a peer that left early would leave another
/// short of its last ticks, "timed out"), and linger_ms more for the acknowledgements of ours
/// to arrive; at most the peer timeout (MatchPeer::peer_timeout_ms: the others wait as long
/// for this one). Then leaves. A wait past a second says so on stderr when it is a terminal
/// (a long round trip makes it up to 8 of them).
void linger_and_leave(MatchPeer& m, const std::string& name) {
  const double most_ms = m.peer_timeout_ms();
  const auto start = std::chrono::steady_clock::now();
  auto since = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  bool told = isatty(STDERR_FILENO) != 1;
  while (m.state() == MatchState::finished && !m.settled() && since() < most_ms &&
         StopOnSignal::requested() == 0) {
    m.poll(1);
    (void)m.advance();
    if (!told && since() >= 1000.0) {
      std::fprintf(stderr,
                   "%s: the match is over; waiting up to %.0f s more for the other players to "
                   "acknowledge its last ticks (Ctrl+C leaves now)\n",
                   name.c_str(), (most_ms - since()) / 1000.0);
      told = true;
    }
  }
  const double settled_at = since();
  while (m.state() == MatchState::finished && since() < settled_at + linger_ms &&
         StopOnSignal::requested() == 0) {
    m.poll(1);
    (void)m.advance();
  }
  m.leave();
}

/// A desync found: keeps answering until it is located with the peer it was found against
/// (MatchPeer::locating: the first differing tick, body and field), at most the peer timeout.
void locate_desync(MatchPeer& m) {
  const double most_ms = m.peer_timeout_ms();
  const auto start = std::chrono::steady_clock::now();
  while (
      m.locating() && StopOnSignal::requested() == 0 &&
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() <
          most_ms) {
    m.poll(1);
  }
}

/// A desync's state of its first differing tick, NAME-desync-pSLOT-tTICK.state in the working
/// directory, to compare with the other peer's.
void keep_desync_state(const MatchPeer& m, const std::string& name) {
  try {
    if (const auto file = write_desync_state(m, ".", name)) {
      std::fprintf(stderr, "%s: this peer's state of the first tick that differs is in %s\n",
                   name.c_str(), file->c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: the desync state was not written: %s\n", name.c_str(),
                 e.what());
  }
}

/// A match without --record that desynced: its streamed recording moved to
/// NAME-desync-pSLOT-tTICK.rec in the working directory, to replay and compare offline.
void keep_desync_recording(MatchPeer& m, const std::string& name) {
  const std::string written = desync_file(name);
  try {
    if (!m.finish_recording()) return;  // none was kept (a warning said so at the start)
    const std::uint64_t tick =
        m.desync() ? m.desync()->first_tick.value_or(m.desync()->tick) : m.world().tick();
    const auto file = move_desync_recording(written, ".", name, m.slot(), tick);
    std::fprintf(stderr, "%s: this peer's recording is in %s (%s --replay %s)\n", name.c_str(),
                 file.c_str(), name.c_str(), file.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: the desync recording was not written: %s\n", name.c_str(),
                 e.what());
  }
}

/// The match's line of the summary: who this peer was and what the network did.
std::string match_summary(const MatchPeer& m) {
  const MatchStats& st = m.stats();
  const std::string who = m.slot() < m.players() ? fmt::format("player={}", m.slot())
                          : m.slot() == no_slot
                              ? std::string("joining")
                              : fmt::format("spectator={}", m.slot() - spectator_slot_base);
  return fmt::format(
      "match: {} ticks={} rtt={}ms input_delay={} rollback_window={} stalls={} stalled={:.0f}ms "
      "rollbacks={} longest_rollback={} waits={} resends={} hashes={} dropped={}",
      who, m.world().tick(), st.round_trip_ms, m.input_delay(), m.rollback_window(), st.stalls,
      st.stalled_ms, st.rollbacks, st.max_rolled_back, st.waits, st.resends, st.hashes_compared,
      st.dropped_total());
}

}  // namespace fixstep::net::detail
