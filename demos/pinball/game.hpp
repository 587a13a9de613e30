// pinball: a small pinball table on fixstep's public API. Launch the ball with the plunger, keep
// it up with two flippers, score on the bumpers and slingshots; three balls.
//
// What the engine does for the game, and what the game does itself:
//   - joints: each flipper is a dynamic body (a rounded polygon) on a revolute joint at its
//     pivot, its limits the rest and raised angles, its motor (flipper_speed, at most
//     flipper_torque) driven up while its key is held and down otherwise: prepare_input() sets
//     the motor's speed with a joint input each tick, as a pinball programmer writes it in
//     Box2D; the ball and the flipper push each other through the contact solver;
//   - contacts: the ball (a dynamic circle shape) bounces off the walls and lanes (static
//     segments), the bumpers (static circles) and the slingshots (static triangles); the rules
//     read World::contacts_begun() to score a hit and kick the ball away (an impulse along the
//     normal bringing it to a set speed: the bumpers' and slingshots' own push, which
//     restitution <= 1 cannot give);
//   - the plunger: held (down or Enter) it draws back, released it gives the ball resting on it
//     a launch speed proportional to the pull.
// The rules keep their state in GameState (plain data, copied with the game by app::run for
// restarts, replays and the sync test); prepare_input() keeps none.
#pragma once

#include <array>
#include <cstdint>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>
#include <vector>

namespace pinball {

// --- the table (units: m, kg, s) --------------------------------------------------------------
inline constexpr double dt = 1.0 / 120.0;  ///< s, one tick
/// m/s²: the slope's pull along the table (a steep table at this scale: the ball crosses it in
/// about a second).
inline constexpr double gravity = 20.0;
inline constexpr double ball_radius = 0.25;  ///< m
inline constexpr double ball_mass = 0.1;     ///< kg
inline constexpr double half_width = 4.5;    ///< m, the playfield's walls at x = ±half_width
inline constexpr double lane_x = 5.0;        ///< m, the plunger lane's middle (right of the field)
inline constexpr double plunger_y = 0.6;     ///< m, the plunger's top: the ball rests on it
inline constexpr double drain_y = -0.8;      ///< m, a ball below it is lost

/// Flippers: pivots at (±flipper_x, flipper_y), flipper_length long, turning between their rest
/// and raised angles (the left flipper's; the right one's are mirrored) at flipper_speed.
inline constexpr double flipper_x = 1.9, flipper_y = 1.6;  ///< m
inline constexpr double flipper_length = 1.5;              ///< m, pivot to tip
inline constexpr double flipper_rest = -0.52;              ///< rad, the left flipper down
inline constexpr double flipper_raised = 0.45;             ///< rad, the left flipper up
inline constexpr double flipper_speed = 32.0;              ///< rad/s, the motor's speed
inline constexpr double flipper_torque = 600.0;            ///< N·m, the motor's most
inline constexpr double flipper_mass = 1.0;                ///< kg

inline constexpr double bumper_radius = 0.55;  ///< m
/// m/s: the speed away from a bumper, and off a slingshot's face, the rules kick the ball to.
inline constexpr double bumper_kick = 9.0, slingshot_kick = 7.0;
inline constexpr double launch_min = 16.0;  ///< m/s, the shortest pull's launch speed
inline constexpr double launch_max = 30.0;  ///< m/s, a full pull's
inline constexpr int full_pull_ticks = 90;  ///< ticks of holding for a full pull
inline constexpr int balls_per_game = 3;
inline constexpr int bumper_points = 100, slingshot_points = 10;
inline constexpr int bumper_count = 3;

/// The plunger's actions (TickInput bits), and each flipper's (their keys: app_settings(); the
/// bits are fixstep's default buttons', so recordings made before the game had actions replay).
inline constexpr std::uint32_t plunger_keys = fixstep::button_down | fixstep::button_action;
inline constexpr std::uint32_t left_flipper_key = fixstep::button_left;
inline constexpr std::uint32_t right_flipper_key = fixstep::button_right;

/// BodyDef::user_data: what a body is (bumpers: bumper_tag + their number).
inline constexpr std::uint64_t ball_tag = 1, flipper_tag = 2, slingshot_tag = 3, bumper_tag = 100;

/// The table: walls, the top arc and the plunger lane (static segments), two slingshots
/// (static triangles), three bumpers (static circles), two flippers (dynamic polygons named
/// "flipper_left" and "flipper_right" on revolute joints of the same names) and the ball
/// ("ball", on the plunger).
[[nodiscard]] fixstep::WorldDef make_table();

// --- the rules --------------------------------------------------------------------------------
enum class Phase : std::uint8_t {
  launch,  ///< the ball rests on the plunger: hold down (or Enter) to pull, let go to launch
  play,    ///< the ball is on the table
  over,    ///< no balls left
};

/// Everything the rules remember between ticks. Plain data.
struct GameState {
  Phase phase = Phase::launch;
  int score = 0;
  int balls_left = balls_per_game;  ///< counting the one in play
  int pull = 0;                     ///< ticks the plunger has been held, up to full_pull_ticks
  int bumper_hits = 0, slingshot_hits = 0;
  /// Ticks each bumper stays lit after a hit (drawn brighter).
  std::array<int, bumper_count> lit{};
  friend bool operator==(const GameState&, const GameState&) = default;
};

/// Before a tick (live play; a recording holds the prepared input): each flipper's motor speed
/// this tick, up (towards the raised limit) while its key is held, else down.
void prepare_input(fixstep::TickInput& input, const fixstep::World& sim);

/// After a tick: the rules (plunger, scoring and kicks, the drain, the next ball, game over).
void after_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim);

/// Whether the ball rests on the plunger (in the lane, at its foot, nearly still).
[[nodiscard]] bool on_plunger(const fixstep::World& sim);

/// "score 1200   balls 2" and a hint, for the HUD.
[[nodiscard]] std::vector<std::string> status_lines(const GameState& game);
/// "score=1200 balls=2 bumpers=11 slingshots=4 phase=play" for summaries and tests.
[[nodiscard]] std::string describe(const GameState& game);

}  // namespace pinball
