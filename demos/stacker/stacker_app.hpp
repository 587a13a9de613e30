// stacker as a fixstep::app game (fixstep/app/app.hpp's Game): the rules of game.hpp, the
// pointer's drag limited to the loaded ball, an autopilot for headless runs, the drawing of
// draw.hpp and the HUD's lines, and the settings it is run with. One definition for the program
// (main.cpp: app::run) and for the web page (web/: game=stacker).
#pragma once

#include <array>
#include <cstdint>
#include <fixstep/app/app.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/pointer_drag.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace stacker {

/// The game app::run plays: drag the loaded ball back with the pointer and let go.
struct Stacker {
  GameState state;
  fixstep::PointerDrag drag{0.3};  // m: a small ball is easy to grab

  void setup(fixstep::WorldDef& level) { level = make_level(); }
  void rules(fixstep::World& world, const fixstep::TickInput& input) {
    after_tick(state, input, world);
  }
  void prepare(fixstep::TickInput& input, const fixstep::World& world) {
    prepare_input(state, drag, input, world);
  }

  /// Headless (60 frames a second): a player who, whenever the ball is loaded, waits 0.5 s,
  /// presses on it, drags it to the next of `pulls` over 0.5 s, holds 0.3 s and lets go: the
  /// gate falls, then the pyramid, then the house (assets/recordings/stacker.rec).
  static constexpr std::array<fixstep::Vec2, shots_per_game> pulls{
      {{-14.0, 2.2}, {-14.3, 2.0}, {-14.6, 1.6}}};
  int shot = 0;                 ///< autopilot: the pull it takes next
  std::int64_t loaded_at = -1;  ///< autopilot: the frame it saw the ball loaded
  void autopilot(std::int64_t frame, const fixstep::World& /*world*/,
                 fixstep::InputSampler& sampler) {
    if (state.phase != Phase::loaded || shot >= shots_per_game) {
      loaded_at = -1;
      return;
    }
    if (loaded_at < 0) loaded_at = frame;
    const std::int64_t t = frame - loaded_at - 30;  // frames into the drag
    const fixstep::Vec2 from = ball_rest_position(), to = pulls[std::size_t(shot)];
    const double f = t < 0 ? 0.0 : t > 30 ? 1.0 : double(t) / 30.0;
    sampler.set_pointer({from.x + f * (to.x - from.x), from.y + f * (to.y - from.y)});
    if (t == 0) sampler.press(fixstep::button_pointer_primary);
    if (t == 48) {
      sampler.release(fixstep::button_pointer_primary);
      ++shot;
    }
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
