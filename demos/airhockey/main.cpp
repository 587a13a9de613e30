// airhockey: two mallets and a puck, against the computer or another player over the network.
// The level, the merged input and the rules are game.hpp's, the game as fixstep::app runs it
// airhockey_app.hpp's; fixstep::net::run is app::run plus networked play:
//
//   airhockey                                   play the computer (mouse or arrows; esc quits)
//   airhockey --host 7777                       host a match on 127.0.0.1:7777 (player 0, red);
//                                               it prints the match's token T
//   airhockey --join 127.0.0.1:7777 --token T   join it (player 1, blue)
//   airhockey --host 7777 --session rollback    the shown world runs ahead of the network
//   airhockey --host 0 --bot --ticks 600 --record a.rec
//                                               a scripted bot plays, headless; the match's
//                                               recording is written at the end
//   airhockey --replay a.rec                    verify a recording with the rules
//   airhockey --help                            the rest
//
// Every tick of a match runs the same steps on both peers, and in a replay:
//   merge  both players' pointers into the mallets' velocities (game.hpp merge)
//   step   world.step(input): the puck off the mallets and walls
//   rules  goals (the goal sensors), the serve, the puck's speed limit
#include <fixstep/net_app/run.hpp>

#include "airhockey_app.hpp"

int main(int argc, char** argv) {
  return fixstep::net::run(airhockey::AirHockey{}, airhockey::app_settings(), argc, argv);
}
