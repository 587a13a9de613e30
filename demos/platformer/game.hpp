// platformer: a small platformer on fixstep's public API. Walk and jump with a character mover
// (a kinematic capsule moved by collide-and-slide: BodyDef::mover), up a 45° ramp and a step,
// onto one-way platforms (jump through from below, land on them from above), onto a moving
// platform that carries it, and push a crate; collect the coins.
//
//   - the player: the game sets the velocity it wants each tick, before the step
//     (app::Settings::rules_before_step): the walk axis times the walking speed, a jump's
//     speed when on the floor, gravity's g·dt while in the air (the mover's gravity is the
//     game's, as Godot's CharacterBody2D's);
//   - the level: a polyline floor with a ramp and a drop, a step, two one-way platforms
//     (SegmentDef::one_way), a kinematic platform moving back and forth (its velocity set by
//     the rules from the tick), a crate (a dynamic box the mover pushes with at most its push
//     force), coins (drawn bodies with no collider: collected within reach).
#pragma once

#include <cstdint>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>
#include <vector>

namespace platformer {

/// The game's actions (TickInput bits; their keys: platformer_app.hpp) and its walk axis.
inline constexpr std::uint32_t jump_action = 1u << 0, run_action = 1u << 1;
inline constexpr std::size_t walk_axis = 0;

inline constexpr double walk_speed = 4.5;      ///< m/s, the walk axis at 1
inline constexpr double run_speed = 7.0;       ///< m/s, with run held
inline constexpr double jump_speed = 7.5;      ///< m/s: a jump about 2.9 m high (v²/2g)
inline constexpr double gravity = 9.81;        ///< m/s², the game's, added while in the air
inline constexpr double fall_limit = 20.0;     ///< m/s, the fastest fall
inline constexpr double coin_reach = 0.6;      ///< m, player centre to coin centre
inline constexpr double platform_speed = 1.5;  ///< m/s, the moving platform
inline constexpr std::uint64_t platform_half_period = 360;  ///< ticks each way (3 s)

/// BodyDef::user_data of the coins.
inline constexpr std::uint64_t coin_tag = 7;

/// The level, its bodies named "player", "crate", "platform" and "coin0", "coin1", ...
[[nodiscard]] fixstep::WorldDef make_level();

/// What the rules remember outside the world.
struct GameState {
  fixstep::Entity player{}, platform{};  ///< handles kept by setup (never destroyed)
  int coins = 0;                         ///< collected
  int coins_total = 0;
  int jumps = 0;
  double x = 0.0;         ///< m, the player's x after the last rules
  bool on_floor = false;  ///< the player's MoverState::on_floor then
};

/// The handles and the coin count of `level` (setup()).
void start(GameState& game, const fixstep::WorldDef& level);
/// Before each tick's step: the player's wanted velocity from the tick's actions and axis, the
/// moving platform's velocity, the coins within reach collected.
void rules(GameState& game, const fixstep::TickInput& input, fixstep::World& world);

/// "coins=N/M jumps=J x=X on_floor=0|1".
[[nodiscard]] std::string describe(const GameState& game);

}  // namespace platformer
