// slingshot: the level and the rules (see game.hpp).
#include "game.hpp"

#include <cmath>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <numbers>
#include <string>

namespace slingshot {

using fixstep::Body;
using fixstep::SpringDamper;
using fixstep::TickInput;
using fixstep::Vec2;

namespace {

constexpr double gravity = 9.81;  // m/s²
constexpr fixstep::Rgba8 ball_color{230, 70, 60, 255};
constexpr fixstep::Rgba8 target_color{250, 200, 60, 255};
constexpr fixstep::Rgba8 knocked_color{120, 120, 130, 255};

// When a flight ends: the ball has moved slower than still_speed for still_limit ticks, left
// the level's box (the walls keep it in; this is a safety net), or flown for flight_limit
// ticks (a ball sliding for ever).
constexpr double still_speed = 0.2;      // m/s
constexpr int still_limit = 60;          // ticks (0.5 s)
constexpr int flight_limit = 8 * 120;    // ticks (8 s)
constexpr double level_half_width = 24;  // m
constexpr double level_bottom = -3;      // m

// The targets: where each rope hangs from and its length, m.
struct Rope {
  Vec2 hook;
  double length;
};
constexpr Rope ropes[target_count] = {{{4, 11}, 4}, {{8, 11}, 6.5}, {{12, 11}, 3}, {{16, 11}, 7}};

// The band: a spring of rest length 0 from the anchor, band_frequency Hz on the ball's mass,
// lightly damped so a loaded ball settles.
SpringDamper band() {
  const fixstep::LinkSpring s = fixstep::spring_from_frequency(band_frequency, 0.1, ball_mass);
  return SpringDamper{.anchor = anchor, .stiffness = s.stiffness, .damping = s.damping};
}

// Puts the ball back on the band, at rest, for the next shot (a teleport: its trail starts
// afresh), its trail off while it waits.
void reload(fixstep::World& sim) {
  const fixstep::Entity b = ball(sim);
  sim.set_body(b, Body{.mass = ball_mass, .position = ball_rest_position(), .velocity = {}});
  sim.set(b, band());
  sim.set(b, ball_look(Phase::loaded));
}

// Scores target `e` (number i) if it is not down yet: knocks it off its rope and greys it.
void knock(GameState& game, int i, fixstep::Entity e, fixstep::World& sim) {
  if ((game.knocked & (1u << i)) != 0) return;  // a target scores once
  game.knocked |= 1u << i;
  ++game.score;
  sim.remove<SpringDamper>(e);
  sim.set(e, fixstep::Appearance{.radius = target_radius, .color = knocked_color});
}

}  // namespace

fixstep::Appearance ball_look(Phase phase) {
  // The trail shows the flight only: not the player's drag while loaded.
  return fixstep::Appearance{.radius = ball_radius,
                             .color = ball_color,
                             .trail = phase == Phase::pulled || phase == Phase::flying,
                             .trail_time = 1.5};
}

fixstep::Entity ball(const fixstep::World& sim) {
  return sim.find("ball");
}

int target_number(const fixstep::World& sim, fixstep::Entity e) {
  if (!sim.contains(e)) return -1;
  const std::uint64_t tag = sim.user_data(e);
  return tag >= target_tag && tag < target_tag + target_count ? int(tag - target_tag) : -1;
}

Vec2 ball_rest_position() {
  const double omega = 2.0 * std::numbers::pi * band_frequency;
  return {anchor.x, anchor.y - gravity / (omega * omega)};  // where band and gravity balance
}

fixstep::WorldDef make_level() {
  fixstep::WorldDef def;
  def.settings = {.dt = dt, .integrator = fixstep::Integrator::semi_implicit_euler};
  // Body-vs-body contacts: the ball and the targets are discs that hit each other (and the
  // targets each other) at their time of impact, bouncing with hit_restitution, frictionless.
  def.settings.contacts = fixstep::ContactSettings{.restitution = hit_restitution, .friction = 0};

  fixstep::BodyDef ball_def;
  ball_def.name = "ball";
  ball_def.body = Body{.mass = ball_mass, .position = ball_rest_position()};
  ball_def.spring = band();
  ball_def.gravity = fixstep::Gravity{{0.0, -gravity}};
  ball_def.appearance = ball_look(Phase::loaded);
  ball_def.collider = fixstep::Collider{ball_radius};  // hits targets, ground and walls
  ball_def.user_data = ball_tag;
  def.bodies.push_back(ball_def);

  for (int i = 0; i < target_count; ++i) {
    // A rope: an anchored spring with a rest length, stiff enough (4 Hz) to hang nearly
    // straight and damped (ζ = 0.2) so a swing dies down.
    const fixstep::LinkSpring rope = fixstep::spring_from_frequency(4.0, 0.2, target_mass);
    fixstep::BodyDef t;
    t.name = "target" + std::to_string(i);
    t.body =
        Body{.mass = target_mass, .position = {ropes[i].hook.x, ropes[i].hook.y - ropes[i].length}};
    t.spring = SpringDamper{.anchor = ropes[i].hook,
                            .stiffness = rope.stiffness,
                            .damping = rope.damping,
                            .rest_length = ropes[i].length};
    t.gravity = fixstep::Gravity{{0.0, -gravity}};
    t.appearance = fixstep::Appearance{.radius = target_radius, .color = target_color};
    t.collider = fixstep::Collider{target_radius};
    t.user_data = target_tag + std::uint64_t(i);
    def.bodies.push_back(t);
  }

  // The slingshot itself (post, fork, rubber) is no body: the game draws it (draw.cpp).

  // The ground (y >= 0) and two walls (|x| <= 22 m): half-planes the bodies'
  // colliders bounce on (restitution e) and slide along (friction μ).
  def.planes.push_back({.normal = {0, 1}, .offset = 0, .restitution = 0.4, .friction = 0.5});
  def.planes.push_back({.normal = {1, 0}, .offset = -22, .restitution = 0.5, .friction = 0.2});
  def.planes.push_back({.normal = {-1, 0}, .offset = -22, .restitution = 0.5, .friction = 0.2});
  return def;
}

void prepare_input(const GameState& game, fixstep::PointerDrag& drag, TickInput& input,
                   const fixstep::World& sim) {
  drag.apply(input, sim);  // picks on press, drops on release
  if (game.phase != Phase::loaded || input.drag_body != ball(sim)) {
    input.drag_body = fixstep::null_entity;  // targets are not for dragging
    return;
  }
  // The band stretches max_pull at most: hold the pointer the ball follows within reach.
  const Vec2 d = input.pointer - anchor;
  const double reach = fixstep::length(d);
  if (reach > max_pull) {
    input.pointer = {anchor.x + d.x * max_pull / reach, anchor.y + d.y * max_pull / reach};
  }
}

void after_tick(GameState& game, const TickInput& input, fixstep::World& sim) {
  const fixstep::Entity the_ball = ball(sim);
  const Body b = sim.body(the_ball);
  switch (game.phase) {
    case Phase::loaded: {
      const bool dragging = input.drag_body == the_ball;
      if (game.dragging && !dragging) {  // let go this tick
        const Vec2 pull = b.position - anchor;
        if (fixstep::length(pull) >= min_pull) {
          game.phase = Phase::pulled;
          game.release_point = b.position;
          --game.shots_left;
          sim.set(the_ball, ball_look(Phase::pulled));
        }
      }
      game.dragging = dragging;
      break;
    }
    case Phase::pulled:
      // The band throws the ball; once it passes the anchor the band is cut and it flies.
      if (dot(b.position - anchor, anchor - game.release_point) >= 0.0) {
        sim.remove<SpringDamper>(the_ball);
        game.phase = Phase::flying;
        game.flight_ticks = game.still_ticks = 0;
      }
      break;
    case Phase::flying: {
      // The engine resolved this tick's disc-disc impacts (the bounce); the rules read them.
      // The ball's first impact with a target knocks it off its rope, and scores.
      for (const fixstep::Impact& hit : sim.impacts()) {
        const fixstep::Entity other =
            hit.a == the_ball ? hit.b : (hit.b == the_ball ? hit.a : fixstep::null_entity);
        const int i = target_number(sim, other);
        if (i >= 0) knock(game, i, other, sim);  // the ball and a target
      }
      const Body now = sim.body(the_ball);
      ++game.flight_ticks;
      game.still_ticks = fixstep::length(now.velocity) < still_speed ? game.still_ticks + 1 : 0;
      const bool left =
          std::abs(now.position.x) > level_half_width || now.position.y < level_bottom;
      if (!left && game.still_ticks < still_limit && game.flight_ticks < flight_limit) break;
      const bool all_down = game.knocked == (1u << target_count) - 1;
      if (game.shots_left > 0 && !all_down) {
        reload(sim);
        game.phase = Phase::loaded;
        game.dragging = false;
      } else {
        game.phase = Phase::over;
      }
      break;
    }
    case Phase::over:
      break;
  }
}

fixstep::TickRules rules(GameState& game) {
  return fixstep::stateful_rules(game, [](GameState& g, fixstep::World& sim,
                                          const TickInput& input) { after_tick(g, input, sim); });
}

std::vector<std::string> status_lines(const GameState& game) {
  std::vector<std::string> lines{"score " + std::to_string(game.score) + "/" +
                                 std::to_string(target_count) + "   balls left " +
                                 std::to_string(game.shots_left)};
  switch (game.phase) {
    case Phase::loaded:
      lines.emplace_back("ball loaded");  // how to shoot: the controls hint beside
      break;
    case Phase::pulled:
    case Phase::flying:
      lines.emplace_back("ball in play");
      break;
    case Phase::over: {
#ifdef __EMSCRIPTEN__
      constexpr const char* keys = "   (r plays again)";  // a page has no Esc to quit with
#else
      constexpr const char* keys = "   (r plays again, esc quits)";
#endif
      lines.emplace_back("GAME OVER: " + std::to_string(game.score) + " of " +
                         std::to_string(target_count) + " down" + keys);
      break;
    }
  }
  return lines;
}

std::string describe(const GameState& game) {
  static constexpr const char* phases[] = {"loaded", "pulled", "flying", "over"};
  std::string knocked;
  for (int i = 0; i < target_count; ++i) knocked += (game.knocked & (1u << i)) ? '1' : '0';
  return "score=" + std::to_string(game.score) + " shots_left=" + std::to_string(game.shots_left) +
         " knocked=" + knocked + " phase=" + phases[static_cast<int>(game.phase)];
}

}  // namespace slingshot
