// The pinball demo's rules (demos/pinball), without a window: the flippers swinging on their
// revolute joints' motors between their limits, a flip sending the ball up the table, fast balls
// never passing through a turning flipper, bumpers scoring and kicking, the plunger, the drain
// and the end of the game.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fixstep/core/shape.hpp>

#include "pinball/game.hpp"

namespace pinball_tests {

using fixstep::Body;
using fixstep::Entity;
using fixstep::TickInput;
using fixstep::Vec2;

struct Table {
  fixstep::World sim{pinball::make_table()};
  pinball::GameState game;
  TickInput input;
  Entity ball = sim.find("ball");
  Entity left = sim.find("flipper_left"), right = sim.find("flipper_right");
  void tick() {
    input.bodies.clear(), input.joints.clear();
    pinball::prepare_input(input, sim);
    sim.step(input);
    pinball::after_tick(game, input, sim);
    ++input.tick;
  }
  void put_ball(Vec2 at, Vec2 v = {}) {
    sim.set_body(ball, Body{.mass = pinball::ball_mass, .position = at, .velocity = v});
    game.phase = pinball::Phase::play;
  }
};

/// The ball's centre in the left flipper's frame (x along it from the pivot, y across).
Vec2 in_flipper_frame(const fixstep::World& sim, Entity flipper, Vec2 p) {
  const Body f = sim.body(flipper);
  const Vec2 d = p - f.position;
  const double c = std::cos(f.angle), s = std::sin(f.angle);
  return {c * d.x + s * d.y, -s * d.x + c * d.y};
}

// A flipper's key held: its motor swings it up at no more than the motor's speed, to its raised
// limit, where it stays (within the joints' angular slop, 2°) while the other rests; released,
// it swings back down to rest.
TEST(Pinball, FlippersSwingOnTheirMotorsBetweenTheirLimits) {
  Table t;
  t.put_ball({0.0, 12.0});  // out of the way
  const double slop = 2.0 / 180.0 * 3.141592653589793;
  EXPECT_EQ(t.sim.body(t.left).angle, pinball::flipper_rest);
  EXPECT_EQ(t.sim.body(t.right).angle, -pinball::flipper_rest);
  t.input.held = pinball::left_flipper_key;
  int ticks = 0;
  while (t.sim.body(t.left).angle < pinball::flipper_raised - slop && ticks < 30) {
    t.tick();
    ++ticks;
    // (a flipper turns 0.27 rad a tick at 32 rad/s and 1/120 s, past fast_joint_turn: its
    // hinge's position correction gives its impulse along the gradient now, which takes from
    // the turn; along the start's it added a share of (ω dt)² = 0.07, 5.4 % here)
    EXPECT_LE(t.sim.body(t.left).angular_velocity, pinball::flipper_speed);
  }
  // (0.45 + 0.52) rad at 32 rad/s: four ticks of 1/120 s at the motor's speed; the flipper is
  // spun up within its first tick by a 600 N·m motor, and the last degrees are the limit's.
  EXPECT_LE(ticks, 6);
  for (int k = 0; k < 30; ++k) {
    t.tick();
    EXPECT_NEAR(t.sim.body(t.left).angle, pinball::flipper_raised, slop) << "held up, tick " << k;
    EXPECT_NEAR(t.sim.body(t.right).angle, -pinball::flipper_rest, slop) << "its key not held";
  }
  t.input.held = 0;
  for (int k = 0; k < 10; ++k) t.tick();
  EXPECT_NEAR(t.sim.body(t.left).angle, pinball::flipper_rest, slop);
}

// A ball held on a raised flipper rolls back to its pivot; the flipper let down, the ball rolls
// down it and off its tip into the drain, on either side. (When an inlane's foot lay below its
// flipper's back end, such a ball came to rest for ever in the notch between them: the
// autopilot's sessions ended there.)
TEST(Pinball, ABallRolledBackToAFlippersPivotDrainsOnceItIsDown) {
  for (const double side : {-1.0, 1.0}) {
    Table t;
    t.input.held = side < 0 ? pinball::left_flipper_key : pinball::right_flipper_key;
    for (int k = 0; k < 20; ++k) t.tick();  // raised
    const double up = side * pinball::flipper_raised;
    const double along = 0.9;  // m from the pivot, on the flipper's top
    t.put_ball({side * (pinball::flipper_x - along * std::cos(up)) - side * 0.3 * std::sin(up),
                pinball::flipper_y + along * std::sin(up) + 0.3 * std::cos(up)});
    for (int k = 0; k < 120; ++k) t.tick();  // it rolls back to the pivot
    t.input.held = 0;
    int ticks = 0;
    while (t.game.balls_left == pinball::balls_per_game && ticks < 600) {
      t.tick();
      ++ticks;
    }
    EXPECT_LT(ticks, 600) << "side " << side << ": the ball did not drain within 5 s, at "
                          << t.sim.body(t.ball).position.x << ", " << t.sim.body(t.ball).position.y;
  }
}

TEST(Pinball, AFlipSendsTheBallUpTheTableAndABumperScores) {
  Table t;
  // The ball resting on the left flipper, two thirds along it.
  const double along = 1.0, c = std::cos(pinball::flipper_rest),
               s = std::sin(pinball::flipper_rest);
  const Vec2 on{-pinball::flipper_x + along * c - 0.5 * s,
                pinball::flipper_y + along * s + 0.5 * c};
  t.put_ball(on);
  for (int k = 0; k < 20; ++k) t.tick();  // settles on the flipper
  ASSERT_LT(t.sim.body(t.ball).position.y, 3.0);
  t.input.held = pinball::left_flipper_key;
  double fastest = 0.0;
  for (int k = 0; k < 12; ++k) {
    t.tick();
    fastest = std::max(fastest, t.sim.body(t.ball).velocity.y);
  }
  EXPECT_GT(fastest, 15.0);  // m/s up the table
  // Then a bumper: the ball straight at the left one from below scores and is kicked back.
  t.input.held = 0;
  const Entity bumper = t.sim.find("bumper0");
  const Vec2 at = t.sim.body(bumper).position;
  t.put_ball({at.x, at.y - 1.5}, {0.0, 8.0});
  const int score = t.game.score;
  for (int k = 0; k < 30 && t.game.bumper_hits == 0; ++k) t.tick();
  EXPECT_EQ(t.game.bumper_hits, 1);
  EXPECT_EQ(t.game.score, score + pinball::bumper_points);
  EXPECT_NEAR(t.sim.body(t.ball).velocity.y, -pinball::bumper_kick, 1e-9);  // kicked to its speed
}

TEST(Pinball, FastBallsNeverPassThroughATurningFlipper) {
  for (const double speed : {20.0, 40.0, 60.0}) {
    for (const double along : {0.2, 0.8, 1.4}) {
      for (int delay = 0; delay < 6; ++delay) {
        Table t;
        const double c = std::cos(pinball::flipper_rest), s = std::sin(pinball::flipper_rest);
        t.put_ball({-pinball::flipper_x + along * c, pinball::flipper_y + along * s + 1.5},
                   {0.0, -speed});
        Vec2 before = in_flipper_frame(t.sim, t.left, t.sim.body(t.ball).position);
        for (int k = 0; k < 40; ++k) {
          if (k == delay) t.input.held = pinball::left_flipper_key;
          t.tick();
          const Vec2 now = in_flipper_frame(t.sim, t.left, t.sim.body(t.ball).position);
          const bool over = now.x > 0 && now.x < pinball::flipper_length && before.x > 0 &&
                            before.x < pinball::flipper_length;
          EXPECT_FALSE(over && before.y > 0 && now.y < 0)
              << "through the flipper at " << speed << " m/s, " << along
              << " m along, flip at tick " << delay << ", tick " << k;
          before = now;
        }
      }
    }
  }
}

TEST(Pinball, ThePlungerLaunchesAndThreeDrainedBallsEndTheGame) {
  Table t;
  ASSERT_TRUE(pinball::on_plunger(t.sim));
  t.input.held = fixstep::button_down;
  for (int k = 0; k < pinball::full_pull_ticks + 10; ++k) t.tick();
  EXPECT_EQ(t.game.pull, pinball::full_pull_ticks);
  t.input.held = 0;
  t.tick();
  EXPECT_GT(t.sim.body(t.ball).velocity.y, pinball::launch_max - 1.0);
  for (int k = 0; k < 10; ++k) t.tick();
  EXPECT_EQ(t.game.phase, pinball::Phase::play);
  for (int b = pinball::balls_per_game; b > 0; --b) {
    EXPECT_EQ(t.game.balls_left, b);
    t.put_ball({0.0, 0.5}, {0.0, -5.0});  // between the flippers, falling
    for (int k = 0; k < 30; ++k) t.tick();
    EXPECT_EQ(t.game.balls_left, b - 1);
  }
  EXPECT_EQ(t.game.phase, pinball::Phase::over);
  EXPECT_EQ(pinball::describe(t.game), "score=0 balls=0 bumpers=0 slingshots=0 phase=over");
}

}  // namespace pinball_tests
