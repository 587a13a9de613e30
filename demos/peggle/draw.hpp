// peggle: what the game draws itself over the world (app::Overlay): the launcher turned to the
// aim, the aim line (the ball's first 0.7 s under gravity) and the ray-cast guide to the first peg
// straight ahead, and the bucket between its rims.
#pragma once

#include <fixstep/app/overlay.hpp>

#include "game.hpp"

namespace peggle {

/// Draws the launcher, the aim line and guide (while aiming) and the bucket into `o`.
void draw_game(const GameState& game, fixstep::app::Overlay& o);

}  // namespace peggle
