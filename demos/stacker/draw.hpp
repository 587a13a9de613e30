// stacker: what the game draws over its world each frame (fixstep::app::Overlay): the
// slingshot's post and fork, its rubber band while loaded, and an aim guide while the player
// pulls. Drawing only: nothing here is in the world, its state hash or the recording.
#pragma once

#include <fixstep/app/overlay.hpp>

#include "game.hpp"

namespace stacker {

/// The launch velocity a release at `ball` (m) would give, m/s: the band's energy at that pull
/// less the height the ball climbs to the anchor, all turned into speed towards the anchor
/// (damping ignored: a guide, not the physics). Zero for a pull too short to shoot.
[[nodiscard]] fixstep::Vec2 predicted_launch(fixstep::Vec2 ball);

/// Draws the post and fork always; the band from the prongs to the ball while loaded; while
/// loaded and pulled at least min_pull, dots along the predicted flight.
void draw_game(const GameState& game, fixstep::app::Overlay& overlay);

}  // namespace stacker
