// slingshot: the game's drawing (draw.hpp).
#include "draw.hpp"

#include <cmath>
#include <cstdint>
#include <optional>

namespace slingshot {

using fixstep::Rgba8;
using fixstep::Vec2;

namespace {

constexpr double gravity = 9.81;  // m/s², as the level's
constexpr Rgba8 wood{150, 105, 60, 255};
constexpr Rgba8 wood_dark{110, 75, 40, 255};
constexpr Rgba8 rubber{120, 30, 30, 255};
constexpr Rgba8 aim{255, 255, 255, 255};
constexpr double post_half_width = 0.18;  // m
constexpr double fork_y = 1.9;            // m, where the post forks

/// The post from the ground to the fork, and the two prongs.
void draw_frame(fixstep::app::Overlay& o) {
  o.rect({anchor.x - post_half_width, 0.0}, {anchor.x + post_half_width, fork_y}, wood);
  // Each prong a quadrilateral from the fork to its tip, counter-clockwise: bottom left,
  // bottom right, top right, top left.
  constexpr double hw = post_half_width, base = fork_y - 0.3, tip_half = 0.12;
  const Vec2 left[4] = {{anchor.x - hw, base},
                        {anchor.x + 0.3 * hw, base},
                        {left_prong.x + tip_half, left_prong.y},
                        {left_prong.x - tip_half, left_prong.y}};
  const Vec2 right[4] = {{anchor.x - 0.3 * hw, base},
                         {anchor.x + hw, base},
                         {right_prong.x + tip_half, right_prong.y},
                         {right_prong.x - tip_half, right_prong.y}};
  o.polygon(left, wood_dark);
  o.polygon(right, wood_dark);
}

}  // namespace

Vec2 predicted_launch(Vec2 ball) {
  const double omega = 2.0 * 3.141592653589793 * band_frequency;
  const Vec2 d{anchor.x - ball.x, anchor.y - ball.y};
  const double pull = std::hypot(d.x, d.y);
  if (pull < min_pull) return {};
  const double speed2 = omega * omega * pull * pull - 2.0 * gravity * d.y;
  if (!(speed2 > 0.0)) return {};
  const double speed = std::sqrt(speed2);
  return {d.x / pull * speed, d.y / pull * speed};
}

void draw_slingshot(const GameState& game, fixstep::app::Overlay& o) {
  draw_frame(o);
  const fixstep::World* world = o.world();
  if (world == nullptr || game.phase != Phase::loaded) return;
  const std::optional<Vec2> at = o.position(ball(*world));
  if (!at) return;
  // The rubber, prong to ball to prong (behind the ball's disc: the world is drawn first, so it
  // lies over the ball; thin enough to read as the band holding it).
  o.line(left_prong, *at, 0.08, rubber);
  o.line(right_prong, *at, 0.08, rubber);
  const Vec2 v = predicted_launch(*at);
  if (v.x == 0.0 && v.y == 0.0) return;
  o.arrow(*at, anchor, 0.06, 0.35, Rgba8{255, 255, 255, 160});
  for (int k = 1; k <= aim_dots; ++k) {
    const double t = aim_seconds * k / aim_dots;
    const Vec2 p{anchor.x + v.x * t, anchor.y + v.y * t - 0.5 * gravity * t * t};
    const auto alpha = static_cast<std::uint8_t>(230.0 * (1.0 - double(k - 1) / aim_dots));
    o.disc(p, 0.14, Rgba8{aim.r, aim.g, aim.b, alpha});
  }
}

}  // namespace slingshot
