// Internal to fixstep::net_app: the command line of a networked match (net_app.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "fixstep/net/match_peer.hpp"
#include "fixstep/net/net_transport.hpp"

namespace fixstep::net::detail {

/// A rollback host's input delay when --input-delay is not given, ticks.
inline constexpr std::uint16_t rollback_input_delay = 2;

/// What a match's command line asked for.
struct MatchOptions {
  std::optional<std::uint16_t> host_port;  ///< --host PORT
  std::optional<Address> join;             ///< --join HOST:PORT
  std::optional<Address> spectate;         ///< --spectate HOST:PORT
  std::string token;         ///< --token T: the match's (a host's: "" for a random one, printed)
  std::uint8_t players = 2;  ///< --players N (a host)
  std::string bind = "127.0.0.1";  ///< --bind ADDR
  bool rollback = false;           ///< --session rollback
  /// A joiner without --session: the host's kind (MatchSettings::session_from_host), known at
  /// its accept; `rollback` is then false until it is.
  bool session_from_host = false;
  std::uint16_t input_delay = net::MatchSettings{}.input_delay;  ///< --input-delay N
  std::uint16_t max_rollback = 8;  ///< --max-rollback N (rollback only)
  /// Neither --input-delay (lockstep) nor --max-rollback (rollback) given: picked from the
  /// round trip (MatchSettings::adapt_to_round_trip).
  bool adapt = true;
  /// --handshake-timeout: 10 s by default, so that a joiner at a 2 s round trip and 25 % loss
  /// gets a cookie back before giving up (the round trip is not known before it)
  std::uint32_t handshake_timeout_ms = 10000;
  std::uint32_t peer_timeout_ms = net::MatchSettings{}.peer_timeout_ms;  ///< --peer-timeout
  std::uint64_t ticks = 0;           ///< --ticks N (0: until quit)
  std::optional<std::string> scene;  ///< --scene FILE
  std::string record, last_frame;    ///< --record FILE, --last-frame PNG
  bool bot = false, window = false;  ///< --bot, --window
  std::string input;   ///< --input SCRIPT: with --bot, the script plays, not the autopilot
  bool paced = false;  ///< --paced: a headless bot on the real clock
};

/// Whether the command line names a match option (then parse_match handles it all, else
/// app::run does).
[[nodiscard]] bool wants_match(int argc, char** argv);

/// Parses a match's command line. Throws UsageError naming the flag and the bad value (a port
/// outside 0-65535 or not a number, HOST:PORT without a port, not exactly one of --host, --join
/// and --spectate, a --token not of 32 hexadecimal digits, --join or --spectate without
/// --token, --players outside 2..max_players or without --host, --max-rollback without
/// --session rollback, --bot without --ticks, a flag of app::run's other modes); prints the
/// help and returns nullopt for --help.
[[nodiscard]] std::optional<MatchOptions> parse_match(const std::string& program, int max_players,
                                                      int argc, char** argv);

/// Refuses, before anything runs: --scene for a game that builds its level in code (no
/// `default_scene`: its setup() would replace the scene; UsageError); an output that may not be
/// written (a directory, a socket, a descriptor not open for writing), that is the scene file,
/// or that is the other output (PathRefused, fixstep/io/output_paths.hpp); a new file in a
/// missing directory (std::runtime_error). Messages begin with `program` or name the flag.
void check_match_outputs(const MatchOptions& o, const std::string& program,
                         const std::string& default_scene);

/// "HOST:PORT" as an address: HOST a dotted IPv4 address (a name is refused: none is resolved),
/// PORT 1-65535. Throws app::detail::UsageError naming `flag` and the text otherwise.
[[nodiscard]] Address parse_host_port(const std::string& flag, const std::string& text);

}  // namespace fixstep::net::detail
