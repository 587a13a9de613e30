// pinball: the game's drawing (draw.hpp).
#include "draw.hpp"

#include <optional>
#include <string>

namespace pinball {

using fixstep::Rgba8;
using fixstep::Vec2;

namespace {

constexpr Rgba8 metal{170, 175, 190, 255}, spring_color{110, 115, 130, 255};
constexpr Rgba8 ring{255, 230, 120, 255}, drain_color{200, 60, 60, 160};

/// The plunger under the lane: a rod and a knob, drawn down by the pull.
void draw_plunger(const GameState& game, fixstep::app::Overlay& o) {
  const double back = 0.5 * game.pull / full_pull_ticks;  // m
  const double top = plunger_y - back;
  o.rect({lane_x - 0.4, top - 0.15}, {lane_x + 0.4, top}, metal);
  o.line({lane_x, top - 0.15}, {lane_x, -0.9}, 0.12, spring_color);
  o.rect({lane_x - 0.25, -1.05}, {lane_x + 0.25, -0.9}, metal);
}

}  // namespace

void draw_game(const GameState& game, fixstep::app::Overlay& o) {
  const fixstep::World* world = o.world();
  if (world == nullptr) return;
  draw_plunger(game, o);
  for (int i = 0; i < bumper_count; ++i) {
    if (game.lit[i] == 0) continue;
    const std::optional<Vec2> at = o.position(world->find("bumper" + std::to_string(i)));
    if (at) o.circle(*at, bumper_radius + 0.12, 0.1, ring);
  }
  o.line({-flipper_x + 0.6, drain_y}, {flipper_x - 0.6, drain_y}, 0.08, drain_color);
  o.label({-0.5, drain_y + 0.6}, "drain", 1.5, drain_color);
}

}  // namespace pinball
