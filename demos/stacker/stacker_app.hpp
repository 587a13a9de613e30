// stacker as a fixstep::app game (fixstep/app/app.hpp's Game): the rules of game.hpp, the
// pointer's drag limited to the loaded ball (prepare_input), an autopilot for headless runs, the
// drawing of draw.hpp and the HUD's lines, and the settings it is run with. One definition for the
// program (main.cpp: app::run) and for the web page (web/: game=stacker).
#pragma once

#include <array>
#include <cstdint>
#include <fixstep/app/app.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace stacker {

/// The game app::run plays: drag the loaded ball back with the pointer and let go.
struct Stacker {
  GameState state;

  void setup(fixstep::WorldDef& level) { level = make_level(); }
  void rules(fixstep::World& world, const fixstep::TickInput& input) {
    after_tick(state, input, world);
  }
  void prepare(fixstep::TickInput& input, const fixstep::World& world) {
    prepare_input(state, input, world);
  }

  /// Headless (60 frames a second): a player who, whenever the ball is loaded, waits 0.5 s,
  /// presses on it, drags it to the next of `pulls` over 0.5 s, holds 0.3 s and lets go: the
  /// gate falls, then the pyramid, then the house (assets/recordings/stacker.rec). It keeps no
  /// state of its own: the shot and the time come from the rules' state and the world's tick,
  /// so it plays the same under --sync-test, which rolls the game back and forth.
  static constexpr std::array<fixstep::Vec2, shots_per_game> pulls{
      {{-14.0, 2.2}, {-14.3, 2.0}, {-14.6, 1.6}}};
  void autopilot(std::int64_t /*frame*/, const fixstep::World& world,
                 fixstep::InputSampler& sampler) const {
    const int shot = shots_per_game - state.shots_left;
    if (state.phase != Phase::loaded || shot >= shots_per_game) return;
    const auto since = static_cast<std::int64_t>(world.tick() - state.loaded_at);
    const std::int64_t t = since / 2 - 30;  // frames into the drag (two ticks a frame)
    const fixstep::Vec2 from = ball_rest_position(), to = pulls[std::size_t(shot)];
    const double f = t < 0 ? 0.0 : t > 30 ? 1.0 : double(t) / 30.0;
    sampler.set_pointer({from.x + f * (to.x - from.x), from.y + f * (to.y - from.y)});
    if (t >= 0 && t < 48) sampler.press(fixstep::button_pointer_primary);  // once: then held
    if (t >= 48) sampler.release(fixstep::button_pointer_primary);         // a no-op once up
  }

  void draw(fixstep::app::Overlay& overlay) const {
    draw_game(state, overlay);  // post, fork, band, aim guide
    for (const std::string& line : status_lines(state)) overlay.text(line);
  }
  [[nodiscard]] std::string summary() const { return describe(state); }
};

/// What app::run (and the page) run Stacker with: its name (the rules name of its recordings)
/// and the slingshot and the towers in view.
inline fixstep::app::Settings app_settings() {
  return {.name = "stacker",
          .description = "drag the ball back, let go, knock the towers of boxes down",
          // From 4 m behind the slingshot (room to pull the ball back) to the last tower.
          .view_center = fixstep::Vec2{0.0, 7.2},
          .view_width = 32.0,  // m
          .controls = "mouse: drag the ball back and let go",
          .style = fixstep::ViewStyle{.axes = false}};
}

}  // namespace stacker
