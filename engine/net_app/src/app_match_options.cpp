// fixstep::net_app: the command line of a networked match.
#include "app_match_options.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fixstep/io/output_paths.hpp>
#include <fixstep/io/output_target.hpp>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "app_match_error.hpp"
#include "fixstep/net/net_gate.hpp"

namespace fixstep::net::detail {

namespace {

/// The flags only a match has: any of them asks for one.
constexpr std::string_view match_flags[] = {
    "--host",        "--join",         "--spectate", "--players", "--session", "--bind",
    "--input-delay", "--max-rollback", "--ticks",    "--bot",     "--token",   "--paced"};

/// `text` as a whole number in [lo, hi], else nullopt.
std::optional<std::uint64_t> whole(const std::string& text, std::uint64_t lo, std::uint64_t hi) {
  std::uint64_t n = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, n);
  if (error != std::errc{} || stop != end || text.empty() || n < lo || n > hi) return {};
  return n;
}

bool is_ipv4(const std::string& text) {
  in_addr a{};
  return inet_pton(AF_INET, text.c_str(), &a) == 1;
}

/// app::run's own modes, which a match does not take.
constexpr std::string_view app_only_flags[] = {"--frames", "--out", "--replay", "--every",
                                               "--sync-test"};

/// A CLI11 check that a value is a whole number in [lo, hi].
CLI::Validator in_range(std::uint64_t lo, std::uint64_t hi) {
  const std::string range = std::to_string(lo) + "-" + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        if (whole(text, lo, hi)) return {};
        return "wants a whole number in " + range + ", got '" + text + "'";
      },
      range);
}

/// Refuses what does not fit together (UsageError).
void check(const MatchOptions& o, bool players_given) {
  const int roles =
      int{o.host_port.has_value()} + int{o.join.has_value()} + int{o.spectate.has_value()};
  if (roles > 1) {
    throw UsageError("--host, --join and --spectate: a peer either hosts, joins or watches");
  }
  if (roles == 0) {
    throw UsageError(
        "match options need --host PORT (host a match), --join HOST:PORT (play in one) or "
        "--spectate HOST:PORT (watch one)");
  }
  if (!o.token.empty() && !parse_token(o.token)) {
    throw UsageError(fmt::format(
        "--token wants the match's 32 hexadecimal digits (the host prints them), got '{}' ({} "
        "characters)",
        o.token, o.token.size()));
  }
  if (players_given && !o.host_port) {
    throw UsageError("--players is the host's choice (a joiner or spectator is told it)");
  }
  if (!is_ipv4(o.bind)) {
    throw UsageError("--bind wants an IPv4 address such as 127.0.0.1 or 0.0.0.0, got '" + o.bind +
                     "'");
  }
  if (o.bot && o.ticks == 0) throw UsageError("--bot needs --ticks N (when the match ends)");
  if (o.window && !o.bot) throw UsageError("--window needs --bot (without it, the window shows)");
  if (!o.input.empty() && !o.bot) {
    throw UsageError("--input SCRIPT needs --bot (the script plays in the bot's place)");
  }
  if (o.paced && (!o.bot || o.window)) {
    throw UsageError("--paced is for a headless --bot (a window always plays at real time)");
  }
  if (!o.host_port && o.token.empty()) {
    throw UsageError(fmt::format(
        "{} needs --token T: the match's token, 32 hexadecimal digits, which the host prints "
        "(\"token T\") when it starts; without it the host's gate lets no joiner in",
        o.join ? "--join" : "--spectate"));
  }
}

/// Refuses a flag of app::run's other modes (UsageError): a match is played live.
void refuse_app_only_flags(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    for (const std::string_view flag : app_only_flags) {
      const std::string_view arg(argv[i]);
      if (arg == flag || arg.starts_with(std::string(flag) + "=")) {
        throw UsageError(std::string(flag) +
                         " is not a match option: a match is played live (--host / --join); "
                         "replay its recording (--record FILE) afterwards with --replay FILE");
      }
    }
  }
}

/// The values of the flags that parse_match checks or converts before they go into
/// MatchOptions, and the options whose presence it asks about.
struct MatchFlags {
  std::uint16_t host_port = 0;
  std::string join, spectate, session = "lockstep", scene;
  unsigned players = 2;
  CLI::Option *host_opt = nullptr, *join_opt = nullptr, *spectate_opt = nullptr,
              *players_opt = nullptr, *delay_opt = nullptr, *rollback_opt = nullptr,
              *scene_opt = nullptr, *session_opt = nullptr;
};

/// --host, --join and --spectate: the peer's role.
void add_role_options(CLI::App& cli, MatchFlags& f, MatchOptions& o) {
  f.host_opt = cli.add_option("--host", f.host_port, "host a match on PORT (0: any, printed)")
                   ->type_name("PORT")
                   ->check(in_range(0, 65535));
  f.join_opt = cli.add_option("--join", f.join, "join the match hosted at HOST:PORT")
                   ->type_name("HOST:PORT");
  f.spectate_opt =
      cli.add_option("--spectate", f.spectate, "watch the match hosted at HOST:PORT (no input)")
          ->type_name("HOST:PORT");
  cli.add_option("--token", o.token,
                 "the match's token, 32 hex digits: a host's (default: a random one, printed), "
                 "which every joiner and spectator gives")
      ->type_name("T");
}

/// A CLI11 check of --players: a whole number in 2-most, the game's seats.
CLI::Validator players_check(std::uint64_t most) {
  return CLI::Validator(
      [most](std::string& text) -> std::string {
        if (whole(text, 2, most)) return {};
        if (whole(text, most + 1, 255)) {
          return "this game seats at most " + std::to_string(most) +
                 " players (its Settings::max_players), got '" + text + "'";
        }
        return "wants a whole number in 2-" + std::to_string(most) + ", got '" + text + "'";
      },
      "2-" + std::to_string(most));
}

/// --players, --session, --bind, --input-delay, --max-rollback and --ticks: how the match is
/// played; a game seats at most max_players (clamped to 2 .. net::max_players).
void add_session_options(CLI::App& cli, MatchFlags& f, MatchOptions& o, int max_players) {
  const auto most =
      static_cast<std::uint64_t>(std::clamp(max_players, 2, static_cast<int>(net::max_players)));
  f.players_opt =
      cli.add_option("--players", f.players,
                     "a host: players in the match (2-" + std::to_string(most) + ", default 2)")
          ->type_name("N")
          ->check(players_check(most));
  f.session_opt = cli.add_option("--session", f.session,
                                 "lockstep or rollback (default: a host lockstep, a joiner the "
                                 "host's)")
                      ->type_name("KIND")
                      ->check(CLI::IsMember({"lockstep", "rollback"}));
  cli.add_option("--bind", o.bind, "the local IPv4 address (default 127.0.0.1)")->type_name("ADDR");
  f.delay_opt = cli.add_option("--input-delay", o.input_delay,
                               "ticks between an input and its tick (0-60; default: lockstep "
                               "from the round trip, rollback 2)")
                    ->type_name("N")
                    ->check(in_range(0, 60));
  f.rollback_opt =
      cli.add_option("--max-rollback", o.max_rollback,
                     "rollback: most ticks ahead (1-60; default: from the round trip, 8 to 120)")
          ->type_name("N")
          ->check(in_range(1, 60));
  cli.add_option("--handshake-timeout", o.handshake_timeout_ms,
                 "ms to connect and complete the handshake (100-600000; default 10000, and at "
                 "least 8 round trips once one is measured)")
      ->type_name("MS")
      ->check(in_range(100, 600000));
  cli.add_option("--peer-timeout", o.peer_timeout_ms,
                 "ms without a packet before a peer is given up (100-600000; default 5000, and "
                 "at least 8 round trips)")
      ->type_name("MS")
      ->check(in_range(100, 600000));
  cli.add_option("--ticks", o.ticks, "the match ends after N ticks")
      ->type_name("N")
      ->check(in_range(1, 100000000));
}

/// --scene, --record, --last-frame, --bot and --window: the level, the outputs and who plays.
void add_output_options(CLI::App& cli, MatchFlags& f, MatchOptions& o) {
  f.scene_opt = cli.add_option("--scene", f.scene, "play the level in FILE")->type_name("FILE");
  cli.add_option("--record", o.record, "write the match's recording to FILE")->type_name("FILE");
  cli.add_option("--last-frame", o.last_frame, "write the last frame as PNG")->type_name("PNG");
  cli.add_flag("--bot", o.bot,
               "the game's autopilot plays, a spectator just watches (headless unless --window)");
  cli.add_flag("--window", o.window, "with --bot: show the window");
  cli.add_option("--input", o.input,
                 "with --bot: the input script FILE plays this player's actions by name (tick by "
                 "tick), not the autopilot")
      ->type_name("SCRIPT");
  cli.add_flag("--paced", o.paced,
               "with --bot, headless: play at real time, 60 frames a second (default: as fast as "
               "the match goes)");
}

/// The parsed flags of f into o, then the checks of what does not fit together (UsageError).
void take_flags(const MatchFlags& f, MatchOptions& o) {
  if (f.host_opt->count() > 0) o.host_port = f.host_port;
  if (f.join_opt->count() > 0) o.join = parse_host_port("--join", f.join);
  if (f.spectate_opt->count() > 0) o.spectate = parse_host_port("--spectate", f.spectate);
  o.players = static_cast<std::uint8_t>(f.players);
  if (f.scene_opt->count() > 0) o.scene = f.scene;
  o.rollback = f.session == "rollback";
  // A joiner plays the host's kind unless told (both kinds may play one match, but a lockstep
  // joiner of a rollback host plays at its delay of 2 ticks and waits every round trip).
  o.session_from_host = o.join.has_value() && f.session_opt->count() == 0;
  // Rollback shows its own input at once and predicts the others': a short delay spares it
  // re-simulation; lockstep waits for every input, so its default covers two send intervals.
  if (f.delay_opt->count() == 0 && o.rollback) o.input_delay = rollback_input_delay;
  o.adapt =
      o.rollback || o.session_from_host ? f.rollback_opt->count() == 0 : f.delay_opt->count() == 0;
  if (f.rollback_opt->count() > 0 && !o.rollback) {
    throw UsageError("--max-rollback needs --session rollback");
  }
  check(o, f.players_opt->count() > 0);
}

}  // namespace

bool wants_match(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    for (const std::string_view flag : match_flags) {
      if (arg == flag ||
          (arg.starts_with(flag) && arg.size() > flag.size() && arg[flag.size()] == '=')) {
        return true;
      }
    }
  }
  return false;
}

Address parse_host_port(const std::string& flag, const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos) {
    throw UsageError(flag + " wants HOST:PORT (e.g. 127.0.0.1:7777), got '" + text + "'");
  }
  const std::string host = text.substr(0, colon), port = text.substr(colon + 1);
  if (!is_ipv4(host)) {
    throw UsageError(flag + " " + text + ": HOST must be an IPv4 address such as 127.0.0.1 (" +
                     "names are not resolved), got '" + host + "'");
  }
  const auto p = whole(port, 1, 65535);
  if (!p) throw UsageError(flag + " " + text + ": PORT wants 1-65535, got '" + port + "'");
  return Address{host, static_cast<std::uint16_t>(*p)};
}

std::optional<MatchOptions> parse_match(const std::string& program, int max_players, int argc,
                                        char** argv) {
  refuse_app_only_flags(argc, argv);
  MatchOptions o;
  MatchFlags f;
  CLI::App cli(program + ": one peer of a networked match", program);
  add_role_options(cli, f, o);
  add_session_options(cli, f, o, max_players);
  add_output_options(cli, f, o);
  cli.footer(
      "Work: --ticks N at most 10^8 ticks and 10^13 body-substeps in all; with --record, at most "
      "the ticks whose state hashes fit in a recording (256 MiB: about 8.1 million). Both "
      "refused before a port is bound. Memory: the level's world and the rollback window's "
      "snapshots (--max-rollback), whatever the match's length: the recording is streamed to a "
      "temporary file beside FILE (without --record, beside ./.NAME-desync.PID.rec, kept only "
      "on a desync) and renamed into place at the end; without --ticks a match runs until a "
      "player quits, and a recording that nears 256 MiB is finished there, whole. SIGINT or "
      "SIGTERM ends the match within a second between two ticks: the other peers are told, "
      "the recording of every confirmed tick is written; exit 130 or 143.\n");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(cli.help().c_str(), stdout);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  take_flags(f, o);
  return o;
}

void check_match_outputs(const MatchOptions& o, const std::string& program,
                         const std::string& default_scene) {
  if (o.scene && default_scene.empty()) {  // setup() builds the level: a scene would be replaced
    throw UsageError("--scene " + *o.scene + ": " + program +
                     " builds its level in code and plays no scene file, so the scene would not "
                     "be the level played; run without --scene");
  }
  const std::string scene = o.scene.value_or(default_scene);
  OutputPaths paths{.program = program};
  if (!scene.empty()) paths.inputs.push_back({"--scene", scene});
  if (!o.input.empty()) paths.inputs.push_back({"--input", o.input});
  if (!o.record.empty()) paths.outputs.push_back({"--record", o.record});
  if (!o.last_frame.empty()) paths.outputs.push_back({"--last-frame", o.last_frame});
  check_output_paths(paths);  // PathRefused: the checks of the fixstep command's outputs
  // `--record -`: standard output carries the recording alone; the summary goes to stderr.
  if (data_on_standard_output(paths)) keep_standard_output_for_data();
  check_output_before_run("--record", o.record, {scene, o.input});
  check_output_before_run("--last-frame", o.last_frame, {scene, o.input});
}

}  // namespace fixstep::net::detail
