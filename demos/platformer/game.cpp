// platformer: the level and the rules (game.hpp).
#include "game.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fixstep/core/mover.hpp>
#include <fixstep/core/segment.hpp>
#include <fixstep/core/shape.hpp>
#include <fixstep/core/world_settings.hpp>

namespace platformer {

namespace {

using fixstep::BodyDef;
using fixstep::BodyType;
using fixstep::Vec2;

constexpr double dt = 1.0 / 120.0;

void add_floor(fixstep::WorldDef& def) {
  // A wall, the floor, a 45° ramp up to a ledge, a drop, the floor on to a far wall.
  const std::array<Vec2, 8> floor{{{-12.0, 10.0},
                                   {-12.0, 0.0},
                                   {3.0, 0.0},
                                   {6.0, 3.0},
                                   {10.0, 3.0},
                                   {10.0, 0.0},
                                   {34.0, 0.0},
                                   {34.0, 10.0}}};
  def.add_polyline(floor, 0.0, 0.6);
  for (fixstep::SegmentDef& s : def.segments) s.color = {150, 160, 180, 255}, s.width = 0.08;
  // Two one-way platforms: up through them from below, land on them from above.
  for (const auto& [a, b] :
       {std::pair{Vec2{15.0, 1.8}, Vec2{18.0, 1.8}}, std::pair{Vec2{19.5, 3.4}, Vec2{22.5, 3.4}}}) {
    fixstep::SegmentDef s{.a = a, .b = b, .friction = 0.6};
    s.one_way = true;
    s.color = {240, 170, 60, 255};  // drawn apart from the two-sided floor
    s.width = 0.06;
    def.segments.push_back(s);
  }
}

BodyDef static_box(const char* name, Vec2 at, double hx, double hy) {
  BodyDef b;
  b.name = name;
  b.type = BodyType::static_body;
  b.body.position = at;
  b.shapes = {fixstep::make_box(hx, hy)};
  b.appearance = fixstep::Appearance{.radius = hx, .color = {120, 110, 100, 255}};
  return b;
}

void add_bodies(fixstep::WorldDef& def) {
  // The step: 0.15 m high, below the mover's step height.
  def.add_body(static_box("step", {12.5, 0.075}, 0.75, 0.075));
  BodyDef crate;
  crate.name = "crate";
  crate.body = fixstep::Body{.mass = 10.0, .position = {-9.5, 0.4}};
  crate.gravity = fixstep::Gravity{{0.0, -gravity}};
  crate.shapes = {fixstep::make_box(0.4, 0.4)};
  crate.shapes[0].friction = 0.4;
  crate.appearance = fixstep::Appearance{.radius = 0.4, .color = {176, 120, 64, 255}};
  def.add_body(crate);
  BodyDef platform = static_box("platform", {26.0, 2.0}, 1.5, 0.15);
  platform.type = BodyType::kinematic;
  platform.appearance->color = {90, 140, 200, 255};
  def.add_body(platform);
  BodyDef player;
  player.name = "player";
  player.type = BodyType::kinematic;
  player.body.position = {-7.0, 0.8};
  player.shapes = {fixstep::make_capsule({0.0, -0.4}, {0.0, 0.4}, 0.3)};
  player.mover = fixstep::MoverDef{.step_height = 0.2, .snap_distance = 0.15, .push_force = 150.0};
  player.appearance = fixstep::Appearance{.radius = 0.3, .color = {230, 87, 46, 255}};
  def.add_body(player);
  // Coins: drawn, no collider (collected within coin_reach of the player's centre).
  const std::array<Vec2, 7> coins{
      {{-4.5, 1.0}, {4.5, 2.6}, {8.0, 3.8}, {16.5, 2.6}, {21.0, 4.2}, {25.0, 2.6}, {31.0, 0.8}}};
  for (std::size_t i = 0; i < coins.size(); ++i) {
    BodyDef coin;
    coin.name = "coin" + std::to_string(i);
    coin.type = BodyType::static_body;
    coin.body.position = coins[i];
    coin.user_data = coin_tag;
    coin.appearance = fixstep::Appearance{.radius = 0.25, .color = {250, 205, 40, 255}};
    def.add_body(coin);
  }
}

}  // namespace

fixstep::WorldDef make_level() {
  fixstep::WorldDef def;
  def.settings = {.dt = dt, .integrator = fixstep::Integrator::semi_implicit_euler};
  def.settings.contacts = fixstep::ContactSettings{.restitution = 0.0, .friction = 0.6};
  add_floor(def);
  add_bodies(def);
  return def;
}

void start(GameState& game, const fixstep::WorldDef& level) {
  game.player = level.find_body("player");
  game.platform = level.find_body("platform");
  game.coins_total =
      static_cast<int>(std::count_if(level.bodies.begin(), level.bodies.end(),
                                     [](const BodyDef& b) { return b.user_data == coin_tag; }));
  game.x = level.bodies[game.player.index1 - 1].body.position.x;
}

void rules(GameState& game, const fixstep::TickInput& input, fixstep::World& world) {
  const fixstep::MoverState& m = world.mover_state(game.player);
  Vec2 v = m.velocity;
  const double speed = (input.held & run_action) != 0 ? run_speed : walk_speed;
  v.x = input.axes[walk_axis] * speed;
  if (m.on_floor && (input.pressed & jump_action) != 0) {
    v.y = jump_speed;
    ++game.jumps;
  } else if (!m.on_floor) {
    v.y = std::max(v.y - gravity * dt, -fall_limit);
  }
  world.set_velocity(game.player, v);
  // Back and forth, half a period each way, from the tick alone (replays and rollbacks agree).
  const bool out = world.tick() / platform_half_period % 2 == 0;
  world.set_velocity(game.platform, {out ? platform_speed : -platform_speed, 0.0});
  const Vec2 at = world.body(game.player).position;
  for (const fixstep::Entity e : world.bodies()) {
    if (world.user_data(e) != coin_tag) continue;
    const Vec2 d = world.body(e).position - at;
    if (d.x * d.x + d.y * d.y <= coin_reach * coin_reach) {
      world.destroy(e);
      ++game.coins;
      break;  // bodies() changed: the next coin next tick
    }
  }
  game.x = at.x;
  game.on_floor = m.on_floor;
}

std::string describe(const GameState& game) {
  char line[96];
  std::snprintf(line, sizeof line, "coins=%d/%d jumps=%d x=%.2f on_floor=%d", game.coins,
                game.coins_total, game.jumps, game.x, game.on_floor ? 1 : 0);
  return line;
}

}  // namespace platformer
