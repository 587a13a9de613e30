// stacker: the game's drawing (draw.hpp).
#include "draw.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>

namespace stacker {

using fixstep::Rgba8;
using fixstep::Vec2;

namespace {

constexpr double gravity = 9.81;  // m/s², as the level's
constexpr Rgba8 post_color{110, 75, 40, 255};
constexpr Rgba8 rubber{90, 20, 20, 255};
constexpr Vec2 fork{anchor.x, anchor.y - 1.2};               // m, where the post forks
constexpr Vec2 left_prong{anchor.x - 0.75, anchor.y + 0.3};  // m, where the band is tied
constexpr Vec2 right_prong{anchor.x + 0.75, anchor.y + 0.3};
constexpr double aim_seconds = 1.5;  // s of flight the guide shows
constexpr int aim_dots = 15;

}  // namespace

Vec2 predicted_launch(Vec2 ball) {
  const double omega = 2.0 * std::numbers::pi * band_frequency;
  const Vec2 d{anchor.x - ball.x, anchor.y - ball.y};
  const double pull = std::hypot(d.x, d.y);
  if (pull < min_pull) return {};
  const double speed2 = omega * omega * pull * pull - 2.0 * gravity * d.y;
  if (!(speed2 > 0.0)) return {};
  const double speed = std::sqrt(speed2);
  return {d.x / pull * speed, d.y / pull * speed};
}

void draw_game(const GameState& game, fixstep::app::Overlay& o) {
  // The post from the ground to the fork, and the fork: two thick lines to the prongs.
  o.rect({anchor.x - 0.15, 0.0}, {anchor.x + 0.15, fork.y + 0.1}, post_color);
  o.line(fork, left_prong, 0.22, post_color);
  o.line(fork, right_prong, 0.22, post_color);
  const fixstep::World* world = o.world();
  if (world == nullptr || game.phase != Phase::loaded) return;
  const std::optional<Vec2> at = o.position(ball(*world));
  if (!at) return;
  o.line(left_prong, *at, 0.08, rubber);
  o.line(right_prong, *at, 0.08, rubber);
  const Vec2 v = predicted_launch(*at);
  if (v.x == 0.0 && v.y == 0.0) return;
  for (int k = 1; k <= aim_dots; ++k) {
    const double t = aim_seconds * k / aim_dots;
    const Vec2 p{anchor.x + v.x * t, anchor.y + v.y * t - 0.5 * gravity * t * t};
    const auto alpha = static_cast<std::uint8_t>(230.0 * (1.0 - double(k - 1) / aim_dots));
    o.disc(p, 0.12, Rgba8{255, 255, 255, alpha});
  }
}

}  // namespace stacker
