// airhockey as a fixstep::app game, networked (fixstep/net_app/run.hpp's net::run): the rules of
// game.hpp, the players' pointers merged into the mallets' velocities, the computer on the
// right in single-player runs, the scripted bot, the drawing of draw.hpp, and the settings it
// is run with.
#pragma once

#include <fixstep/app/app.hpp>
#include <fixstep/app/session.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <span>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace airhockey {

/// The game net::run (and app::run) plays: move your mallet with the pointer (or the arrows)
/// and put the puck into the other goal.
struct AirHockey {
  GameState state;
  int player = 0;  ///< the local player (seat())

  void setup(fixstep::WorldDef& level) { level = make_level(); }
  void rules(fixstep::World& world, const fixstep::TickInput&) { after_tick(state, world); }
  /// A match: which mallet this program's pointer and bot drive.
  void seat(int p) { player = p; }
  /// Every peer, every tick of a match: the players' pointers into the mallets' velocities.
  [[nodiscard]] fixstep::TickInput merge(std::span<const fixstep::TickInput> players,
                                         const fixstep::World& world) const {
    return airhockey::merge(players, world);
  }
  /// Single-player (not in a match): the pointer drives the left mallet, the computer the right.
  void prepare(fixstep::TickInput& input, const fixstep::World& world) {
    const fixstep::TickInput both[2] = {input, computer_input(1, world)};
    input = airhockey::merge(both, world);
  }
  /// The bot: a scripted sweep of its half, by tick (in a match) or frame.
  void autopilot(std::int64_t frame, const fixstep::World&, fixstep::InputSampler& sampler) {
    sampler.set_pointer(bot_pointer(player, frame));
  }
  void draw(fixstep::app::Overlay& overlay) const { draw_table(state, player, overlay); }
  [[nodiscard]] std::string summary() const { return describe(state); }
};

/// What net::run runs AirHockey with: its name (the rules name of its recordings), the table
/// in view, no grid.
inline fixstep::app::Settings app_settings() {
  return {.name = "airhockey",
          .description =
              "two mallets, one puck: play the computer, or another player "
              "(--host PORT / --join HOST:PORT)",
          .width = 960,
          .height = 600,
          .view_center = fixstep::Vec2{0.0, 0.75},
          .view_width = 10.0,
          .controls = "mouse (or arrows): move your mallet",
          .style = fixstep::ViewStyle{.grid = false, .axes = false, .scale_bar = false},
          .hud_text_scale = 1.75f,  // the network line fits beside the score at 960 px
          .hud_lines = fixstep::hud_title};
}

}  // namespace airhockey
