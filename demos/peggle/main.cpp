// peggle: aim with the pointer, shoot ten balls into the pegs, clear them. The level and the
// rules are game.hpp's; fixstep::app::run gives the game its window, recording, replay with
// verification, headless frames and the sync test:
//
//   peggle [--record FILE]                     play (mouse aims, click shoots; r restart; esc quit)
//   peggle --frames N [--out DIR]              N frames headless, the autopilot shooting
//   peggle --replay FILE [--out DIR [--every K]] [--last-frame PNG]
//   peggle --help                              the rest
#include <fixstep/app.hpp>
#include <fixstep/det_math.hpp>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace {

using namespace fixstep;

struct Peggle {
  peggle::GameState state;

  void setup(WorldDef& level) { level = peggle::make_level(); }
  void rules(World& world, const TickInput& input) { peggle::after_tick(state, input, world); }
  std::int64_t aimed_since = 0;  ///< autopilot: the frame the current aim began

  /// Headless: sweeps the aim across the field and shoots 0.75 s after each ball is gone.
  void autopilot(std::int64_t frame, const World& /*world*/, InputSampler& sampler) {
    const double t = static_cast<double>(frame) / 60.0;
    if (state.phase == peggle::Phase::aiming) {  // the pointer rests while a ball flies
      sampler.set_pointer(Vec2{7.0 * det::sin(0.9 * t + 0.4), 0.0});
    }
    sampler.release(button_action);  // the last frame's press, if any (a no-op otherwise)
    if (state.phase != peggle::Phase::aiming) {
      aimed_since = frame + 1;
    } else if (frame - aimed_since == 45) {
      sampler.press(button_action);
    }
  }
  void draw(app::Overlay& overlay) const {
    peggle::draw_game(state, overlay);
    for (const std::string& line : peggle::status_lines(state)) overlay.text(line);
  }
  [[nodiscard]] std::string summary() const { return peggle::describe(state); }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(
      Peggle{},
      {.name = "peggle",
       .description = "aim, shoot ten balls into the pegs and clear them",
       .view_center = Vec2{0.0, -0.6},  // the launcher to below the bucket
       .view_width = 38.0,
       .controls = "mouse: aim   click or enter: shoot",
       .style =
           ViewStyle{
               .background = {18, 20, 32, 255}, .grid = false, .axes = false, .scale_bar = true},
       .hud_text_scale = 1.4f},  // the HUD fits left of the field
      argc, argv);
}
