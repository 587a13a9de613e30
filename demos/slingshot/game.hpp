// slingshot: a small game on fixstep's public API. Drag the red ball back on its rubber band,
// let go, and knock the targets off their ropes.
//
// The whole game is two things:
//   1. a level: a WorldDef built in code (make_level), and
//   2. rules: after_tick(), a function run after every tick that reads the world, the tick's
//      impacts and input and changes the world (cuts the band, knocks targets off, reloads),
//      given to the library as a fixstep::TickRules (rules()) so that fixstep::replay and
//      fixstep::SyncTest run it as the live game does.
// The engine does the physics, the hits included (disc-disc contacts); the rules only score.
// The rules keep their state in GameState, which depends only on the inputs and the world, so
// replaying a recording's inputs reproduces the game bit for bit: score, shots and state hash.
#pragma once

#include <cstdint>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/pointer_drag.hpp>
#include <fixstep/core/rules.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>
#include <vector>

namespace slingshot {

// --- the level (units: m, kg, s) --------------------------------------------------------------
inline constexpr double dt = 1.0 / 120.0;       ///< s, one tick
inline constexpr fixstep::Vec2 anchor{-12, 3};  ///< m, the band's fork: where the ball sits
inline constexpr double band_frequency = 1.2;   ///< Hz, the rubber band on the ball's mass
inline constexpr double max_pull = 3.0;         ///< m, farthest the band stretches
inline constexpr double min_pull = 0.5;         ///< m, a shorter pull is no shot
inline constexpr double ball_radius = 0.35;     ///< m
inline constexpr double ball_mass = 1.0;        ///< kg
inline constexpr double target_radius = 0.6;    ///< m
inline constexpr double target_mass = 0.5;      ///< kg
inline constexpr double hit_restitution = 0.8;  ///< e of the disc-disc contacts (0..1)
inline constexpr int shots_per_game = 3;        ///< balls the player gets
inline constexpr int target_count = 4;          ///< targets, hanging from ropes
/// BodyDef::user_data of the ball, and of target i (0 <= i < target_count): target_tag + i. The
/// rules tell the bodies apart by it.
inline constexpr std::uint64_t ball_tag = 1;
inline constexpr std::uint64_t target_tag = 100;
/// The ball's handle (World::find, O(1)).
[[nodiscard]] fixstep::Entity ball(const fixstep::World& sim);
/// The target `e` is (from its user data), or -1 when it is not a target or not a live body.
[[nodiscard]] int target_number(const fixstep::World& sim, fixstep::Entity e);

/// The level: the ball resting on its band at `anchor`, four targets hanging from ropes
/// (anchored springs with a rest length), gravity on both, the ground and two walls (planes)
/// that the colliders of ball and targets bounce on (the slingshot's post and fork are drawn by
/// the game: draw.hpp). Contacts are on: ball and targets are discs that hit each other
/// (restitution hit_restitution, no friction), resolved by the engine at their time of impact.
[[nodiscard]] fixstep::WorldDef make_level();
/// Where the ball rests on its band (the anchor, sagged by gravity), m.
[[nodiscard]] fixstep::Vec2 ball_rest_position();

// --- the rules --------------------------------------------------------------------------------
enum class Phase : std::uint8_t {
  loaded,  ///< the ball sits on the band; drag it back and let go
  pulled,  ///< let go: the band is throwing the ball towards the anchor
  flying,  ///< the band is cut: the ball flies under gravity until it stops or leaves
  over,    ///< no shots left, or every target is down
};

/// Everything the rules remember between ticks. Plain data: two runs with the same inputs
/// give equal GameStates at every tick.
struct GameState {
  Phase phase = Phase::loaded;
  int score = 0;                    ///< targets knocked off
  int shots_left = shots_per_game;  ///< balls not yet thrown
  std::uint32_t knocked = 0;        ///< bit i: target i is down
  bool dragging = false;            ///< the ball was dragged during the last tick
  fixstep::Vec2 release_point{};    ///< where the ball was let go, m
  int flight_ticks = 0;             ///< ticks since the band was cut
  int still_ticks = 0;              ///< consecutive slow ticks in flight
  friend bool operator==(const GameState&, const GameState&) = default;
};

/// The ball's Appearance in `phase`: its trail on only in flight (pulled, flying), 1.5 s long.
[[nodiscard]] fixstep::Appearance ball_look(Phase phase);

/// Before a tick (live play only; a replay takes the recorded input as is): lets the pointer
/// drag the ball, and only the ball, and only while it is loaded, never farther than max_pull
/// from the anchor. `drag` holds the pick between ticks.
void prepare_input(const GameState& game, fixstep::PointerDrag& drag, fixstep::TickInput& input,
                   const fixstep::World& sim);

/// After a tick: the rules. `input` is the tick's input (with drag_body set), `sim` the world
/// right after sim.step(input); a hit is read from sim.impacts(), the tick's disc-disc impacts.
/// Changes the world through World's handle API only (remove, set, set_body).
void after_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim);

/// The rules as the library runs them (fixstep::replay, fixstep::SyncTest): after_tick on
/// `game` (held by reference: it must outlive the rules), saved and restored with the world
/// (fixstep::stateful_rules).
[[nodiscard]] fixstep::TickRules rules(GameState& game);

/// One tick of the game from a prepared input: step, then the rules.
inline void play_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim) {
  sim.step(input);
  after_tick(game, input, sim);
}

/// "score 2/4   balls left 1" and a hint for the HUD.
[[nodiscard]] std::vector<std::string> status_lines(const GameState& game);
/// "score=2 shots_left=1 knocked=0101 phase=over" for summaries and tests.
[[nodiscard]] std::string describe(const GameState& game);

}  // namespace slingshot
