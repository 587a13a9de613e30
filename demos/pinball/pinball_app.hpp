// pinball as a fixstep::app game (fixstep/app/app.hpp's Game): the rules of game.hpp, the
// flippers driven before each tick (prepare), the autopilot of a headless run, the drawing of
// draw.hpp and the HUD's lines, and the settings it is run with. One definition for the program
// (main.cpp: app::run) and for the web page (web/: game=pinball), so that both play, record and
// replay the same game.
#pragma once

#include <cmath>
#include <cstdint>
#include <fixstep/app/app.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>
#include <utility>
#include <vector>

#include "draw.hpp"
#include "game.hpp"

namespace pinball {

/// The game app::run plays: Z / M (or the arrows, or the shift keys, or a gamepad's shoulders)
/// flip, space (or down, Enter, a gamepad's A) pulls the plunger.
struct Pinball {
  GameState state;
  void setup(fixstep::WorldDef& level) { level = make_table(); }
  void rules(fixstep::World& world, const fixstep::TickInput& input) {
    after_tick(state, input, world);
  }
  void prepare(fixstep::TickInput& input, const fixstep::World& world) {
    prepare_input(input, world);
  }

  /// Headless: pulls the plunger to 80 ticks and lets go; raises a flipper while the ball comes
  /// down over it, lowering it once raised and the ball is gone. It keeps no state of its own
  /// (the sync test rolls the game back, and the autopilot with it): it reads the world, the
  /// rules' pull and the sampler's held keys.
  void autopilot(std::int64_t /*frame*/, const fixstep::World& world,
                 fixstep::InputSampler& sampler) {
    if (state.phase == Phase::over) {  // hands off
      sampler.release(left_flipper_key | right_flipper_key | fixstep::button_down);
      return;
    }
    if (on_plunger(world) && state.pull < 80) {
      sampler.press(fixstep::button_down);
    } else {
      sampler.release(fixstep::button_down);
    }
    const fixstep::Body b = world.body(world.find("ball"));
    for (const double side : {-1.0, 1.0}) {
      const std::uint32_t key = side < 0 ? left_flipper_key : right_flipper_key;
      const fixstep::Body flipper =
          world.body(world.find(side < 0 ? "flipper_left" : "flipper_right"));
      // Along the flipper from its pivot (m), and the height of its top there at rest.
      const double along = -side * (b.position.x - side * flipper_x);
      const double top = flipper_y + 0.2 - 0.5 * along;
      const bool over = along > 0.7 && along < flipper_length && b.velocity.y < 0.0 &&
                        b.position.y < top + ball_radius + 0.3;
      if (over) {
        sampler.press(key);
      } else if (std::abs(flipper.angle + side * flipper_raised) < 0.05) {  // at its limit
        sampler.release(key);
      }
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
  using fixstep::Key;
  std::vector<fixstep::LoopBinding> loop = fixstep::default_loop_bindings();
  for (fixstep::LoopBinding& b : loop) {  // space is the plunger's: pause on P
    if (b.action == fixstep::LoopAction::pause) b.keys = {Key::p};
  }
  return {.name = "pinball",
          .description = "flip the ball up the table, hit the bumpers; three balls",
          .view_center = fixstep::Vec2{0.5, 7.3},  // the drain to the top of the arc
          .view_width = 30.0,
          .controls = "z / m: flippers   space: plunger",
          .actions = {{"left_flipper",
                       left_flipper_key,
                       {Key::z, Key::left, Key::left_shift, Key::pad_left_shoulder}},
                      {"right_flipper",
                       right_flipper_key,
                       {Key::m, Key::right, Key::right_shift, Key::pad_right_shoulder}},
                      {"plunger", fixstep::button_down, {Key::space, Key::down, Key::pad_a}},
                      {"launch", fixstep::button_action, {Key::enter, Key::keypad_enter}}},
          .loop_keys = std::move(loop),
          .style =
              fixstep::ViewStyle{
                  .background = {16, 18, 30, 255}, .grid = false, .axes = false, .scale_bar = true},
          .hud_text_scale = 1.4f};
}

}  // namespace pinball
