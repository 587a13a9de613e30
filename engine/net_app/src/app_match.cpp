// fixstep::net_app: a game of fixstep::app played as one peer of a networked match
// (fixstep/net_app/run.hpp): the match set up from the command line, played in a window or by the
// game's autopilot, drawn from the shown world, its recording written at the end.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fixstep/app/game_play.hpp>
#include <fixstep/app/key_bindings.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/command_limits.hpp>
#include <fixstep/io/output_paths.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/io/recording_writer.hpp>
#include <fixstep/io/stale_temporaries.hpp>
#include <fixstep/io/standard_output.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <fixstep/io/summary.hpp>
#include <fixstep/net/desync_recording.hpp>
#include <fixstep/net/match_clock.hpp>
#include <fixstep/net/match_peer.hpp>
#include <fixstep/net_app/run.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>

#include "app_match_end.hpp"
#include "app_match_error.hpp"
#include "app_match_options.hpp"
#include "app_match_view.hpp"

namespace fixstep::net::detail {

namespace {

using app::detail::AnyGame;
using app::detail::Level;

/// A frame of the window's loop and of a paced bot's: 60 frames a second.
constexpr auto frame_period = std::chrono::microseconds(16667);

/// Throws LimitError when `ticks` ticks exceed the work a command may do on `def`, or when
/// `record` is given and their state hashes (one a tick) exceed what a recording may hold
/// (max_recording_bytes). The recording is streamed to its file (MatchSettings::record_file),
/// so memory bounds no length.
void check_match_bounds(const WorldDef& def, std::uint64_t ticks, const std::string& record) {
  check_command_work(ticks, tick_work(def), fmt::format("--ticks {}", ticks));
  constexpr std::uint64_t hash_line_bytes = 33;  // "hash " + 10 digits + " " + 16 hex + "\n"
  if (!record.empty() && ticks > max_recording_bytes / hash_line_bytes) {
    throw LimitError(fmt::format(
        "--record {}: --ticks {}, each with its state hash: about {:.0f} MB of hashes; a "
        "recording may hold at most {} MiB: record at most {} ticks",
        record, ticks, double(ticks) * double(hash_line_bytes) / 1e6, max_recording_bytes >> 20,
        max_recording_bytes / hash_line_bytes));
  }
}

/// The match's settings from the command line and the level (recorded as the game records).
MatchSettings match_settings(const app::Settings& settings, const Level& level,
                             const MatchOptions& o) {
  MatchSettings s;
  s.players = o.players;
  s.token = o.token;
  s.input_delay = o.input_delay;
  s.match_ticks = o.ticks;
  s.max_rollback = o.rollback || o.session_from_host ? o.max_rollback : 0;
  s.session_from_host = o.session_from_host;
  s.adapt_to_round_trip = o.adapt;
  s.handshake_timeout_ms = o.handshake_timeout_ms;
  s.peer_timeout_ms = o.peer_timeout_ms;
  s.scene_name = level.scene_name;
  s.scene_text = level.scene_text;
  s.rules_name = app::detail::rules_name_of(settings.name);
  s.rules_version = settings.rules_version;
  s.record_file = o.record.empty() ? desync_file(settings.name) : o.record;
  s.record_in_memory = false;  // streamed: memory flat whatever the match's length
  return s;
}

/// The merge every peer runs: the game's merge(), else the network's default.
InputMerge game_merge(const AnyGame& game) {
  return [&game](std::span<const TickInput> players, const World& world) {
    TickInput out;
    if (game.merge(players, world, out)) return out;
    return merge_inputs(players, world);
  };
}

/// One peer: the level, the game copies (the rules' state, and the local player's input side),
/// the match.
class Peer {
 public:
  Peer(const AnyGame& game, const app::Settings& settings, const MatchOptions& o)
      : level_(app::detail::load_level(game, settings, o.scene.value_or(settings.scene_file))),
        rules_(level_.game->clone()),
        player_(level_.game->clone()),
        match_(start(settings, o)),
        clock_(level_.def.settings.dt) {
    if (!o.input.empty()) {  // --input: the script plays in the bot's place
      script_ = std::make_unique<InputScript>(app::detail::game_script(settings, level_, o.input));
      script_player_.emplace(*script_);
    }
  }

  MatchPeer& match() { return match_; }
  /// The game's clock (paced play and the window).
  MatchClock& clock() { return clock_; }
  const Level& level() const { return level_; }
  /// The rules' game (the shown world's state), seated as the local player for drawing.
  const AnyGame& drawn_game() {
    if (match_.slot() < match_.players()) rules_->seat(match_.slot());
    return *rules_;
  }
  [[nodiscard]] bool live() const {
    return match_.state() == MatchState::connecting || match_.state() == MatchState::playing;
  }

  /// The local player's input of `tick`: the sampler's (after the game's autopilot, when
  /// `bot`, called with the input's tick, so a bot's input depends on the tick only).
  TickInput input(InputSampler& sampler, bool bot, std::uint64_t tick) {
    if (!seated_ && match_.state() == MatchState::playing && match_.slot() < match_.players()) {
      player_->seat(match_.slot());
      seated_ = true;
    }
    if (bot && script_player_) {
      script_player_->feed(tick, sampler);
    } else if (bot) {
      player_->autopilot(static_cast<std::int64_t>(tick), match_.shown_world(), sampler);
    }
    return sampler.sample(tick);
  }
  /// Gives the match every input it wants now (input()). Returns the inputs given.
  int give_inputs(InputSampler& sampler, bool bot) {
    int given = 0;
    while (match_.wants_input()) {
      match_.add_input(input(sampler, bot, match_.next_input_tick()));
      ++given;
    }
    return given;
  }
  AnyGame& player() { return *player_; }

 private:
  MatchPeer start(const app::Settings& settings, const MatchOptions& o) {
    if (o.ticks > 0) check_match_bounds(level_.def, o.ticks, o.record);  // before a port is bound
    MatchSettings s = match_settings(settings, level_, o);
    if (o.record.empty()) {  // the desync recording's file: the match plays on without it
      const std::string ours =
          "." + settings.name + "-desync.";  // a killed match's, not a live one's
      remove_stale_temporaries(".", [&](std::string_view t) { return t.starts_with(ours); });
      try {
        (void)RecordingWriter(level_.def, s.scene_name, s.record_hash_every, s.record_file);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: warning: no recording is kept for a desync: %s\n",
                     settings.name.c_str(), e.what());
        s.record_file.clear();
      }
    }
    if (o.host_port) {
      return MatchPeer::host(level_.def, s, Address{o.bind, *o.host_port},
                             app::detail::game_rules(*rules_, settings.rules_before_step),
                             game_merge(*level_.game));
    }
    const bool spectator = o.spectate.has_value();
    return MatchPeer::join(level_.def, s, spectator ? *o.spectate : *o.join, spectator,
                           app::detail::game_rules(*rules_, settings.rules_before_step),
                           game_merge(*level_.game), Address{o.bind, 0});
  }

  Level level_;
  std::unique_ptr<AnyGame> rules_;   ///< runs the rules: the shown world's state between calls
  std::unique_ptr<AnyGame> player_;  ///< the local player's input() and autopilot()
  MatchPeer match_;
  MatchClock clock_;
  bool seated_ = false;
  std::unique_ptr<InputScript> script_;        ///< --input
  std::optional<ScriptPlayer> script_player_;  ///< plays script_, tick by tick
};

/// A line of progress (tick of ticks, stalls) on stderr, twice a second, when it is a terminal.
class Progress {
 public:
  explicit Progress(std::string name) : name_(std::move(name)) {}
  ~Progress() {
    if (terminal_) std::fputs("\n", stderr);
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void show(const MatchPeer& m, std::uint64_t ticks) {
    if (!terminal_ || std::chrono::steady_clock::now() < next_) return;
    next_ += std::chrono::milliseconds(500);
    std::fprintf(stderr, "\r%s: tick %llu of %llu, %llu stalls ", name_.c_str(),
                 static_cast<unsigned long long>(m.world().tick()),
                 static_cast<unsigned long long>(ticks),
                 static_cast<unsigned long long>(m.stats().stalls));
  }

 private:
  std::string name_;
  bool terminal_ = isatty(STDERR_FILENO) == 1;
  std::chrono::steady_clock::time_point next_ = std::chrono::steady_clock::now();
};

/// Plays headless, until the match ends or a stop is asked for (StopOnSignal): unpaced, the
/// autopilot gives every input wanted and the match goes as fast as the network lets it;
/// paced, on the real clock at 60 frames a second, as the window does (the game's clock:
/// MatchClock).
void play_bot(Peer& peer, const std::string& name, std::uint64_t ticks, bool paced) {
  InputSampler sampler;
  MatchPeer& m = peer.match();
  Progress progress(name);
  MatchClock& clock = peer.clock();
  const InputSource source = [&](std::uint64_t tick) { return peer.input(sampler, true, tick); };
  RealClock real;
  while (peer.live() && StopOnSignal::requested() == 0) {
    if (paced) {
      const auto frame_start = std::chrono::steady_clock::now();
      m.poll(0);
      (void)clock.frame(m, real.frame_seconds(), source);
      m.poll(0);  // what this frame's ticks gave, sent now rather than a frame later
      std::this_thread::sleep_until(frame_start + frame_period);
    } else {
      m.poll(1);
      (void)peer.give_inputs(sampler, true);
      (void)m.advance();
    }
    progress.show(m, ticks);
  }
}

/// Plays in the window on the real clock (MatchClock: as many ticks a frame as real time asks),
/// until Esc, the close button, a stop request (StopOnSignal) or the match's end. Returns false
/// when the player quit or a stop was asked for.
bool play_window(Peer& peer, MatchView& view, const app::Settings& settings, bool bot) {
  InputSampler sampler;
  MatchPeer& m = peer.match();
  view.open_window(settings.name);
  MatchClock& clock = peer.clock();
  const InputSource source = [&](std::uint64_t tick) { return peer.input(sampler, bot, tick); };
  RealClock real;
  while (peer.live()) {
    if (StopOnSignal::requested() != 0) return false;
    const auto frame_start = std::chrono::steady_clock::now();
    if (!view.poll_window(sampler, peer.player(), m.shown_world(), bot)) return false;
    m.poll(0);
    (void)clock.frame(m, real.frame_seconds(), source);
    m.poll(0);
    view.draw(peer.drawn_game(), m);
    view.present();
    std::this_thread::sleep_until(frame_start + frame_period);
  }
  return true;
}

/// What the match came to: the summary lines, the recording, the exit status.
int finish(Peer& peer, const app::Settings& settings, const MatchOptions& o, bool quit) {
  MatchPeer& m = peer.match();
  const World& world = m.world();
  if (m.state() == MatchState::failed && world.tick() == 0 && !quit) {  // never played
    std::fprintf(stderr, "%s: error: %s\n", settings.name.c_str(), m.error().c_str());
    return exit_failed;
  }
  std::printf("%s\n", summary_line(world, World(peer.level().def).energy().total()).c_str());
  if (const std::string s = peer.drawn_game().summary(); !s.empty()) std::printf("%s\n", s.c_str());
  std::printf("%s\n", match_summary(m).c_str());
  if (o.paced || !o.bot || o.window) {  // played on the game's clock: what a player saw
    const Freezes& f = peer.clock().freezes();
    std::printf("frames: played=%.3fs freezes over 100 ms=%llu over 250 ms=%llu longest=%.0fms\n",
                f.played_s, static_cast<unsigned long long>(f.over_100ms),
                static_cast<unsigned long long>(f.over_250ms), f.longest_s * 1000.0);
  }
  if (!o.record.empty() && world.tick() > 0) {
    if (const std::optional<std::uint64_t> ticks = m.finish_recording()) {
      std::printf("recorded %llu ticks to %s (check it: %s --replay %s)\n",
                  static_cast<unsigned long long>(*ticks), o.record.c_str(), settings.name.c_str(),
                  o.record.c_str());
    }
  }
  if (const std::optional<std::uint64_t> cut = m.recording_cut()) {
    std::fprintf(stderr,
                 "%s: warning: the recording reached %zu MiB, the most a recording may hold, at "
                 "tick %llu: it is written up to there, the rest of the match is not recorded\n",
                 settings.name.c_str(), max_recording_bytes >> 20,
                 static_cast<unsigned long long>(*cut));
    std::error_code ec;  // a match without --record: its desync file is not wanted
    if (o.record.empty() && m.state() != MatchState::desynced)
      std::filesystem::remove(desync_file(settings.name), ec);
  }
  std::fflush(stdout);
  if (m.state() == MatchState::desynced) {
    std::fprintf(stderr, "%s: error: %s\n", settings.name.c_str(), m.error().c_str());
    if (o.record.empty() && world.tick() > 0) keep_desync_recording(m, settings.name);
    keep_desync_state(m, settings.name);
    return exit_desync;
  }
  if (m.state() == MatchState::failed && !quit) {
    std::fprintf(stderr, "%s: error: %s\n", settings.name.c_str(), m.error().c_str());
    return exit_failed;
  }
  return 0;
}

/// The session the command line asked for, as the "joining" line and the window's first status
/// line name it: "lockstep", "rollback", or, for a joiner without --session, the host's.
const char* session_asked(const MatchOptions& o) {
  if (o.session_from_host) return "the host's session";
  return o.rollback ? "rollback" : "lockstep";
}

int play_match(const AnyGame& game, const app::Settings& settings, const MatchOptions& o) {
  Peer peer(game, settings, o);
  MatchPeer& m = peer.match();
  if (o.host_port) {
    const std::string delay = o.adapt && !o.rollback
                                  ? std::string("input delay from the round trip")
                                  : fmt::format("input delay {}", o.input_delay);
    std::printf("%s: hosting on %s:%u (%u players, %s, %s)\n", settings.name.c_str(),
                o.bind.c_str(), static_cast<unsigned>(m.port()), static_cast<unsigned>(o.players),
                o.rollback ? "rollback" : "lockstep", delay.c_str());
    std::printf("%s: token %s (joiners and spectators give --token %s)\n", settings.name.c_str(),
                m.token().c_str(), m.token().c_str());
  } else {
    const Address& to = o.join ? *o.join : *o.spectate;
    std::printf("%s: %s %s:%u (%s)\n", settings.name.c_str(), o.join ? "joining" : "watching",
                to.host.c_str(), static_cast<unsigned>(to.port), session_asked(o));
  }
  std::fflush(stdout);
  MatchView view(peer.level(), settings, session_asked(o));
  bool quit = false;
  if (o.bot && !o.window) {
    play_bot(peer, settings.name, o.ticks, o.paced);
  } else {
    quit = !play_window(peer, view, settings, o.bot);
  }
  if (m.state() == MatchState::finished) {
    linger_and_leave(m, settings.name);
  } else {
    locate_desync(m);
    m.leave();  // quit, a desync, a failure: the other player is told at once, not timed out
  }
  if (!o.last_frame.empty()) view.write_last_frame(peer.drawn_game(), m, o.last_frame);
  const int status = finish(peer, settings, o, quit || StopOnSignal::requested() != 0);
  if (StopOnSignal::requested() == 0 || status != 0) return status;
  std::fprintf(stderr, "%s: stopped by %s after tick %llu%s\n", settings.name.c_str(),
               StopOnSignal::name(), static_cast<unsigned long long>(m.world().tick()),
               o.record.empty() ? "" : "; the recording written up to that tick");
  return 128 + StopOnSignal::requested();
}

/// The match, its exit status or its error's.
int match_checked(const AnyGame& game, const app::Settings& settings, int argc, char** argv) {
  const char* name = settings.name.c_str();
  try {
    const std::optional<MatchOptions> o =
        parse_match(settings.name, settings.max_players, argc, argv);
    if (!o) return 0;  // --help
    check_match_outputs(*o, settings.name, settings.scene_file);
    // Ticks stay whole (a peer's bookkeeping follows each): the loops poll between them.
    const StopOnSignal signals(false);
    return play_match(game, settings, *o);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\nRun with --host 0 --help for more information.\n", name,
                 e.what());
    return exit_usage;
  } catch (const PathRefused& e) {  // an output that is an input or the other output
    std::fprintf(stderr, "%s\n", e.what());
    return exit_usage;
  } catch (const std::exception& e) {  // a bad scene, a port in use, no display
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return exit_error;
  }
}

}  // namespace

int run_networked(const AnyGame& game, const app::Settings& settings, int argc, char** argv) {
  const char* name = settings.name.c_str();
  if (!wants_match(argc, argv)) {
    return with_results_on_standard_output(settings.name, [&] {
      const int status = app::detail::run_game_unchecked(game, settings, argc, argv);
      for (int i = 1; i < argc; ++i) {
        const std::string arg(argv[i]);
        if (arg == "--help" || arg == "-h") {
          std::printf(
              "\nNetworked play: %s --host PORT | --join HOST:PORT [--session "
              "lockstep|rollback] ...\n(%s --host 0 --help lists the match options)\n",
              name, name);
        }
      }
      return status;
    });
  }
  return with_results_on_standard_output(settings.name,
                                         [&] { return match_checked(game, settings, argc, argv); });
}

}  // namespace fixstep::net::detail
