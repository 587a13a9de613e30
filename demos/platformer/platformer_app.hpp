// platformer as a fixstep::app game (fixstep/app/app.hpp's Game): the rules of game.hpp run
// before each tick's step, an autopilot for headless runs, the HUD's lines, and the settings
// (actions, keys, the walk axis) it is run with. One definition for the program (main.cpp:
// app::run) and for the web page (web/: game=platformer).
#pragma once

#include <cstdint>
#include <fixstep/app/app.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>
#include <utility>
#include <vector>

#include "game.hpp"

namespace platformer {

/// The game app::run plays: A / D (or the arrows, or a stick) walk, space (or W, up, a
/// gamepad's A) jumps, shift runs.
struct Platformer {
  GameState state;

  void setup(fixstep::WorldDef& level) {
    level = make_level();
    start(state, level);
  }
  void rules(fixstep::World& world, const fixstep::TickInput& input) {
    platformer::rules(state, input, world);
  }
  /// Headless: walks right, jumping every 1.5 s (it reads nothing: a pattern of the frame).
  void autopilot(std::int64_t frame, const fixstep::World& /*world*/,
                 fixstep::InputSampler& sampler) const {
    sampler.set_axis(walk_axis, 1.0);
    if (frame % 90 == 45) {
      sampler.press(jump_action);
    } else {
      sampler.release(jump_action);
    }
  }
  void draw(fixstep::app::Overlay& overlay) const {
    overlay.text("coins " + std::to_string(state.coins) + " of " +
                 std::to_string(state.coins_total));
  }
  [[nodiscard]] std::string summary() const { return describe(state); }
};

/// What app::run (and the page) run Platformer with: its actions and walk axis, pause on P
/// (space jumps), the view following the player.
inline fixstep::app::Settings app_settings() {
  using fixstep::Key;
  std::vector<fixstep::LoopBinding> loop = fixstep::default_loop_bindings();
  for (fixstep::LoopBinding& b : loop) {
    if (b.action == fixstep::LoopAction::pause) b.keys = {Key::p};
  }
  return {.name = "platformer",
          .description =
              "walk, jump through one-way platforms, ride, push the crate, collect "
              "the coins",
          .view_width = 24.0,
          .follow = "player",
          .controls = "a / d: walk   space: jump   shift: run",
          .actions = {{"jump", jump_action, {Key::space, Key::w, Key::up, Key::pad_a}},
                      {"run", run_action, {Key::left_shift, Key::right_shift, Key::pad_x}}},
          .axes = {{"walk",
                    walk_axis,
                    {Key::a, Key::left, Key::pad_left},
                    {Key::d, Key::right, Key::pad_right},
                    fixstep::PadAxis::left_x,
                    0.2}},
          .loop_keys = std::move(loop),
          .rules_before_step = true,
          .style = fixstep::ViewStyle{.background = {28, 32, 48, 255}, .axes = false}};
}

}  // namespace platformer
