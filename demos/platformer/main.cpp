// platformer: walk and jump with a character mover over one-way platforms, a moving platform
// and a crate, collecting coins. The level and the rules are game.hpp's, the game as
// fixstep::app runs it platformer_app.hpp's; fixstep::app::run gives it a window, recording,
// replay with verification, headless frames (the autopilot or --input SCRIPT playing) and the
// sync test:
//
//   platformer [--record FILE]                  play (a/d walk, space jump, shift run; p pause)
//   platformer --frames N --input SCRIPT        N frames headless, the script playing
//   platformer --replay FILE [--out DIR]        re-simulate a recording, verifying it
//   platformer --help                           the rest
#include <fixstep/app/app.hpp>

#include "platformer_app.hpp"

int main(int argc, char** argv) {
  return fixstep::app::run(platformer::Platformer{}, platformer::app_settings(), argc, argv);
}
