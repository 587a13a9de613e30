// The peggle demo's rules (demos/peggle), without a window: pegs lit by the ball's contacts and
// cleared at the turn's end, the bucket's sensor giving the ball back, the aim guide's ray, and
// the same game from the same inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "peggle/game.hpp"

namespace peggle_tests {

using fixstep::Entity;
using fixstep::TickInput;
using fixstep::Vec2;

struct Game {
  fixstep::World sim{peggle::make_level()};
  peggle::GameState game;
  TickInput input;
  void tick() {
    sim.step(input);
    peggle::after_tick(game, input, sim);
    input.pressed = 0;
    ++input.tick;
  }
  void shoot_at(Vec2 pointer) {
    input.pointer = pointer;
    tick();  // the aim follows the pointer
    input.pressed = fixstep::button_action;
    tick();
  }
};

TEST(Peggle, AimFollowsThePointerWithinItsLimits) {
  EXPECT_EQ(peggle::aim_from(peggle::launcher + Vec2{0, -5}), 0.0);
  EXPECT_NEAR(peggle::aim_from(peggle::launcher + Vec2{5, -5}), std::atan(1.0), 1e-15);
  EXPECT_NEAR(peggle::aim_from(peggle::launcher + Vec2{-5, -5}), -std::atan(1.0), 1e-15);
  EXPECT_EQ(peggle::aim_from(peggle::launcher + Vec2{5, 5}), peggle::max_aim);  // clamped
  const Vec2 v = peggle::launch_velocity(0.3);
  EXPECT_NEAR(fixstep::length(v), peggle::launch_speed, 1e-12);
}

TEST(Peggle, TheBallLightsExactlyThePegsItTouchesAndTheTurnClearsThem) {
  Game r;
  r.tick();  // rolls the orange pegs
  const int pegs = r.game.pegs_left;
  ASSERT_GT(pegs, 40);
  const std::optional<fixstep::RayHit> guide = peggle::aim_guide(r.sim, 0.2);
  ASSERT_TRUE(guide.has_value());
  EXPECT_TRUE(peggle::is_peg(r.sim, guide->body));  // the guide sees pegs only
  r.shoot_at(peggle::launcher + Vec2{std::sin(0.2), -std::cos(0.2)});
  ASSERT_EQ(r.game.phase, peggle::Phase::flying);
  // Brute force: the least distance of the ball to every peg over the flight.
  std::vector<Entity> all;
  for (const Entity e : r.sim.bodies()) {
    if (peggle::is_peg(r.sim, e)) all.push_back(e);
  }
  std::vector<double> closest(all.size(), 1e9);
  std::vector<Entity> lit;
  while (r.game.phase == peggle::Phase::flying) {
    const Entity ball = r.game.ball;
    const Vec2 b = r.sim.body(ball).position;
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (!r.sim.contains(all[i])) continue;
      closest[i] = std::min(closest[i], fixstep::length(b - r.sim.body(all[i]).position));
    }
    lit = r.game.lit;
    r.tick();
  }
  ASSERT_FALSE(lit.empty());
  const double touch = peggle::ball_radius + peggle::peg_radius;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const bool was_lit = std::find(lit.begin(), lit.end(), all[i]) != lit.end();
    // A touch happens between ticks: the ball's sampled centre comes within a tick's travel.
    if (was_lit) {
      EXPECT_LT(closest[i], touch + 0.2) << "peg " << i << " lit from afar";
    } else {
      EXPECT_GT(closest[i], touch * 0.99) << "peg " << i << " touched, not lit";
    }
    EXPECT_EQ(r.sim.contains(all[i]), !was_lit) << "peg " << i;  // cleared once the ball left
  }
  EXPECT_EQ(r.game.pegs_left, pegs - static_cast<int>(lit.size()));
  EXPECT_EQ(r.game.balls_left, peggle::balls_per_game - 1);
  EXPECT_GE(r.game.score, 10 * static_cast<int>(lit.size()));
}

TEST(Peggle, TheBucketsSensorCatchesABallAndGivesItBack) {
  Game r;
  r.tick();
  for (const Entity e : std::vector<Entity>(r.sim.bodies().begin(), r.sim.bodies().end())) {
    if (peggle::is_peg(r.sim, e)) r.sim.destroy(e);  // a clear field
  }
  r.game.pegs_left = 1;                                          // keep the game going
  for (const char* name : {"catch", "rim_left", "rim_right"}) {  // the bucket under the launcher
    const Entity e = r.sim.find(name);
    const Vec2 at = r.sim.body(e).position;
    r.sim.set_position(e, Vec2{at.x - r.sim.body(r.sim.find("catch")).position.x, at.y});
    r.sim.set_velocity(e, Vec2{0, 0});
  }
  r.shoot_at(peggle::launcher + Vec2{0, -1});
  int ticks = 0;
  while (r.game.phase == peggle::Phase::flying && ticks++ < 1000) r.tick();
  EXPECT_EQ(r.game.caught, 1);
  EXPECT_EQ(r.game.balls_left, peggle::balls_per_game);  // given back
  EXPECT_EQ(r.game.phase, peggle::Phase::aiming);
}

TEST(Peggle, TheSameInputsGiveTheSameGameAndARestoreReplaysIt) {
  auto play = [](Game& r, fixstep::WorldSnapshot* save_at_200, peggle::GameState* saved) {
    for (int t = 0; t < 1500; ++t) {
      r.input.pointer = Vec2{6.0 * std::sin(0.01 * t), 0};
      if (t % 300 == 5) r.input.pressed = fixstep::button_action;
      r.tick();
      if (t == 200 && save_at_200) r.sim.save(*save_at_200), *saved = r.game;
    }
  };
  Game a, b;
  fixstep::WorldSnapshot snap;
  peggle::GameState saved;
  play(a, &snap, &saved);
  play(b, nullptr, nullptr);
  EXPECT_EQ(a.sim.state_hash(), b.sim.state_hash());
  EXPECT_EQ(peggle::describe(a.game), peggle::describe(b.game));
  EXPECT_LT(a.game.balls_left, peggle::balls_per_game);
  // From the snapshot at tick 201, the same inputs again: the same end.
  Game c;
  c.sim.restore(snap);
  c.game = saved;
  c.input.tick = 201;
  for (int t = 201; t < 1500; ++t) {
    c.input.pointer = Vec2{6.0 * std::sin(0.01 * t), 0};
    if (t % 300 == 5) c.input.pressed = fixstep::button_action;
    c.tick();
  }
  EXPECT_EQ(c.sim.state_hash(), a.sim.state_hash());
  EXPECT_EQ(peggle::describe(c.game), peggle::describe(a.game));
}

}  // namespace peggle_tests
