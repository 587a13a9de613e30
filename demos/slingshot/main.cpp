// slingshot: drag the red ball back on its rubber band, let go, and knock the targets off their
// ropes. The level and the rules are game.hpp's; fixstep::app::run gives the game its window,
// recording, replay with verification, headless frames and the sync test:
//
//   slingshot [--record FILE]                     play (mouse: drag the ball; r restart; esc quit)
//   slingshot --replay FILE [--out DIR [--every K]] [--last-frame PNG]
//   slingshot --help                              the rest
//
// Every tick of play runs the same steps, live or replayed:
//   input    the mouse, sampled for this tick (InputSampler), or the recording's input
//   prepare  the pointer may drag only the loaded ball (live only: the recording holds the
//            prepared input, drag_body included)
//   step     world.step(input): physics, with the pointer's drag spring
//   rules    cut the band, score the hits (world.impacts()), knock targets off, reload
// and every frame the game draws the slingshot and its aim guide over the world (draw.hpp).
#include <fixstep/app.hpp>
#include <fixstep/pointer_drag.hpp>
#include <string>

#include "draw.hpp"
#include "game.hpp"

namespace {

using namespace fixstep;

struct Slingshot {
  slingshot::GameState state;
  PointerDrag drag{0.3};  // m: a small ball is easy to grab

  void setup(WorldDef& level) { level = slingshot::make_level(); }
  void rules(World& world, const TickInput& input) { slingshot::after_tick(state, input, world); }
  void prepare(TickInput& input, const World& world) {
    slingshot::prepare_input(state, drag, input, world);
  }
  void draw(app::Overlay& overlay) const {
    slingshot::draw_slingshot(state, overlay);  // post, fork, band, aim guide
    for (const std::string& line : slingshot::status_lines(state)) overlay.text(line);
  }
  [[nodiscard]] std::string summary() const { return slingshot::describe(state); }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(Slingshot{},
                  {.name = "slingshot",
                   .description = "drag the red ball back, let go, knock the targets off their "
                                  "ropes",
                   .view_center = Vec2{0.0, 9.0},  // the whole level, ground near the bottom
                   .view_width = 46.0,             // m: walls at the edges
                   .controls = "mouse: drag the ball back and let go",
                   // The grid, without the x = 0 axis through the middle of the playfield.
                   .style = ViewStyle{.axes = false}},
                  argc, argv);
}
