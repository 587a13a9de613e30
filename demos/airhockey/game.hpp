// airhockey: two players, two kinematic mallets and a puck, for networked play (fixstep::net:
// main.cpp's --host / --join) and against the computer.
//
// What the engine does for the game, and what the game does itself:
//   - contacts: the puck (a dynamic disc) bounces off the mallets (kinematic discs moved by
//     per-body velocity input) and the four walls (planes) at its time of impact;
//   - sensors: each goal is a static sensor disc centred on an end wall (its half inside the
//     table is the goal crease); World::sensors_begun() reports the puck entering it;
//   - input: each player's pointer (a level, so a rollback peer predicts it well) is where its
//     mallet heads; merge() turns the players' pointers into the mallets' velocities, inside the
//     tick, on every peer alike; the arrow keys drive the mallet instead while held;
//   - the score and the serve are the rules' state (GameState, plain data: copied for restarts,
//     replays, the sync test and rollback).
#pragma once

#include <array>
#include <cstdint>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <span>
#include <string>
#include <vector>

namespace airhockey {

// --- the level (units: m, kg, s) --------------------------------------------------------------
inline constexpr double dt = 1.0 / 120.0;       ///< s, one tick
inline constexpr double half_length = 4.0;      ///< m, end walls (with the goals) at x = ±
inline constexpr double half_width = 2.2;       ///< m, side walls at y = ±
inline constexpr double goal_radius = 0.7;      ///< m, the goal crease round each end's centre
inline constexpr double puck_radius = 0.16;     ///< m
inline constexpr double mallet_radius = 0.3;    ///< m
inline constexpr double mallet_speed = 9.0;     ///< m/s, the fastest a mallet moves
inline constexpr double puck_top_speed = 12.0;  ///< m/s, the puck is slowed to it
inline constexpr int serve_ticks = 60;          ///< the puck rests this long after a goal
inline constexpr int winning_score = 7;

/// A player's half: where its mallet may go (its reach), m. Player 0 plays on the left (x < 0)
/// and defends the left goal.
struct Reach {
  fixstep::Vec2 lo, hi;
};
[[nodiscard]] Reach reach(int player);

/// The table: the puck at the centre moving towards player 0, the two mallets at home, the
/// four walls, the two goal sensors. Contacts on (restitution 0.9, no friction).
[[nodiscard]] fixstep::WorldDef make_level();

/// The tick's input from the players' inputs (index = player, 1 or 2 of them; a missing player's
/// mallet keeps still): each mallet's velocity towards its player's pointer (clamped into its
/// reach), or along the held arrows. Deterministic: the same on every peer.
[[nodiscard]] fixstep::TickInput merge(std::span<const fixstep::TickInput> players,
                                       const fixstep::World& world);

/// The computer's input for `player` (single-player: the right mallet): its pointer on the
/// puck when the puck is in its half, else back at its goal.
[[nodiscard]] fixstep::TickInput computer_input(int player, const fixstep::World& world);

/// A bot's pointer at tick `tick` for `player`: a scripted sweep of its half (depends on the
/// tick and the player only, so a bot's inputs are the same in every run).
[[nodiscard]] fixstep::Vec2 bot_pointer(int player, std::int64_t tick);

// --- the rules --------------------------------------------------------------------------------
/// Everything the rules remember between ticks. Plain data.
struct GameState {
  std::array<int, 2> score{};
  int serve_wait = 0;   ///< ticks left before the puck is served (after a goal)
  int serve_to = 0;     ///< the player the next serve goes to (the one scored on)
  int still_ticks = 0;  ///< ticks the puck has been almost still (re-served at 3 s)
  bool over = false;    ///< a player reached winning_score
  friend bool operator==(const GameState&, const GameState&) = default;
};

/// After a tick: goals (sensors), the serve, the puck's speed limit.
void after_tick(GameState& game, fixstep::World& sim);

/// "red 2 : 1 blue" and a hint, for the HUD.
[[nodiscard]] std::vector<std::string> status_lines(const GameState& game);
/// "red=2 blue=1 over=0" for summaries and tests.
[[nodiscard]] std::string describe(const GameState& game);

}  // namespace airhockey
