// peggle: aim with the pointer, shoot ten balls into the pegs, clear them. The level and the
// rules are game.hpp's, the game as fixstep::app runs it peggle_app.hpp's; fixstep::app::run
// gives the game its window, recording, replay with verification, headless frames and the sync
// test:
//
//   peggle [--record FILE]                     play (mouse aims, click shoots; r restart; esc quit)
//   peggle --frames N [--out DIR]              N frames headless, the autopilot shooting
//   peggle --replay FILE [--out DIR [--every K]] [--last-frame PNG]
//   peggle --help                              the rest
#include <fixstep/app/app.hpp>

#include "peggle_app.hpp"

int main(int argc, char** argv) {
  return fixstep::app::run(peggle::Peggle{}, peggle::app_settings(), argc, argv);
}
