// The airhockey demo's rules (demos/airhockey), without a window or a network: the merged input
// keeps each mallet inside its reach and moves it towards its player's pointer, a puck driven
// into a goal sensor scores for the other player and is served after the pause, the puck's
// speed is limited, and the same inputs give the same game.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "airhockey/game.hpp"

namespace airhockey_tests {

using fixstep::TickInput;
using fixstep::Vec2;

struct Table {
  fixstep::World sim{airhockey::make_level()};
  airhockey::GameState game;
  std::array<TickInput, 2> players{};
  void tick() {
    const TickInput in = airhockey::merge(players, sim);
    sim.step(in);
    airhockey::after_tick(game, sim);
  }
  Vec2 at(const char* name) const { return sim.body(sim.find(name)).position; }
};

TEST(AirHockey, MalletsHeadForTheirPointersAndStayInTheirReach) {
  Table t;
  t.players[0].pointer = {-1.5, 1.0};  // inside player 0's reach
  t.players[1].pointer = {-3.0, 0.0};  // on the other half: player 1's mallet stops at the line
  for (int k = 0; k < 240; ++k) t.tick();
  EXPECT_NEAR(t.at("mallet0").x, -1.5, 1e-3);
  EXPECT_NEAR(t.at("mallet0").y, 1.0, 1e-3);
  const airhockey::Reach r1 = airhockey::reach(1);
  EXPECT_NEAR(t.at("mallet1").x, r1.lo.x, 1e-9);  // clamped to its reach, never past it
  EXPECT_GE(t.at("mallet1").x, r1.lo.x);
}

TEST(AirHockey, ArrowsDriveTheMalletAtItsTopSpeed) {
  Table t;
  t.players[0].held = fixstep::button_up;
  const double y0 = t.at("mallet0").y;
  t.tick();
  EXPECT_NEAR(t.at("mallet0").y - y0, airhockey::mallet_speed * airhockey::dt, 1e-12);
  // Held long enough, they stop at the edge of the reach: never past the centre line.
  t.players[1].held = fixstep::button_left;
  for (int k = 0; k < 240; ++k) t.tick();
  EXPECT_NEAR(t.at("mallet1").x, airhockey::reach(1).lo.x, 1e-12);
  EXPECT_NEAR(t.at("mallet0").y, airhockey::reach(0).hi.y, 1e-12);
}

TEST(AirHockey, APuckInAGoalScoresForTheOtherPlayerAndIsServedAfterThePause) {
  Table t;
  const fixstep::Entity puck = t.sim.find("puck");
  t.sim.set_position(puck, {-3.0, 0.5});   // past player 0's mallet (at (-2.6, 0))
  t.sim.set_velocity(puck, {-8.0, -2.0});  // into player 0's (left) goal
  t.players[0].pointer = {-2.6, -1.8};     // mallets out of the way
  t.players[1].pointer = {2.6, -1.8};
  int ticks = 0;
  while (t.game.score[1] == 0 && ticks < 240) t.tick(), ++ticks;
  EXPECT_EQ(t.game.score, (std::array<int, 2>{0, 1}));
  EXPECT_LT(ticks, 15);  // into the crease (0.86 m from the goal's centre) within 0.2 m
  EXPECT_EQ(t.at("puck").x, 0.0);
  EXPECT_EQ(t.game.serve_to, 0);
  for (int k = 0; k < airhockey::serve_ticks; ++k) t.tick();
  EXPECT_LT(t.sim.body(puck).velocity.x, 0.0);  // served towards the player scored on
  EXPECT_EQ(t.game.serve_wait, 0);
}

TEST(AirHockey, ThePuckIsSlowedToItsTopSpeed) {
  Table t;
  const fixstep::Entity puck = t.sim.find("puck");
  t.sim.set_velocity(puck, {0.0, 40.0});
  t.tick();
  const Vec2 v = t.sim.body(puck).velocity;
  EXPECT_LE(std::sqrt(v.x * v.x + v.y * v.y), airhockey::puck_top_speed * (1 + 1e-12));
}

TEST(AirHockey, TheSameBotInputsGiveTheSameGame) {
  Table a, b;
  for (int k = 0; k < 600; ++k) {
    for (int p = 0; p < 2; ++p) {
      a.players[static_cast<std::size_t>(p)].pointer = airhockey::bot_pointer(p, k);
      b.players[static_cast<std::size_t>(p)].pointer = airhockey::bot_pointer(p, k);
    }
    a.tick();
    b.tick();
  }
  EXPECT_EQ(a.sim.state_hash(), b.sim.state_hash());
  EXPECT_EQ(a.game, b.game);
}

}  // namespace airhockey_tests
