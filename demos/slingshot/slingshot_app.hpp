// slingshot as a fixstep::app game (fixstep/app/app.hpp's Game): the rules of game.hpp, the
// pointer's drag limited to the loaded ball, the drawing of draw.hpp and the HUD's lines, and
// the settings it is run with (its view and look). One definition for the program (main.cpp:
// app::run) and for the web page (web/: game=slingshot), so that both play, record and replay
// the same game.
#pragma once

#include <fixstep/app/app.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/pointer_drag.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace slingshot {

/// The game app::run plays: drag the loaded ball back with the pointer and let go.
struct Slingshot {
  GameState state;
  fixstep::PointerDrag drag{0.3};  // m: a small ball is easy to grab

  void setup(fixstep::WorldDef& level) { level = make_level(); }
  void rules(fixstep::World& world, const fixstep::TickInput& input) {
    after_tick(state, input, world);
  }
  void prepare(fixstep::TickInput& input, const fixstep::World& world) {
    prepare_input(state, drag, input, world);
  }
  void draw(fixstep::app::Overlay& overlay) const {
    draw_slingshot(state, overlay);  // post, fork, band, aim guide
    for (const std::string& line : status_lines(state)) overlay.text(line);
  }
  [[nodiscard]] std::string summary() const { return describe(state); }
};

/// What app::run (and the page) run Slingshot with: its name (the rules name of its
/// recordings) and the whole level in view.
inline fixstep::app::Settings app_settings() {
  return {.name = "slingshot",
          .description = "drag the red ball back, let go, knock the targets off their ropes",
          .view_center = fixstep::Vec2{0.0, 9.0},  // the whole level, ground near the bottom
          .view_width = 46.0,                      // m: walls at the edges
          .controls = "mouse: drag the ball back and let go",
          // The grid, without the x = 0 axis through the middle of the playfield.
          .style = fixstep::ViewStyle{.axes = false}};
}

}  // namespace slingshot
