// stacker: the level and the rules (see game.hpp).
#include "game.hpp"

#include <cmath>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/shape.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <numbers>
#include <string>

namespace stacker {

using fixstep::Body;
using fixstep::SpringDamper;
using fixstep::TickInput;
using fixstep::Vec2;

namespace {

constexpr double gravity = 9.81;  // m/s²
constexpr fixstep::Rgba8 ball_color{200, 40, 40, 255};
constexpr fixstep::Rgba8 wood_color{196, 148, 92, 255};
constexpr fixstep::Rgba8 target_color{110, 200, 70, 255};
constexpr fixstep::Rgba8 down_color{120, 120, 130, 255};
constexpr fixstep::Rgba8 stone_color{95, 100, 110, 255};

// When a flight ends: the ball has moved slower than still_speed for still_limit ticks, left
// the level, or flown for flight_limit ticks.
constexpr double still_speed = 0.2;      // m/s
constexpr int still_limit = 60;          // ticks (0.5 s)
constexpr int flight_limit = 6 * 120;    // ticks (6 s)
constexpr double level_half_width = 30;  // m
constexpr double level_bottom = -3;      // m

// The towers. Planks stand up (0.3 m × 2 m) or lie across (2.6 m × 0.3 m); blocks are 1 m.
constexpr Piece pieces[piece_count] = {
    // A gate at x = 3: two posts, a lintel, a block, the target.
    {{2.0, 1.0}, 0.15, 1.0},
    {{4.0, 1.0}, 0.15, 1.0},
    {{3.0, 2.15}, 1.3, 0.15},
    {{3.0, 2.8}, 0.5, 0.5},
    {{3.0, 3.7}, 0.4, 0.4, PieceKind::target},
    // A pyramid of blocks at x = 8 under a plank and the target.
    {{7.5, 0.5}, 0.5, 0.5},
    {{8.5, 0.5}, 0.5, 0.5},
    {{8.0, 1.5}, 0.5, 0.5},
    {{8.0, 2.15}, 1.3, 0.15},
    {{8.0, 2.7}, 0.4, 0.4, PieceKind::target},
    // A two-storey house at x = 13 on the stone plinth, the target on its roof.
    {{12.0, 3.0}, 0.15, 1.0},
    {{14.0, 3.0}, 0.15, 1.0},
    {{13.0, 4.15}, 1.3, 0.15},
    {{12.4, 5.1}, 0.15, 0.8},
    {{13.6, 5.1}, 0.15, 0.8},
    {{13.0, 6.05}, 1.0, 0.15},
    {{13.0, 6.6}, 0.4, 0.4, PieceKind::target},
};

// The band: a spring of rest length 0 from the anchor, band_frequency Hz on the ball's mass,
// lightly damped so a loaded ball settles.
SpringDamper band() {
  const fixstep::LinkSpring s = fixstep::spring_from_frequency(band_frequency, 0.1, ball_mass);
  return SpringDamper{.anchor = anchor, .stiffness = s.stiffness, .damping = s.damping};
}

fixstep::Appearance ball_look(Phase phase) {
  // The trail shows the flight only: not the player's drag while loaded.
  return fixstep::Appearance{.radius = ball_radius,
                             .color = ball_color,
                             .trail = phase == Phase::pulled || phase == Phase::flying,
                             .trail_time = 1.0};
}

fixstep::Appearance piece_look(const Piece& p, bool down) {
  // The radius is what the pointer may pick by (none: the player drags only the ball).
  const fixstep::Rgba8 color =
      down ? down_color : (p.kind == PieceKind::target ? target_color : wood_color);
  return fixstep::Appearance{.radius = 0.01, .color = color, .trail = false};
}

// Puts the ball back on the band, at rest, for the next shot (a teleport: its trail starts
// afresh, its spin stops).
void reload(fixstep::World& sim) {
  const fixstep::Entity b = ball(sim);
  sim.set_body(b, Body{.mass = ball_mass, .position = ball_rest_position()});
  sim.set(b, band());
  sim.set(b, ball_look(Phase::loaded));
}

// Scores every piece that is down and was not yet: fallen topple_drop below its start, or
// turned past topple_angle. A piece scores once, and turns grey.
void score_pieces(GameState& game, fixstep::World& sim) {
  for (const fixstep::Entity e : sim.defined_bodies()) {
    const int i = piece_number(sim, e);
    if (i < 0 || (game.down & (1u << i)) != 0) continue;
    const Body b = sim.body(e);
    if (b.position.y > pieces[i].at.y - topple_drop && std::abs(b.angle) < topple_angle) continue;
    game.down |= 1u << i;
    ++game.score;
    if (pieces[i].kind == PieceKind::target) ++game.targets_down;
    sim.set(e, piece_look(pieces[i], true));
  }
}

}  // namespace

const Piece& piece(int i) {
  return pieces[i];
}

fixstep::Entity ball(const fixstep::World& sim) {
  return sim.find("ball");
}

int piece_number(const fixstep::World& sim, fixstep::Entity e) {
  if (!sim.contains(e)) return -1;
  const std::uint64_t tag = sim.user_data(e);
  return tag >= piece_tag && tag < piece_tag + piece_count ? int(tag - piece_tag) : -1;
}

Vec2 ball_rest_position() {
  const double omega = 2.0 * std::numbers::pi * band_frequency;
  return {anchor.x, anchor.y - gravity / (omega * omega)};  // where band and gravity balance
}

fixstep::WorldDef make_level() {
  fixstep::WorldDef def;
  def.settings = {.dt = dt, .integrator = fixstep::Integrator::semi_implicit_euler};
  // Contacts between bodies: wood on wood grips (μ 0.6) and does not bounce.
  def.settings.contacts = fixstep::ContactSettings{.restitution = 0.0, .friction = 0.6};

  fixstep::BodyDef ball_def;
  ball_def.name = "ball";
  ball_def.body = Body{.mass = ball_mass, .position = ball_rest_position()};
  ball_def.spring = band();
  ball_def.gravity = fixstep::Gravity{{0.0, -gravity}};
  ball_def.appearance = ball_look(Phase::loaded);
  ball_def.shapes = {fixstep::make_circle(ball_radius)};
  ball_def.shapes[0].restitution = 0.3;
  ball_def.user_data = ball_tag;
  def.bodies.push_back(ball_def);

  for (int i = 0; i < piece_count; ++i) {
    const Piece& p = pieces[i];
    fixstep::BodyDef b;
    b.name = (p.kind == PieceKind::target ? "target" : "wood") + std::to_string(i);
    b.body = Body{.mass = 1.0, .position = p.at};  // mass from the density below
    b.gravity = fixstep::Gravity{{0.0, -gravity}};
    b.appearance = piece_look(p, false);
    b.shapes = {fixstep::make_box(p.half_width, p.half_height)};
    b.shapes[0].density = wood_density;
    b.user_data = piece_tag + std::uint64_t(i);
    def.bodies.push_back(b);
  }

  // A plinth of stone under the house: a static body (it never moves) with a box shape.
  fixstep::BodyDef plinth;
  plinth.name = "plinth";
  plinth.type = fixstep::BodyType::static_body;
  plinth.body.position = {13.0, 1.0};
  plinth.appearance = fixstep::Appearance{.radius = 0.01, .color = stone_color, .trail = false};
  plinth.shapes = {fixstep::make_box(1.6, 1.0)};
  def.bodies.push_back(plinth);

  // The ground, y >= 0: a half-plane everything rests on. (The slingshot's post is drawn by
  // the game: draw.hpp.)
  def.planes.push_back({.normal = {0, 1}, .offset = 0, .restitution = 0.1, .friction = 0.6});
  return def;
}

void prepare_input(const GameState& game, TickInput& input, const fixstep::World& sim) {
  input.drag_body = fixstep::null_entity;
  const fixstep::Entity the_ball = ball(sim);
  const bool held = (input.held & fixstep::button_pointer_primary) != 0;
  const bool pressed = (input.pressed & fixstep::button_pointer_primary) != 0;
  const bool on_ball = fixstep::length(input.pointer - sim.body(the_ball).position) <= grab_reach;
  if (game.phase != Phase::loaded || !held || !(game.dragging || (pressed && on_ball))) return;
  input.drag_body = the_ball;
  // The band stretches max_pull at most: hold the pointer the ball follows within reach.
  const Vec2 d = input.pointer - anchor;
  const double reach = fixstep::length(d);
  if (reach > max_pull) {
    input.pointer = {anchor.x + d.x * max_pull / reach, anchor.y + d.y * max_pull / reach};
  }
}

void after_tick(GameState& game, const TickInput& input, fixstep::World& sim) {
  score_pieces(game, sim);  // in every phase: a tower may still be falling
  const fixstep::Entity the_ball = ball(sim);
  const Body b = sim.body(the_ball);
  switch (game.phase) {
    case Phase::loaded: {
      const bool dragging = input.drag_body == the_ball;
      if (game.dragging && !dragging && fixstep::length(b.position - anchor) >= min_pull) {
        game.phase = Phase::pulled;  // let go this tick, far enough back
        game.release_point = b.position;
        --game.shots_left;
        sim.set(the_ball, ball_look(Phase::pulled));
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
      ++game.flight_ticks;
      game.still_ticks = fixstep::length(b.velocity) < still_speed ? game.still_ticks + 1 : 0;
      const bool left = std::abs(b.position.x) > level_half_width || b.position.y < level_bottom;
      if (!left && game.still_ticks < still_limit && game.flight_ticks < flight_limit) break;
      if (game.shots_left > 0 && game.targets_down < target_count) {
        reload(sim);
        game.phase = Phase::loaded;
        game.loaded_at = input.tick + 1;
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
  std::vector<std::string> lines{
      "score " + std::to_string(game.score) + "/" + std::to_string(piece_count) + "   targets " +
      std::to_string(game.targets_down) + "/" + std::to_string(target_count) + "   balls left " +
      std::to_string(game.shots_left)};
  switch (game.phase) {
    case Phase::loaded:
      lines.emplace_back("ball loaded");
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
      const bool won = game.targets_down == target_count;
      lines.emplace_back(std::string(won ? "ALL TARGETS DOWN: " : "GAME OVER: ") +
                         std::to_string(game.score) + " pieces down" + keys);
      break;
    }
  }
  return lines;
}

std::string describe(const GameState& game) {
  static constexpr const char* phases[] = {"loaded", "pulled", "flying", "over"};
  std::string down;
  for (int i = 0; i < piece_count; ++i) down += (game.down & (1u << i)) ? '1' : '0';
  return "score=" + std::to_string(game.score) + " targets=" + std::to_string(game.targets_down) +
         " shots_left=" + std::to_string(game.shots_left) + " down=" + down +
         " phase=" + phases[static_cast<int>(game.phase)];
}

}  // namespace stacker
