// airhockey: the level, the players' merged input and the rules (see game.hpp).
#include "game.hpp"

#include <algorithm>
#include <cmath>
#include <fixstep/core/components.hpp>
#include <fixstep/core/det_math.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <string>

namespace airhockey {

using fixstep::BodyDef;
using fixstep::BodyType;
using fixstep::Entity;
using fixstep::Vec2;

namespace {

constexpr double wall_restitution = 0.9;
constexpr double puck_drag = 0.15;    // 1/s: the puck loses this fraction of its speed a second
constexpr double mallet_gain = 14.0;  // 1/s: a mallet closes this fraction of its gap a second
constexpr double serve_speed = 2.5;   // m/s
constexpr double still_speed = 0.05;  // m/s: below it the puck counts as still
constexpr int still_limit = 3 * 120;  // ticks: a still puck is served again
constexpr std::uint32_t arrows =
    fixstep::button_left | fixstep::button_right | fixstep::button_up | fixstep::button_down;
constexpr const char* mallet_names[2] = {"mallet0", "mallet1"};
constexpr const char* goal_names[2] = {"goal0", "goal1"};

BodyDef disc(const char* name, Vec2 at, double r, BodyType type, fixstep::Rgba8 color) {
  BodyDef b;
  b.name = name;
  b.type = type;
  b.body.position = at;
  b.collider = fixstep::Collider{r};
  b.appearance = fixstep::Appearance{.radius = r, .color = color};
  b.appearance->trail = false;
  return b;
}

Vec2 clamp_into(Vec2 p, const Reach& r) {
  return {std::clamp(p.x, r.lo.x, r.hi.x), std::clamp(p.y, r.lo.y, r.hi.y)};
}

/// Player `i`'s mallet velocity from its input, m/s.
Vec2 mallet_velocity(int i, const fixstep::TickInput& in, const fixstep::World& world) {
  const Vec2 at = world.body(world.find(mallet_names[i])).position;
  const Reach r = reach(i);
  Vec2 v{};
  if ((in.held & arrows) != 0) {
    v.x = ((in.held & fixstep::button_right) ? 1.0 : 0.0) -
          ((in.held & fixstep::button_left) ? 1.0 : 0.0);
    v.y = ((in.held & fixstep::button_up) ? 1.0 : 0.0) -
          ((in.held & fixstep::button_down) ? 1.0 : 0.0);
    v = v * mallet_speed;
  } else {
    v = (clamp_into(in.pointer, r) - at) * mallet_gain;
  }
  const double speed = std::sqrt(v.x * v.x + v.y * v.y);
  if (speed > mallet_speed) v = v * (mallet_speed / speed);
  // Never out of its reach: the step lands inside it.
  const Vec2 next = clamp_into(at + v * dt, r);
  return (next - at) / dt;
}

void serve(GameState& game, fixstep::World& sim) {
  const Entity puck = sim.find("puck");
  sim.set_position(puck, Vec2{0.0, 0.0});
  const double toward = game.serve_to == 0 ? -1.0 : 1.0;
  const double slant = (game.score[0] + game.score[1]) % 2 == 0 ? 0.35 : -0.35;
  sim.set_velocity(puck, Vec2{toward * serve_speed, slant * serve_speed});
  game.still_ticks = 0;
}

/// A goal into player `defender`'s goal: the other scores; the puck rests at the centre.
void goal(GameState& game, fixstep::World& sim, int defender) {
  ++game.score[1 - defender];
  game.over = game.score[1 - defender] >= winning_score;
  game.serve_to = defender;
  game.serve_wait = serve_ticks;
  const Entity puck = sim.find("puck");
  sim.set_position(puck, Vec2{0.0, 0.0});
  sim.set_velocity(puck, Vec2{0.0, 0.0});
}

/// Drag, and the puck's top speed (so no mallet can fire it through a wall in one tick).
void slow_puck(GameState& game, fixstep::World& sim) {
  const Entity puck = sim.find("puck");
  Vec2 v = sim.body(puck).velocity * (1.0 - puck_drag * dt);
  const double speed = std::sqrt(v.x * v.x + v.y * v.y);
  if (speed > puck_top_speed) v = v * (puck_top_speed / speed);
  sim.set_velocity(puck, v);
  game.still_ticks = speed < still_speed ? game.still_ticks + 1 : 0;
}

}  // namespace

Reach reach(int player) {
  const double side = player == 0 ? -1.0 : 1.0;
  const double inner = mallet_radius, outer = half_length - goal_radius - mallet_radius;
  const double y = half_width - mallet_radius;
  return side < 0 ? Reach{{-outer, -y}, {-inner, y}} : Reach{{inner, -y}, {outer, y}};
}

fixstep::WorldDef make_level() {
  fixstep::WorldDef def;
  def.settings = {.dt = dt, .integrator = fixstep::Integrator::semi_implicit_euler};
  def.settings.contacts = fixstep::ContactSettings{.restitution = 0.9, .friction = 0.0};
  BodyDef puck = disc("puck", {0.0, 0.0}, puck_radius, BodyType::dynamic, {250, 220, 60, 255});
  puck.body.mass = 0.05;
  puck.body.velocity = {-serve_speed, 0.35 * serve_speed};
  puck.appearance->trail = true;
  def.bodies.push_back(puck);
  def.bodies.push_back(
      disc(mallet_names[0], {-2.6, 0.0}, mallet_radius, BodyType::kinematic, {230, 70, 70, 255}));
  def.bodies.push_back(
      disc(mallet_names[1], {2.6, 0.0}, mallet_radius, BodyType::kinematic, {70, 130, 240, 255}));
  for (int i = 0; i < 2; ++i) {
    const double x = i == 0 ? -half_length : half_length;
    BodyDef g =
        disc(goal_names[i], {x, 0.0}, goal_radius, BodyType::static_body, {255, 255, 255, 40});
    g.collider->sensor = true;
    g.appearance->visible = false;  // the game draws the creases
    def.bodies.push_back(g);
  }
  const double r = wall_restitution;
  def.planes.push_back({.normal = {1, 0}, .offset = -half_length, .restitution = r});
  def.planes.push_back({.normal = {-1, 0}, .offset = -half_length, .restitution = r});
  def.planes.push_back({.normal = {0, 1}, .offset = -half_width, .restitution = r});
  def.planes.push_back({.normal = {0, -1}, .offset = -half_width, .restitution = r});
  return def;
}

fixstep::TickInput merge(std::span<const fixstep::TickInput> players, const fixstep::World& world) {
  fixstep::TickInput out;
  if (!players.empty()) {
    out.tick = players[0].tick;
    out.pointer = players[0].pointer;
  }
  for (int i = 0; i < 2; ++i) {
    const Vec2 v = i < static_cast<int>(players.size())
                       ? mallet_velocity(i, players[static_cast<std::size_t>(i)], world)
                       : Vec2{};
    out.bodies.push_back({world.find(mallet_names[i]), fixstep::BodyInputKind::velocity, v});
  }
  return out;
}

fixstep::TickInput computer_input(int player, const fixstep::World& world) {
  const Vec2 puck = world.body(world.find("puck")).position;
  const Reach r = reach(player);
  const bool mine = player == 0 ? puck.x < 0.0 : puck.x > 0.0;
  const double home = player == 0 ? r.lo.x : r.hi.x;
  fixstep::TickInput in;
  in.pointer = mine ? puck : Vec2{home, puck.y * 0.5};
  return in;
}

Vec2 bot_pointer(int player, std::int64_t tick) {
  const double t = static_cast<double>(tick) * dt, phase = player == 0 ? 0.0 : 1.7;
  const double side = player == 0 ? -1.0 : 1.0;
  return {side * (1.2 + 2.0 * fixstep::det::sin(4.3 * t + phase)),
          2.0 * fixstep::det::sin((0.7 + 0.23 * player) * t + phase)};
}

void after_tick(GameState& game, fixstep::World& sim) {
  if (game.serve_wait > 0) {
    if (--game.serve_wait == 0 && !game.over) serve(game, sim);
    return;
  }
  const Entity puck = sim.find("puck");
  for (const fixstep::SensorEvent& s : sim.sensors_begun()) {
    if (s.visitor != puck) continue;
    for (int i = 0; i < 2; ++i) {
      if (s.sensor == sim.find(goal_names[i])) return goal(game, sim, i);
    }
  }
  slow_puck(game, sim);
  if (game.still_ticks > still_limit) serve(game, sim);
}

std::vector<std::string> status_lines(const GameState& game) {
  std::vector<std::string> lines{"red " + std::to_string(game.score[0]) + " : " +
                                 std::to_string(game.score[1]) + " blue"};
  if (game.over) {
    lines.emplace_back(game.score[0] > game.score[1] ? "RED WINS" : "BLUE WINS");
  } else if (game.serve_wait > 0) {
    lines.emplace_back("goal!");
  }
  return lines;
}

std::string describe(const GameState& game) {
  return "red=" + std::to_string(game.score[0]) + " blue=" + std::to_string(game.score[1]) +
         " over=" + std::to_string(game.over ? 1 : 0);
}

}  // namespace airhockey
