// slingshot: what the game draws over its world each frame (fixstep::app::Overlay): the
// slingshot's post and fork, its rubber band while loaded, and an aim guide while the player
// pulls. Drawing only: nothing here is in the world, its state hash or the recording.
#pragma once

#include <fixstep/app/overlay.hpp>

#include "game.hpp"

namespace slingshot {

/// Where the fork's two prongs end, m (the band is tied there).
inline constexpr fixstep::Vec2 left_prong{anchor.x - 0.55, anchor.y + 0.35};
inline constexpr fixstep::Vec2 right_prong{anchor.x + 0.55, anchor.y + 0.35};

/// Seconds of flight the aim guide predicts.
inline constexpr double aim_seconds = 1.6;
/// Dots of the aim guide.
inline constexpr int aim_dots = 16;

/// The launch velocity a release at `ball` (m) would give, m/s: the band's energy at that pull
/// less the height the ball climbs to the anchor, all turned into speed towards the anchor
/// (damping ignored: a guide, not the physics). Zero for a pull too short to shoot.
[[nodiscard]] fixstep::Vec2 predicted_launch(fixstep::Vec2 ball);

/// Draws the slingshot behind nothing and in front of the world: the post and fork always; the
/// rubber from the prongs to the ball while loaded; while loaded and pulled at least min_pull,
/// the aim guide (aim_dots dots along the predicted flight from the anchor, fading over
/// aim_seconds) and an arrow of the pull. Uses the ball's drawn position (overlay.position).
void draw_slingshot(const GameState& game, fixstep::app::Overlay& overlay);

}  // namespace slingshot
