// A game draws: shapes over the world with app::Overlay, after the bodies and under the HUD.
// A ball bounces on the ground; the game draws its velocity as an arrow and a label that follow
// it (at its drawn, interpolated position), a dashed line to where it will land, and a screen
// corner badge; a second ball is simulated but hidden (Appearance::visible), its place drawn as a
// ring. The view has no grid (ViewStyle) and the HUD sits bottom right, in small text.
//
//   10_overlay --frames 100 --last-frame OUT.png      headless, the last frame as PNG
//   10_overlay                                         in a window
#include <cmath>
#include <cstdio>
#include <fixstep/app/app.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <optional>

namespace {

using namespace fixstep;

constexpr double g = 9.81;  // m/s²

struct Overlaid {
  Entity ball, ghost;

  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
    BodyDef b;
    b.body = Body{.mass = 1.0, .position = {-4.0, 3.0}, .velocity = {2.0, 4.0}};
    b.gravity = Gravity{};
    b.collider = Collider{.radius = 0.3};
    b.appearance = Appearance{.radius = 0.3, .color = {230, 70, 60, 255}, .trail_time = 1.5};
    ball = level.add_body(b);
    b.body.position = {3.0, 4.0};
    b.body.velocity = {-1.0, 0.0};
    b.appearance->visible = false;  // simulated, collides, but not drawn: the game draws it
    ghost = level.add_body(b);
    level.planes.push_back({.normal = {0, 1}, .offset = 0, .restitution = 0.8, .friction = 0});
  }
  void rules(World&, const TickInput&) {}

  void draw(app::Overlay& o) const {
    const World* world = o.world();
    if (const std::optional<Vec2> p = o.position(ball); p && world) {
      const Vec2 v = world->body(ball).velocity;
      o.arrow(*p, {p->x + 0.4 * v.x, p->y + 0.4 * v.y}, 0.06, 0.3, {255, 255, 255, 220});
      char speed[32];
      std::snprintf(speed, sizeof speed, "%.1f m/s", std::hypot(v.x, v.y));
      o.label({p->x + 0.45, p->y - 0.1}, speed, 2.0, {255, 255, 255, 255});
      // Where it lands: y(t) = y + vy t - g t²/2 = 0.3 (its radius), the later root.
      const double a = 0.5 * g, b = -v.y, c = 0.3 - p->y;
      const double t = (-b + std::sqrt(std::max(0.0, b * b - 4 * a * c))) / (2 * a);
      const Vec2 land{p->x + v.x * t, 0.3};
      for (int k = 0; k < 10; ++k) {  // a dashed line, one dash in two
        const double s0 = k / 10.0, s1 = s0 + 0.05;
        o.line({p->x + (land.x - p->x) * s0, p->y + (land.y - p->y) * s0},
               {p->x + (land.x - p->x) * s1, p->y + (land.y - p->y) * s1}, 0.04,
               {250, 200, 60, 200});
      }
      o.circle(land, 0.3, 0.05, {250, 200, 60, 255});
    }
    if (const std::optional<Vec2> q = o.position(ghost)) {
      o.circle(*q, 0.3, 0.04, {120, 200, 255, 255});  // the hidden ball, as a ring
    }
    o.rect({o.width() - 170.0, 10.0}, {o.width() - 10.0, 40.0}, {40, 120, 90, 200}, Space::screen);
    o.label({o.width() - 160.0, 18.0}, "overlay demo", 2.0, {255, 255, 255, 255}, Space::screen);
  }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(Overlaid{},
                  {.name = "10_overlay",
                   .description = "a game that draws over its world (app::Overlay)",
                   .width = 640,
                   .height = 360,
                   .view_center = Vec2{0.0, 3.0},
                   .view_width = 12.0,
                   .style = ViewStyle{.grid = false},
                   .hud_corner = HudCorner::bottom_right,
                   .hud_text_scale = 1.0f},
                  argc, argv);
}
