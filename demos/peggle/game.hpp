// peggle: a Peggle-like on fixstep's public API. Aim the launcher with the pointer, shoot ten
// balls into a field of pegs; a peg the ball touches lights up and is cleared when the ball
// leaves the field; a ball caught by the moving bucket is given back.
//
// What the engine does for the game, and what the game does itself:
//   - contacts: the ball bounces off static pegs and the walls at its time of impact; the game
//     reads World::contacts_begun() to light a peg;
//   - a sensor: the bucket's catch zone (a kinematic sensor disc riding with the bucket) reports
//     the ball through World::sensors_begun();
//   - collision filters: balls never touch each other (one negative group), the catch zone sees
//     only balls (its mask);
//   - a query: the aim guide is World::cast_ray against the pegs (a QueryFilter of their
//     category), drawn by the game;
//   - deterministic maths: the aim angle is det::atan2 of the pointer and the launch velocity
//     det::sin/cos of the clamped angle; which pegs are orange is rolled with World::random()
//     in the first tick's rules, so a replay rolls the same.
// The rules keep their state in GameState (plain data, copied with the game by app::run for
// restarts, replays and the sync test).
#pragma once

#include <cstdint>
#include <fixstep/core/input.hpp>
#include <fixstep/core/query.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <optional>
#include <string>
#include <vector>

namespace peggle {

// --- the level (units: m, kg, s) --------------------------------------------------------------
inline constexpr double dt = 1.0 / 120.0;         ///< s, one tick
inline constexpr fixstep::Vec2 launcher{0, 9};    ///< m, where balls leave
inline constexpr double launch_speed = 9.0;       ///< m/s
inline constexpr double max_aim = 1.35;           ///< rad from straight down, either side
inline constexpr double half_width = 8.0;         ///< m, walls at x = ±half_width
inline constexpr double floor_y = -11.0;          ///< m, a ball below it has left the field
inline constexpr double ball_radius = 0.22;       ///< m
inline constexpr double peg_radius = 0.25;        ///< m
inline constexpr double bucket_y = -9.6;          ///< m, height of the bucket's rims
inline constexpr double bucket_half_width = 1.1;  ///< m, rim to centre
inline constexpr double bucket_speed = 3.0;       ///< m/s, left and right
inline constexpr int balls_per_game = 10;
inline constexpr int orange_pegs = 8;  ///< rolled at the first tick
inline constexpr int blue_points = 10, orange_points = 100;

/// Collision categories (CollisionFilter bits).
inline constexpr std::uint64_t ball_category = 1, peg_category = 2, bucket_category = 4;
/// BodyDef::user_data: what a body is (pegs: peg_tag + their number).
inline constexpr std::uint64_t ball_tag = 1, rim_tag = 2, catch_tag = 3, peg_tag = 1000;

/// The level: rows of static pegs, two walls (planes), the bucket (two kinematic rim discs and a
/// kinematic sensor between them, moving at bucket_speed). Contacts on (restitution 0.7).
[[nodiscard]] fixstep::WorldDef make_level();

// --- the rules --------------------------------------------------------------------------------
enum class Phase : std::uint8_t {
  aiming,  ///< the pointer aims; press (mouse or Enter) to shoot
  flying,  ///< a ball is in the field
  over,    ///< no balls left, or every peg cleared
};

/// Everything the rules remember between ticks. Plain data.
struct GameState {
  Phase phase = Phase::aiming;
  int score = 0;
  int balls_left = balls_per_game;
  int caught = 0;          ///< balls the bucket gave back
  int pegs_left = 0;       ///< set at the first tick
  bool rolled = false;     ///< the orange pegs were chosen
  fixstep::Entity ball{};  ///< the ball in play (flying)
  int flight_ticks = 0;
  double aim = 0.0;                  ///< rad from straight down (positive: to the right)
  std::vector<fixstep::Entity> lit;  ///< pegs lit by the ball in play, in order
  friend bool operator==(const GameState&, const GameState&) = default;
};

/// The aim angle (rad from straight down, within ±max_aim) the pointer at `pointer` gives.
[[nodiscard]] double aim_from(fixstep::Vec2 pointer);
/// The launch velocity of angle `aim`, m/s.
[[nodiscard]] fixstep::Vec2 launch_velocity(double aim);

/// After a tick: the rules (shoot, light pegs, the bucket, clear pegs, game over).
void after_tick(GameState& game, const fixstep::TickInput& input, fixstep::World& sim);

/// Whether body `e` is a peg of the level (by its user data), and whether it is orange.
[[nodiscard]] bool is_peg(const fixstep::World& sim, fixstep::Entity e);

/// The aim guide: where a ball launched at `aim` would first meet a peg if it flew straight
/// for 2 s of launch speed (World::cast_ray against the pegs), or nullopt.
[[nodiscard]] std::optional<fixstep::RayHit> aim_guide(const fixstep::World& sim, double aim);

/// "score 120   balls 7   pegs 38" and a hint, for the HUD.
[[nodiscard]] std::vector<std::string> status_lines(const GameState& game);
/// "score=120 balls=7 caught=1 pegs=38 phase=aiming" for summaries and tests.
[[nodiscard]] std::string describe(const GameState& game);

}  // namespace peggle
