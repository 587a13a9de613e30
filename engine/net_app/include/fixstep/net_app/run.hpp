// A game written for fixstep::app::run, networked by choosing a session on the command line:
// fixstep::net::run(game, settings, argc, argv) is app::run with two more ways to play,
//
//   NAME --host PORT [match options]        host a match as player 0 on PORT (0: any free port,
//                                           printed) and play it; prints the match's token T
//   NAME --join HOST:PORT --token T [match options]
//                                           join the match hosted at HOST:PORT as the next
//                                           free player (1, 2, ...)
//   NAME --spectate HOST:PORT --token T [options]
//                                           watch it (no input; up to 8 spectators)
//
//   match options:
//     --token T                     the match's token, 32 hexadecimal digits: a host's (default
//                                   a random one), which a joiner or spectator must give (the
//                                   host's gate lets in no one else: docs/NETWORK.md)
//     --players N                   a host: the match's players, 2 .. Settings::max_players
//                                   (default 2); it starts when all have joined
//     --session lockstep|rollback   lockstep: every peer shows the confirmed world; rollback:
//                                   the shown world runs ahead on predictions (default: a
//                                   host lockstep, a joiner the host's kind)
//     --input-delay N               ticks between an input and its tick (host decides; 0-60,
//                                   default 6, or 2 for a rollback host)
//     --max-rollback N              rollback: most ticks shown ahead (1-60, default 8)
//     --bind ADDR                   the local IPv4 address (default 127.0.0.1)
//     --ticks N                     the match ends after N ticks (default: until Esc)
//     --record FILE                 record the match's confirmed ticks (streamed to a temporary
//                                   file beside FILE, renamed into place at the end)
//     --bot                         the game's autopilot plays (seat-aware, by tick), headless
//                                   unless --window; needs --ticks (a spectator: watches
//                                   headless)
//     --window                      with --bot: show the match in a window
//     --last-frame PNG              write the last frame drawn
//     --scene FILE                  another level (both peers must play the same)
//
// and every other command line goes to app::run unchanged. Each tick of a match runs, on every
// peer: the players' inputs merged (the game's merge(), else net::merge_inputs; prepare() is
// for single-player runs only), World::step, the game's rules(); the recording is
// an ordinary recording of the game (NAME --replay FILE verifies it with the rules). Exit
// status as app::run's: 0 the match played to its end (or the player quit), 1 an error (a
// port that cannot be bound, refused, timed out, the other player left, --ticks beyond the work
// limit, or with --record beyond the state hashes a recording may hold, standard output closed
// or failing), 2 a bad command line or a refused output path (--record and --last-frame get
// app::run's checks; --scene is refused for a level built in code), 4 the peers' states
// differed (a desync: the message names the tick), 130 / 143 stopped by SIGINT / SIGTERM
// (between two ticks; the recording of every confirmed tick written). Layering: net_app uses
// fixstep::app and fixstep::net, and app never uses net; a program that calls this links
// fixstep::net_app.
#pragma once

#include <fixstep/app/app.hpp>
#include <utility>

namespace fixstep::net {

namespace detail {
/// net::run's body: the match when the command line asks for one, app::run's modes otherwise.
[[nodiscard]] int run_networked(const app::detail::AnyGame& game, const app::Settings& settings,
                                int argc, char** argv);
}  // namespace detail

/// Runs `game` as app::run does, or as one peer of a networked match (see the top of this file).
/// Never throws.
template <app::Game G>
int run(G game, const app::Settings& settings, int argc, char** argv) {
  return detail::run_networked(app::detail::GameModel<G>(std::move(game)), settings, argc, argv);
}

}  // namespace fixstep::net
