// slingshot: drag the red ball back on its rubber band, let go, and knock the targets off their
// ropes. The level and the rules are game.hpp's, the game as fixstep::app runs it
// slingshot_app.hpp's; fixstep::app::run gives the game its window, recording, replay with
// verification, headless frames and the sync test:
//
//   slingshot [--record FILE]                     play (mouse: drag the ball; r restart; esc quit)
//   slingshot --replay FILE [--out DIR [--every K]] [--last-frame PNG]
//   slingshot --help                              the rest
//
// Every tick of play runs the same steps, live or replayed:
//   input    the mouse, sampled for this tick (InputSampler), or the recording's input
//   prepare  the pointer may drag only the loaded ball (live only: the recording holds the
//            prepared input, drag_body included)
//   step     world.step(input): physics, with the pointer's drag spring
//   rules    cut the band, score the hits (world.impacts()), knock targets off, reload
// and every frame the game draws the slingshot and its aim guide over the world (draw.hpp).
#include <fixstep/app/app.hpp>

#include "slingshot_app.hpp"

int main(int argc, char** argv) {
  return fixstep::app::run(slingshot::Slingshot{}, slingshot::app_settings(), argc, argv);
}
