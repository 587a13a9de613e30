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

#include "game.hpp"

namespace {

using namespace fixstep;

struct Peggle {
  peggle::GameState state;

  void setup(WorldDef& level) { level = peggle::make_level(); }
  void rules(World& world, const TickInput& input) { peggle::after_tick(state, input, world); }
  /// Headless: sweeps the aim across the field and shoots every 4 s.
  void autopilot(std::int64_t frame, const World& /*world*/, InputSampler& sampler) {
    const double t = static_cast<double>(frame) / 60.0;
    sampler.set_pointer(Vec2{7.0 * det::sin(0.7 * t + 0.4), 0.0});
    if (frame % 240 == 40) sampler.press(button_action);
    if (frame % 240 == 41) sampler.release(button_action);
  }
  void draw(app::Overlay& overlay) const {
    for (std::string& line : peggle::status_lines(state)) overlay.text(std::move(line));
  }
  [[nodiscard]] std::string summary() const { return peggle::describe(state); }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(Peggle{},
                  {.name = "peggle",
                   .description = "aim, shoot ten balls into the pegs and clear them",
                   .view_center = Vec2{0.0, -0.5},
                   .view_width = 30.0,
                   .controls = "mouse: aim   click or enter: shoot"},
                  argc, argv);
}
