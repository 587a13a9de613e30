// pinball: what the game draws itself over the table (app::Overlay): the plunger drawn back by
// the pull, the bumpers' rings lit after a hit, and the drain's mark.
#pragma once

#include <fixstep/app/overlay.hpp>

#include "game.hpp"

namespace pinball {

/// Draws the plunger, the lit bumpers' rings and the drain into `o`.
void draw_game(const GameState& game, fixstep::app::Overlay& o);

}  // namespace pinball
