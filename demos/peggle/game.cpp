// peggle: the level and the rules (see game.hpp).
#include "game.hpp"

#include <algorithm>
#include <fixstep/core/components.hpp>
#include <fixstep/core/det_math.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/query.hpp>
#include <fixstep/core/random.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <string>

namespace peggle {

using fixstep::Body;
using fixstep::BodyDef;
using fixstep::BodyType;
using fixstep::Entity;
using fixstep::Vec2;

namespace {

constexpr double gravity = 9.81;                // m/s²
constexpr int flight_limit = 25 * 120;          // ticks: a ball stuck on pegs ends its turn
constexpr std::uint64_t orange_bit = 1u << 20;  // in a peg's user data
constexpr fixstep::Rgba8 blue{70, 130, 240, 255}, orange{250, 140, 40, 255};
constexpr fixstep::Rgba8 lit_blue{170, 215, 255, 255}, lit_orange{255, 225, 130, 255};
constexpr fixstep::Rgba8 ball_color{245, 245, 245, 255}, rim_color{200, 200, 210, 255};

BodyDef disc(std::string name, Vec2 at, double r, BodyType type, fixstep::Rgba8 color) {
  BodyDef b;
  b.name = std::move(name);
  b.type = type;
  b.body.position = at;
  b.collider = fixstep::Collider{r};
  b.appearance = fixstep::Appearance{.radius = r, .color = color};
  b.appearance->trail = false;  // pegs and the bucket stand still or glide: no trails
  return b;
}

bool orange_peg(const fixstep::World& sim, Entity e) {
  return (sim.user_data(e) & orange_bit) != 0;
}

/// The first tick: rolls which pegs are orange with the world's generator (in the snapshot, so a
/// replay or a rewind rolls the same).
void roll_oranges(GameState& game, fixstep::World& sim) {
  std::vector<Entity> pegs;
  for (const Entity e : sim.bodies()) {
    if (is_peg(sim, e)) pegs.push_back(e);
  }
  game.pegs_left = static_cast<int>(pegs.size());
  for (int k = 0; k < orange_pegs && !pegs.empty(); ++k) {
    const std::uint32_t i = sim.random().below(static_cast<std::uint32_t>(pegs.size()));
    sim.set_user_data(pegs[i], sim.user_data(pegs[i]) | orange_bit);
    fixstep::Appearance a = *sim.get<fixstep::Appearance>(pegs[i]);
    a.color = orange;
    sim.set(pegs[i], a);
    pegs.erase(pegs.begin() + i);
  }
  game.rolled = true;
}

void shoot(GameState& game, fixstep::World& sim) {
  BodyDef b = disc("ball", launcher, ball_radius, BodyType::dynamic, ball_color);
  b.body.mass = 0.1;
  b.body.velocity = launch_velocity(game.aim);
  b.gravity = fixstep::Gravity{{0.0, -gravity}};
  b.collider->filter = {.category = ball_category, .mask = fixstep::all_categories, .group = -1};
  b.appearance->trail = true;
  b.user_data = ball_tag;
  game.ball = sim.create_body(b);
  --game.balls_left;
  game.flight_ticks = 0;
  game.phase = Phase::flying;
}

/// Lights peg `e` (once per ball) and scores it.
void light(GameState& game, fixstep::World& sim, Entity e) {
  if (std::find(game.lit.begin(), game.lit.end(), e) != game.lit.end()) return;
  game.lit.push_back(e);
  const bool o = orange_peg(sim, e);
  game.score += o ? orange_points : blue_points;
  fixstep::Appearance a = *sim.get<fixstep::Appearance>(e);
  a.color = o ? lit_orange : lit_blue;
  sim.set(e, a);
}

/// The ball's turn is over: its lit pegs go, and the next ball (if any) is aimed.
void end_turn(GameState& game, fixstep::World& sim) {
  for (const Entity e : game.lit) sim.destroy(e);
  game.pegs_left -= static_cast<int>(game.lit.size());
  game.lit.clear();
  sim.destroy(game.ball);
  game.ball = Entity{};
  game.phase = game.balls_left > 0 && game.pegs_left > 0 ? Phase::aiming : Phase::over;
}

/// Turns the bucket (rims and catch zone) round at the walls.
void move_bucket(fixstep::World& sim) {
  const Entity zone = sim.find("catch");
  const Body b = sim.body(zone);
  const double edge = half_width - bucket_half_width - 0.3;
  const bool turn =
      (b.position.x > edge && b.velocity.x > 0) || (b.position.x < -edge && b.velocity.x < 0);
  if (!turn) return;
  for (const char* name : {"catch", "rim_left", "rim_right"}) {
    const Entity e = sim.find(name);
    sim.set_velocity(e, Vec2{-sim.body(e).velocity.x, 0});
  }
}

}  // namespace

fixstep::WorldDef make_level() {
  fixstep::WorldDef def;
  def.settings = {.dt = dt, .integrator = fixstep::Integrator::semi_implicit_euler};
  def.settings.seed = 2026;  // World::random(): which pegs are orange
  def.settings.contacts = fixstep::ContactSettings{.restitution = 0.7, .friction = 0.0};
  int n = 0;
  for (int row = 0; row < 6; ++row) {
    const double y = 5.5 - 2.0 * row, shift = row % 2 ? 0.8 : 0.0;
    for (int col = 0; col < 9; ++col) {
      const double x = -6.4 + 1.6 * col + shift;
      if (x > half_width - 1.0) continue;
      BodyDef p = disc("peg" + std::to_string(n), {x, y}, peg_radius, BodyType::static_body, blue);
      p.collider->filter.category = peg_category;
      p.user_data = peg_tag + std::uint64_t(n++);
      def.bodies.push_back(p);
    }
  }
  // The bucket: two rims the ball bounces off, and the catch zone between them: a sensor that
  // sees balls only.
  for (const double side : {-1.0, 1.0}) {
    BodyDef rim = disc(side < 0 ? "rim_left" : "rim_right", {side * bucket_half_width, bucket_y},
                       0.18, BodyType::kinematic, rim_color);
    rim.body.velocity = {bucket_speed, 0};
    rim.collider->filter.category = bucket_category;
    rim.user_data = rim_tag;
    def.bodies.push_back(rim);
  }
  BodyDef zone = disc("catch", {0, bucket_y - 0.25}, bucket_half_width - 0.25, BodyType::kinematic,
                      {255, 255, 255, 40});
  zone.body.velocity = {bucket_speed, 0};
  zone.collider->sensor = true;
  zone.collider->filter = {.category = bucket_category, .mask = ball_category, .group = 0};
  zone.appearance->visible = false;  // the game draws the bucket itself
  zone.user_data = catch_tag;
  def.bodies.push_back(zone);
  def.planes.push_back({.normal = {1, 0}, .offset = -half_width, .restitution = 0.8});
  def.planes.push_back({.normal = {-1, 0}, .offset = -half_width, .restitution = 0.8});
  return def;
}

double aim_from(Vec2 pointer) {
  const Vec2 d = pointer - launcher;
  if (!(d.x != 0.0 || d.y != 0.0)) return 0.0;
  const double a = fixstep::det::atan2(d.x, -d.y);  // 0: straight down, > 0: to the right
  return std::clamp(a, -max_aim, max_aim);
}

Vec2 launch_velocity(double aim) {
  return Vec2{fixstep::det::sin(aim), -fixstep::det::cos(aim)} * launch_speed;
}

bool is_peg(const fixstep::World& sim, Entity e) {
  return sim.contains(e) && (sim.user_data(e) & ~orange_bit) >= peg_tag;
}

std::optional<fixstep::RayHit> aim_guide(const fixstep::World& sim, double aim) {
  const fixstep::QueryFilter pegs{.category = fixstep::all_categories, .mask = peg_category};
  return sim.cast_ray(launcher, launch_velocity(aim) * 1.2, pegs);
}

void after_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim) {
  if (!game.rolled) roll_oranges(game, sim);
  move_bucket(sim);
  switch (game.phase) {
    case Phase::aiming:
      game.aim = aim_from(input.pointer);
      if ((input.pressed & (fixstep::button_pointer_primary | fixstep::button_action)) != 0) {
        shoot(game, sim);
      }
      break;
    case Phase::flying: {
      for (const fixstep::ContactEvent& c : sim.contacts_begun()) {
        const Entity other = c.a == game.ball ? c.b : (c.b == game.ball ? c.a : Entity{});
        if (is_peg(sim, other)) light(game, sim, other);
      }
      bool caught = false;
      for (const fixstep::SensorEvent& s : sim.sensors_begun()) caught |= s.visitor == game.ball;
      if (caught) ++game.balls_left, ++game.caught;
      const fixstep::Body b = sim.body(game.ball);
      if (caught || b.position.y < floor_y || ++game.flight_ticks > flight_limit)
        end_turn(game, sim);
      break;
    }
    case Phase::over:
      break;
  }
}

std::vector<std::string> status_lines(const GameState& game) {
  std::vector<std::string> lines{"score " + std::to_string(game.score) + "   balls " +
                                 std::to_string(game.balls_left) + "   pegs " +
                                 std::to_string(game.pegs_left)};
  switch (game.phase) {
    case Phase::aiming:
      lines.emplace_back("aiming");  // how to aim and shoot: the controls hint beside
      break;
    case Phase::flying:
      lines.emplace_back(game.lit.empty() ? "ball in play"
                                          : "lit " + std::to_string(game.lit.size()));
      break;
    case Phase::over:
      lines.emplace_back("GAME OVER: " + std::to_string(game.score) + " points   (r plays again)");
      break;
  }
  return lines;
}

std::string describe(const GameState& game) {
  static constexpr const char* phases[] = {"aiming", "flying", "over"};
  return "score=" + std::to_string(game.score) + " balls=" + std::to_string(game.balls_left) +
         " caught=" + std::to_string(game.caught) + " pegs=" + std::to_string(game.pegs_left) +
         " phase=" + phases[static_cast<int>(game.phase)];
}

}  // namespace peggle
