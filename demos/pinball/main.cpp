// pinball: a small pinball table. The table and the rules are game.hpp's, the game as
// fixstep::app runs it pinball_app.hpp's; fixstep::app::run gives the game its window,
// recording, replay with verification, headless frames and the sync test:
//
//   pinball [--record FILE]                    play (arrows flip, down pulls; r restart; esc quit)
//   pinball --frames N [--out DIR]             N frames headless, the autopilot playing
//   pinball --replay FILE [--out DIR [--every K]] [--last-frame PNG]
//   pinball --help                             the rest
#include <fixstep/app/app.hpp>

#include "pinball_app.hpp"

int main(int argc, char** argv) {
  return fixstep::app::run(pinball::Pinball{}, pinball::app_settings(), argc, argv);
}
