// stacker: a small Angry-Birds-like game on fixstep's public API. Three towers of wooden
// blocks and planks stand on the ground and on a stone plinth, a green target box on each; drag the
// ball back on its rubber band, let go, and knock them down.
//
// The whole game is two things:
//   1. a level: a WorldDef built in code (make_level): bodies with box shapes (they turn and
//      stack: the engine's contact manifolds), the ball a circle shape on a band, the ground;
//   2. rules: after_tick(), run after every tick: it cuts the band, counts the pieces that fell
//      or turned over, reloads the ball, ends the game. rules() gives it to the library as a
//      fixstep::TickRules, so fixstep::replay and fixstep::SyncTest run it as live play does.
// The engine does all of the physics; the rules only read positions and angles, and score.
#pragma once

#include <cstdint>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/rules.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>
#include <vector>

namespace stacker {

// --- the level (units: m, kg, s) --------------------------------------------------------------
inline constexpr double dt = 1.0 / 120.0;       ///< s, one tick
inline constexpr fixstep::Vec2 anchor{-12, 3};  ///< m, the band's fork: where the ball sits
inline constexpr double band_frequency = 1.2;   ///< Hz, the rubber band on the ball's mass
inline constexpr double max_pull = 3.0;         ///< m, farthest the band stretches
inline constexpr double min_pull = 0.5;         ///< m, a shorter pull is no shot
inline constexpr double grab_reach = 0.6;       ///< m from the ball's centre a press picks it
inline constexpr double ball_radius = 0.4;      ///< m
inline constexpr double ball_mass = 2.0;        ///< kg (a block of wood is 1 kg)
inline constexpr double wood_density = 1.0;     ///< kg/m²: a 1 m block weighs 1 kg
inline constexpr int shots_per_game = 3;        ///< balls the player gets
inline constexpr int piece_count = 17;          ///< blocks, planks and targets
inline constexpr int target_count = 3;          ///< of which targets (one on each tower)
/// A piece is down (and scores) once its centre is this far below where it started, m, or
/// once it has turned past topple_angle either way, rad.
inline constexpr double topple_drop = 0.5;
inline constexpr double topple_angle = 0.6;  // about 34°

/// What a piece is: a block or plank of wood, or a target (the game is won when all are down).
enum class PieceKind : std::uint8_t { wood, target };
/// One piece of the towers as the level places it: a box of half-extents (m) at a point (m).
struct Piece {
  fixstep::Vec2 at;
  double half_width, half_height;
  PieceKind kind = PieceKind::wood;
};
/// The towers, left to right (game.cpp). Piece i is the body with user_data piece_tag + i.
[[nodiscard]] const Piece& piece(int i);
inline constexpr std::uint64_t ball_tag = 1;
inline constexpr std::uint64_t piece_tag = 100;

/// The ball's handle (World::find, O(1)).
[[nodiscard]] fixstep::Entity ball(const fixstep::World& sim);
/// The piece `e` is (from its user data), or -1 when it is not a piece or not a live body.
[[nodiscard]] int piece_number(const fixstep::World& sim, fixstep::Entity e);

/// The level: the ground (a half-plane), the towers (dynamic bodies of one box shape each,
/// resting on the ground, on one another and on a static stone plinth), the ball (a circle shape)
/// resting on its band at `anchor`, gravity on everything, friction 0.6 and no bounce between wood
/// and wood.
[[nodiscard]] fixstep::WorldDef make_level();
/// Where the ball rests on its band (the anchor, sagged by gravity), m.
[[nodiscard]] fixstep::Vec2 ball_rest_position();

// --- the rules --------------------------------------------------------------------------------
enum class Phase : std::uint8_t {
  loaded,  ///< the ball sits on the band; drag it back and let go
  pulled,  ///< let go: the band is throwing the ball towards the anchor
  flying,  ///< the band is cut: the ball flies until it stops or leaves
  over,    ///< no shots left, or every target is down
};

/// Everything the rules remember between ticks. Plain data: two runs with the same inputs
/// give equal GameStates at every tick.
struct GameState {
  Phase phase = Phase::loaded;
  int score = 0;                    ///< pieces down
  int targets_down = 0;             ///< of which targets
  int shots_left = shots_per_game;  ///< balls not yet thrown
  std::uint32_t down = 0;           ///< bit i: piece i is down
  bool dragging = false;            ///< the ball was dragged during the last tick
  fixstep::Vec2 release_point{};    ///< where the ball was let go, m
  int flight_ticks = 0;             ///< ticks since the band was cut
  int still_ticks = 0;              ///< consecutive slow ticks in flight
  std::uint64_t loaded_at = 0;      ///< the tick the ball was last loaded (0: the start)
  friend bool operator==(const GameState&, const GameState&) = default;
};

/// Before a tick (live play only; a replay takes the recorded input as is): lets the pointer
/// drag the ball, and only the ball, and only while it is loaded, never farther than max_pull
/// from the anchor. A press within grab_reach of the ball picks it; holding the button keeps it
/// (GameState::dragging, so a rollback of the rules' state rolls the pick back with them).
void prepare_input(const GameState& game, fixstep::TickInput& input, const fixstep::World& sim);

/// After a tick: the rules (see the top of this file). Changes the world through World's
/// handle API only (remove, set, set_body).
void after_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim);

/// The rules as the library runs them (fixstep::replay, fixstep::SyncTest): after_tick on
/// `game` (held by reference: it must outlive the rules), saved and restored with the world.
[[nodiscard]] fixstep::TickRules rules(GameState& game);

/// One tick of the game from a prepared input: step, then the rules.
inline void play_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim) {
  sim.step(input);
  after_tick(game, input, sim);
}

/// "score 5/17   targets 1/3   balls left 2" and a hint for the HUD.
[[nodiscard]] std::vector<std::string> status_lines(const GameState& game);
/// "score=5 targets=1 shots_left=0 phase=over" for summaries and tests.
[[nodiscard]] std::string describe(const GameState& game);

}  // namespace stacker
