// stacker: knock three towers of boxes down with a ball thrown from a slingshot. The level and
// the rules are game.hpp's, the game as fixstep::app runs it stacker_app.hpp's;
// fixstep::app::run gives it a window, recording, replay with verification, headless frames
// (the autopilot shooting) and the sync test:
//
//   stacker [--record FILE]                      play (mouse: drag the ball; r restart; esc quit)
//   stacker --frames N [--out DIR]               N frames headless, the autopilot shooting
//   stacker --replay FILE [--out DIR [--every K]] [--last-frame PNG]
//   stacker --help                               the rest
#include <fixstep/app/app.hpp>

#include "stacker_app.hpp"

int main(int argc, char** argv) {
  return fixstep::app::run(stacker::Stacker{}, stacker::app_settings(), argc, argv);
}
