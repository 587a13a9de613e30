// airhockey's drawing over the world: the table's markings, each mallet's reach, the goal
// creases and the score.
#pragma once

#include <fixstep/app/overlay.hpp>

#include "game.hpp"

namespace airhockey {

/// Draws the centre line and circle, both goal creases, each player's reach (a frame round
/// where its mallet may go, brighter for `seat`, the local player; -1: none) and the score.
void draw_table(const GameState& game, int seat, fixstep::app::Overlay& overlay);

}  // namespace airhockey
