// pinball as a fixstep::app game (fixstep/app/app.hpp's Game): the rules of game.hpp, the
// flippers driven before each tick (prepare), the autopilot of a headless run, the drawing of
// draw.hpp and the HUD's lines, and the settings it is run with. One definition for the program
// (main.cpp: app::run) and for the web page (web/: game=pinball), so that both play, record and
// replay the same game.
#pragma once

#include <cstdint>
#include <fixstep/app/app.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace pinball {

/// The game app::run plays: left and right arrows flip, down (or Enter) pulls the plunger.
struct Pinball {
  GameState state;
  std::int64_t pulled_since = -1;             ///< autopilot: the frame it began pulling the plunger
  std::int64_t flipped_at[2] = {-100, -100};  ///< autopilot: each flipper's last flip, frame

  void setup(fixstep::WorldDef& level) { level = make_table(); }
  void rules(fixstep::World& world, const fixstep::TickInput& input) {
    after_tick(state, input, world);
  }
  void prepare(fixstep::TickInput& input, const fixstep::World& world) {
    prepare_input(input, world);
  }

  /// Headless: pulls the plunger for most of a second and lets go; flips a flipper when the
  /// ball comes down over it, holding it up for 0.2 s.
  void autopilot(std::int64_t frame, const fixstep::World& world, fixstep::InputSampler& sampler) {
    if (state.phase == Phase::over) return;
    if (on_plunger(world)) {
      if (pulled_since < 0) pulled_since = frame, sampler.press(fixstep::button_down);
      if (frame - pulled_since >= 50) sampler.release(fixstep::button_down), pulled_since = -1;
    }
    const fixstep::Body b = world.body(world.find("ball"));
    for (int k = 0; k < 2; ++k) {
      const double side = k == 0 ? -1.0 : 1.0;
      const std::uint32_t key = k == 0 ? left_flipper_key : right_flipper_key;
      // Along the flipper from its pivot (m), and the height of its top there at rest.
      const double along = -side * (b.position.x - side * flipper_x);
      const double top = flipper_y + 0.2 - 0.5 * along;
      const bool over = along > 0.3 && along < flipper_length && b.velocity.y < 0.0 &&
                        b.position.y < top + ball_radius + 0.3;
      if (over && frame - flipped_at[k] > 30) sampler.press(key), flipped_at[k] = frame;
      if (frame - flipped_at[k] == 12) sampler.release(key);
    }
  }
  void draw(fixstep::app::Overlay& overlay) const {
    draw_game(state, overlay);
    for (const std::string& line : status_lines(state)) overlay.text(line);
  }
  [[nodiscard]] std::string summary() const { return describe(state); }
};

/// What app::run (and the page) run Pinball with: its name (the rules name of its recordings),
/// the whole table in view, a dark background and a larger HUD.
inline fixstep::app::Settings app_settings() {
  return {.name = "pinball",
          .description = "flip the ball up the table, hit the bumpers; three balls",
          .view_center = fixstep::Vec2{0.5, 7.3},  // the drain to the top of the arc
          .view_width = 30.0,
          .controls = "left/right: flippers   down or enter: plunger",
          .style =
              fixstep::ViewStyle{
                  .background = {16, 18, 30, 255}, .grid = false, .axes = false, .scale_bar = true},
          .hud_text_scale = 1.4f};
}

}  // namespace pinball
