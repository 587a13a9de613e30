// peggle as a fixstep::app game (fixstep/app/app.hpp's Game): the rules of game.hpp, the autopilot
// of a headless run, the drawing of draw.hpp and the HUD's lines, and the settings it is run
// with (its view and look). One definition for the program (main.cpp: app::run) and for the web
// page (web/: game=peggle), so that both play, record and replay the same game.
#pragma once

#include <cstdint>
#include <fixstep/app/app.hpp>
#include <fixstep/core/det_math.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace peggle {

/// The game app::run plays: the pointer aims, a press (click or Enter) shoots.
struct Peggle {
  GameState state;

  void setup(fixstep::WorldDef& level) { level = make_level(); }
  void rules(fixstep::World& world, const fixstep::TickInput& input) {
    after_tick(state, input, world);
  }
  std::int64_t aimed_since = 0;  ///< autopilot: the frame the current aim began

  /// Headless: sweeps the aim across the field and shoots 0.75 s after each ball is gone.
  void autopilot(std::int64_t frame, const fixstep::World& /*world*/,
                 fixstep::InputSampler& sampler) {
    const double t = static_cast<double>(frame) / 60.0;
    if (state.phase == Phase::aiming) {  // the pointer rests while a ball flies
      sampler.set_pointer(fixstep::Vec2{7.0 * fixstep::det::sin(0.9 * t + 0.4), 0.0});
    }
    sampler.release(fixstep::button_action);  // the last frame's press, if any (a no-op otherwise)
    if (state.phase != Phase::aiming) {
      aimed_since = frame + 1;
    } else if (frame - aimed_since == 45) {
      sampler.press(fixstep::button_action);
    }
  }
  void draw(fixstep::app::Overlay& overlay) const {
    draw_game(state, overlay);
    for (const std::string& line : status_lines(state)) overlay.text(line);
  }
  [[nodiscard]] std::string summary() const { return describe(state); }
};

/// What app::run (and the page) run Peggle with: its name (the rules name of its recordings),
/// the view from the launcher to below the bucket, a dark background and a larger HUD.
inline fixstep::app::Settings app_settings() {
  return {.name = "peggle",
          .description = "aim, shoot ten balls into the pegs and clear them",
          .view_center = fixstep::Vec2{0.0, -0.6},  // the launcher to below the bucket
          .view_width = 38.0,
          .controls = "mouse: aim   click or enter: shoot",
          .style =
              fixstep::ViewStyle{
                  .background = {18, 20, 32, 255}, .grid = false, .axes = false, .scale_bar = true},
          .hud_text_scale = 1.4f};  // the HUD fits left of the field
}

}  // namespace peggle
