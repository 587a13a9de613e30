// peggle: the game's drawing (draw.hpp).
#include "draw.hpp"

#include <cstdint>
#include <fixstep/core/det_math.hpp>
#include <fixstep/core/query.hpp>
#include <optional>

namespace peggle {

using fixstep::Rgba8;
using fixstep::Vec2;

namespace {

constexpr double gravity = 9.81;  // m/s², as the level's
constexpr Rgba8 metal{170, 175, 190, 255}, metal_dark{90, 95, 110, 255};
constexpr Rgba8 guide{255, 255, 255, 120}, target_ring{255, 240, 120, 255};
constexpr Rgba8 bucket_color{120, 200, 140, 200};
constexpr int aim_dots = 14;
constexpr double aim_seconds = 0.7;

/// The launcher: a barrel from the pivot along the aim, over a round base.
void draw_launcher(double aim, fixstep::app::Overlay& o) {
  const Vec2 u = launch_velocity(aim) / launch_speed, n{-u.y, u.x};
  const double half = 0.2, length = 1.1;
  const Vec2 barrel[4] = {launcher - n * half, launcher + n * half,
                          launcher + n * half + u * length, launcher - n * half + u * length};
  o.polygon(barrel, metal);
  o.disc(launcher, 0.45, metal_dark);
}

/// While aiming: the ball's path for aim_seconds (dots, fading) and the guide: a ray straight
/// ahead to the first peg it meets (World::cast_ray), that peg ringed.
void draw_aim(double aim, const fixstep::World& world, fixstep::app::Overlay& o) {
  const Vec2 v = launch_velocity(aim);
  for (int k = 1; k <= aim_dots; ++k) {
    const double t = aim_seconds * k / aim_dots;
    const Vec2 p{launcher.x + v.x * t, launcher.y + v.y * t - 0.5 * gravity * t * t};
    const auto alpha = static_cast<std::uint8_t>(230.0 * (1.0 - double(k - 1) / aim_dots));
    o.disc(p, 0.09, Rgba8{255, 255, 255, alpha});
  }
  if (const std::optional<fixstep::RayHit> hit = aim_guide(world, aim)) {
    o.line(launcher, hit->point, 0.04, guide);
    if (const std::optional<Vec2> peg = o.position(hit->body)) {
      o.circle(*peg, peg_radius + 0.12, 0.06, target_ring);
    }
  }
}

/// The bucket: a tray between the two rims, where they are drawn this frame.
void draw_bucket(const fixstep::World& world, fixstep::app::Overlay& o) {
  const std::optional<Vec2> left = o.position(world.find("rim_left"));
  const std::optional<Vec2> right = o.position(world.find("rim_right"));
  if (!left || !right) return;
  const double depth = 0.55;
  const Vec2 tray[4] = {*left, Vec2{left->x + 0.25, left->y - depth},
                        Vec2{right->x - 0.25, right->y - depth}, *right};
  o.polygon(tray, bucket_color);
}

}  // namespace

void draw_game(const GameState& game, fixstep::app::Overlay& o) {
  const fixstep::World* world = o.world();
  if (world == nullptr) return;
  draw_bucket(*world, o);
  if (game.phase == Phase::aiming) draw_aim(game.aim, *world, o);
  draw_launcher(game.aim, o);
}

}  // namespace peggle
