// pinball: the table and the rules (see game.hpp).
#include "game.hpp"

#include <algorithm>
#include <cmath>
#include <fixstep/core/components.hpp>
#include <fixstep/core/det_math.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/joint.hpp>
#include <fixstep/core/shape.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <string>

namespace pinball {

using fixstep::Body;
using fixstep::BodyDef;
using fixstep::BodyType;
using fixstep::Entity;
using fixstep::Vec2;

namespace {

constexpr fixstep::Rgba8 ball_color{230, 232, 240, 255}, flipper_color{240, 200, 70, 255};
constexpr fixstep::Rgba8 bumper_color{220, 60, 90, 255}, slingshot_color{70, 170, 230, 255};
constexpr double wall_restitution = 0.35, wall_friction = 0.1;
constexpr int lit_ticks = 18;  // a bumper stays lit 0.15 s after a hit

/// Where the bumpers stand, m.
constexpr std::array<Vec2, bumper_count> bumpers{{{-1.4, 9.6}, {1.4, 9.6}, {0.0, 11.6}}};

/// The left slingshot, counter-clockwise; the right one is its mirror. Its kicking face is the
/// edge from corner 1 to corner 2 (the long side, facing the middle of the table).
constexpr std::array<Vec2, 3> left_slingshot{{{-3.16, 3.48}, {-2.16, 2.83}, {-3.16, 4.8}}};

Vec2 mirror(Vec2 p) {
  return {-p.x, p.y};
}

/// The outward unit normal of a slingshot's kicking face (side -1 left, +1 right).
Vec2 kick_normal(double side) {
  const Vec2 a = left_slingshot[1], b = left_slingshot[2];
  const Vec2 d = b - a;
  const Vec2 n = Vec2{d.y, -d.x} / fixstep::length(d);  // outward for a counter-clockwise edge
  return side < 0 ? n : mirror(n);
}

Vec2 ball_rest() {
  return {lane_x, plunger_y + ball_radius};  // touching the plunger's top
}

BodyDef static_body(std::string name, Vec2 at, fixstep::ShapeDef shape, fixstep::Rgba8 color,
                    std::uint64_t tag) {
  BodyDef b;
  b.name = std::move(name);
  b.type = BodyType::static_body;
  b.body.position = at;
  b.shapes = {shape};
  b.appearance = fixstep::Appearance{.color = color, .trail = false};
  b.user_data = tag;
  return b;
}

/// A flipper (side -1 left, +1 right): a tapered, rounded polygon from its pivot to its tip,
/// dynamic, at its rest angle (its joint: flipper_joint).
BodyDef flipper(double side) {
  const double l = flipper_length, wide = 0.2, narrow = 0.08;
  std::array<Vec2, 4> pts{{{0, -wide}, {l, -narrow}, {l, narrow}, {0, wide}}};
  if (side > 0) pts = {{{0, wide}, {-l, narrow}, {-l, -narrow}, {0, -wide}}};  // mirrored
  BodyDef b;
  b.name = side < 0 ? "flipper_left" : "flipper_right";
  b.body = Body{.mass = flipper_mass, .position = {side * flipper_x, flipper_y}};
  b.body.angle = side < 0 ? flipper_rest : -flipper_rest;
  fixstep::ShapeDef s = fixstep::make_polygon(pts, 0.05);
  s.restitution = 0.2;
  s.friction = 0.4;
  b.shapes = {s};
  b.appearance = fixstep::Appearance{.color = flipper_color, .trail = false};
  b.user_data = flipper_tag;
  b.gravity = fixstep::Gravity{{0.0, -gravity}};
  return b;
}

/// The revolute joint of a flipper (body `e`) to the table at its pivot: limited between its
/// rest angle (the joint's 0) and its raised one, its motor holding it down at the start.
fixstep::JointDef flipper_joint(double side, Entity e) {
  const double swing = side * (flipper_rest - flipper_raised);  // raised, from rest
  return {.type = fixstep::JointType::revolute,
          .body_b = e,
          .anchor = {side * flipper_x, flipper_y},
          .lower = std::min(0.0, swing),
          .upper = std::max(0.0, swing),
          .motor_speed = side * flipper_speed,
          .max_motor_torque = flipper_torque,
          .name = side < 0 ? "flipper_left" : "flipper_right"};
}

void add_walls(fixstep::WorldDef& def) {
  // The outer wall: from the left inlane's foot up the left side, over the top arc (centre
  // (0.5, 10.5), radius 5) and down the lane's outer side to the floor. Each inlane's foot
  // lies on its flipper's top at rest, so a ball rolls from one onto the other: a foot lower
  // than the flipper's back end made a notch in which a ball lay for ever.
  std::vector<Vec2> outer{{-flipper_x - 0.15, flipper_y + 0.4}, {-half_width, 3.4}};
  constexpr double pi = 3.141592653589793;
  for (int k = 0; k <= 12; ++k) {
    const double a = pi - pi * k / 12.0;
    outer.push_back({0.5 + 5.0 * fixstep::det::cos(a), 10.5 + 5.0 * fixstep::det::sin(a)});
  }
  outer.push_back({half_width + 1.0, 0.0});
  def.add_polyline(outer, wall_restitution, wall_friction);
  // The right inlane's slope to the right flipper, and the wall between field and lane.
  const std::array<Vec2, 3> right{
      {{flipper_x + 0.15, flipper_y + 0.4}, {half_width, 3.4}, {half_width, 9.5}}};
  def.add_polyline(right, wall_restitution, wall_friction);
  const std::array<Vec2, 2> lane_foot{{{half_width, 0.0}, {half_width, 3.4}}};
  def.add_polyline(lane_foot, wall_restitution, wall_friction);
  // The plunger's top, across the lane: the ball rests on it.
  const std::array<Vec2, 2> plunger{{{half_width, plunger_y}, {half_width + 1.0, plunger_y}}};
  def.add_polyline(plunger, 0.0, 0.5);
}

/// Kicks the ball off a surface of outward normal `n` (unit) at `speed` (m/s): an impulse along
/// n that brings the ball's speed away from it up to `speed` (none if it leaves faster), so a
/// kick gives the ball a set speed rather than adding to its bounce (two slingshots would
/// otherwise keep a ball between them for ever).
void kick(fixstep::World& sim, Entity ball, Vec2 n, double speed) {
  const Vec2 v = sim.body(ball).velocity;
  sim.set_velocity(ball, v + n * std::max(0.0, speed - dot(v, n)));
}

/// Scores and kicks the ball off what it began touching this tick.
void score_hits(GameState& game, fixstep::World& sim, Entity ball) {
  for (const fixstep::ContactEvent& c : sim.contacts_begun()) {
    const Entity other = c.a == ball ? c.b : (c.b == ball ? c.a : Entity{});
    if (!sim.contains(other)) continue;
    const std::uint64_t tag = sim.user_data(other);
    const Vec2 at = sim.body(ball).position;
    if (tag >= bumper_tag && tag < bumper_tag + bumper_count) {
      const Vec2 d = at - sim.body(other).position;
      kick(sim, ball, d / fixstep::length(d), bumper_kick);
      game.score += bumper_points;
      ++game.bumper_hits;
      game.lit[tag - bumper_tag] = lit_ticks;
    } else if (tag == slingshot_tag) {
      const double side = at.x < 0 ? -1.0 : 1.0;  // the slingshot on the ball's side
      const Vec2 face = side < 0 ? left_slingshot[1] : mirror(left_slingshot[1]);
      const Vec2 n = kick_normal(side);
      if (dot(at - face, n) < 0.0) continue;  // on its short sides: no kick
      kick(sim, ball, n, slingshot_kick);
      game.score += slingshot_points;
      ++game.slingshot_hits;
    }
  }
}

/// The plunger: held, it pulls (up to a full pull); let go after a pull, it launches the ball
/// resting on it.
void plunger(GameState& game, const fixstep::TickInput& input, fixstep::World& sim, Entity ball) {
  if (!on_plunger(sim)) {
    game.pull = 0;
    // Launched: the ball has left the plunger's foot of the lane.
    if (game.phase == Phase::launch && sim.body(ball).position.y > plunger_y + 2.0) {
      game.phase = Phase::play;
    }
    return;
  }
  game.phase = Phase::launch;  // back on the plunger (a launch too weak to leave the lane)
  if ((input.held & plunger_keys) != 0) {
    game.pull = std::min(game.pull + 1, full_pull_ticks);
  } else if (game.pull > 0) {
    const double speed = launch_min + (launch_max - launch_min) * game.pull / full_pull_ticks;
    sim.set_velocity(ball, {0.0, speed});
    game.pull = 0;
  }
}

/// A drained ball: the next one on the plunger, or the game is over.
void drain(GameState& game, fixstep::World& sim, Entity ball) {
  --game.balls_left;
  sim.set_body(ball, Body{.mass = ball_mass, .position = ball_rest()});
  game.pull = 0;
  game.phase = game.balls_left > 0 ? Phase::launch : Phase::over;
}

}  // namespace

fixstep::WorldDef make_table() {
  fixstep::WorldDef def;
  def.settings = {.dt = dt, .integrator = fixstep::Integrator::semi_implicit_euler};
  def.settings.contacts =
      fixstep::ContactSettings{.restitution = wall_restitution, .friction = wall_friction};
  add_walls(def);
  for (const double side : {-1.0, 1.0}) {
    std::array<Vec2, 3> tri = left_slingshot;
    if (side > 0)
      tri = {mirror(left_slingshot[0]), mirror(left_slingshot[2]),
             mirror(left_slingshot[1])};  // counter-clockwise again
    fixstep::ShapeDef s = fixstep::make_polygon(tri, 0.04);
    s.restitution = 0.5;
    def.bodies.push_back(static_body(side < 0 ? "slingshot_left" : "slingshot_right", {}, s,
                                     slingshot_color, slingshot_tag));
  }
  for (int i = 0; i < bumper_count; ++i) {
    fixstep::ShapeDef s = fixstep::make_circle(bumper_radius);
    s.restitution = 0.6;
    def.bodies.push_back(static_body("bumper" + std::to_string(i), bumpers[i], s, bumper_color,
                                     bumper_tag + std::uint64_t(i)));
  }
  for (const double side : {-1.0, 1.0}) {
    const Entity e = def.add_body(flipper(side));
    def.joints.push_back(flipper_joint(side, e));
  }
  BodyDef ball;
  ball.name = "ball";
  ball.body = Body{.mass = ball_mass, .position = ball_rest()};
  fixstep::ShapeDef s = fixstep::make_circle(ball_radius);
  s.friction = 0.2;
  ball.shapes = {s};
  ball.gravity = fixstep::Gravity{{0.0, -gravity}};
  ball.appearance = fixstep::Appearance{.color = ball_color, .trail = true, .trail_time = 0.3};
  ball.user_data = ball_tag;
  def.bodies.push_back(ball);
  return def;
}

void prepare_input(fixstep::TickInput& input, const fixstep::World& sim) {
  for (const double side : {-1.0, 1.0}) {
    const fixstep::Joint j = sim.find_joint(side < 0 ? "flipper_left" : "flipper_right");
    if (!sim.contains(j)) continue;
    const bool up = (input.held & (side < 0 ? left_flipper_key : right_flipper_key)) != 0;
    const double speed = (up ? -side : side) * flipper_speed;  // up: the left one turns +
    input.joints.push_back({j, fixstep::JointInputKind::motor_speed, {speed, 0.0}});
  }
}

bool on_plunger(const fixstep::World& sim) {
  const Body b = sim.body(sim.find("ball"));
  return std::abs(b.position.x - lane_x) < 0.3 && b.position.y < plunger_y + ball_radius + 0.1 &&
         fixstep::length(b.velocity) < 0.5;
}

void after_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim) {
  for (int& t : game.lit) t = std::max(t - 1, 0);
  if (game.phase == Phase::over) return;
  const Entity ball = sim.find("ball");
  score_hits(game, sim, ball);
  plunger(game, input, sim, ball);
  if (sim.body(ball).position.y < drain_y) drain(game, sim, ball);
}

std::vector<std::string> status_lines(const GameState& game) {
  std::vector<std::string> lines{"score " + std::to_string(game.score) + "   balls " +
                                 std::to_string(game.balls_left)};
  switch (game.phase) {
    case Phase::launch:
      lines.emplace_back(game.pull > 0
                             ? "pull " + std::to_string(100 * game.pull / full_pull_ticks) + "%"
                             : "hold down to pull the plunger, let go");
      break;
    case Phase::play:
      lines.emplace_back("bumpers " + std::to_string(game.bumper_hits));
      break;
    case Phase::over:
      lines.emplace_back("GAME OVER: " + std::to_string(game.score) + " points   (r plays again)");
      break;
  }
  return lines;
}

std::string describe(const GameState& game) {
  static constexpr const char* phases[] = {"launch", "play", "over"};
  return "score=" + std::to_string(game.score) + " balls=" + std::to_string(game.balls_left) +
         " bumpers=" + std::to_string(game.bumper_hits) +
         " slingshots=" + std::to_string(game.slingshot_hits) +
         " phase=" + phases[static_cast<int>(game.phase)];
}

}  // namespace pinball
