// The character mover (BodyDef::mover, mover.hpp; docs/MOVER.md): exact checks of walking up a
// 45° slope at the wanted speed, stopping at a 60° one, stepping up a step of step_height and
// not one 1 mm higher, landing (on_floor, v.y = 0), standing on a 40° slope, riding a moving and
// a turning platform, pushing a crate with at most push_force, walls and ceilings; snapshots,
// threads, and the definitions refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/mover.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"

// support/count_new.cpp: bytes the global operator new hands out while counting.
extern std::atomic<bool> counting;
extern std::atomic<std::size_t> counted_bytes;

namespace fixstep {
namespace mover_test {  // named: a unity batch shares anonymous namespaces

constexpr double dt = 1.0 / 60.0;       // s
constexpr double g = 9.81;              // m/s², the game's gravity
constexpr double radius = 0.3;          // m, the capsule's
constexpr double half = 0.5;            // m, half its segment
constexpr double foot = half + radius;  // m, from its position down to its lowest point
constexpr double skin = 0.005;          // m, MoverDef's default

WorldSettings settings(int threads = 1) {
  WorldSettings s{.dt = dt};
  s.contacts = ContactSettings{};
  s.threads = threads;
  return s;
}

BodyDef mover_def(Vec2 at, MoverDef md = {}) {
  BodyDef b;
  b.name = "mover";
  b.type = BodyType::kinematic;
  b.body.position = at;
  b.shapes = {make_capsule({0.0, -half}, {0.0, half}, radius)};
  b.mover = md;
  return b;
}

BodyDef static_box(Vec2 centre, double hx, double hy, double friction = 0.6) {
  BodyDef b;
  b.type = BodyType::static_body;
  b.body.position = centre;
  b.shapes = {make_box(hx, hy)};
  b.shapes[0].friction = friction;
  return b;
}

/// A game's rules, as Godot's platformer template writes them: the wanted horizontal speed,
/// gravity added while not on the floor, a jump from the floor.
void play(World& w, Entity e, double vx, double jump = 0.0) {
  const MoverState s = w.mover_state(e);
  double vy = s.velocity.y;
  if (jump > 0.0 && s.on_floor) {
    vy = jump;
  } else if (!s.on_floor) {
    vy -= g * dt;
  }
  TickInput in;
  in.bodies.push_back(BodyInput{e, BodyInputKind::velocity, {vx, vy}});
  w.step(in);
}

/// The gap between the capsule's lowest point and the height `ground` (m).
double gap(const World& w, Entity e, double ground) {
  return w.body(e).position.y - foot - ground;
}

// Falling from 0.5 m onto a segment: on_floor, v.y exactly 0, floor normal +y, resting skin
// above the ground (the cast stops within 10⁻⁵ m of skin).
TEST(Mover, LandsOnAFloorWithNoVerticalSpeedLeft) {
  World w(WorldDef::empty(Precision::f64, settings()));
  w.add_segment(SegmentDef{.a = {-50.0, 0.0}, .b = {50.0, 0.0}});
  const Entity e = w.create_body(mover_def({0.0, foot + 0.5}));
  bool landed = false;
  for (int t = 0; t < 60; ++t) {
    play(w, e, 0.0);
    const MoverState s = w.mover_state(e);
    if (!landed && s.on_floor) {
      landed = true;
      EXPECT_EQ(s.velocity.y, 0.0);
      EXPECT_EQ(s.floor_normal.y, 1.0);
      EXPECT_TRUE(s.floor_body.is_null());
    }
  }
  ASSERT_TRUE(landed);
  EXPECT_TRUE(w.mover_state(e).on_floor);
  EXPECT_EQ(w.body(e).velocity.y, 0.0);
  EXPECT_GE(gap(w, e, 0.0), skin - 1e-12);
  EXPECT_LE(gap(w, e, 0.0), skin + 1e-5);
  EXPECT_EQ(w.body(e).position.x, 0.0);
}

// Up a 45° slope (a polyline from flat ground) at 3 m/s: on the slope every tick moves
// 3 m/s · dt along it (Godot's constant speed on floors), to 10⁻⁹ m.
TEST(Mover, ClimbsA45DegreeSlopeAtItsWantedSpeed) {
  World w(WorldDef::empty(Precision::f64, settings()));
  const std::vector<Vec2> ground{{-10.0, 0.0}, {0.0, 0.0}, {10.0, 10.0}};
  w.add_polyline(ground, 0.0, 0.6);
  const Entity e = w.create_body(mover_def({-2.0, foot + skin}));
  int measured = 0;
  for (int t = 0; t < 180; ++t) {
    play(w, e, 3.0);
    const Body b = w.body(e);
    if (b.position.x < 1.0 || b.position.x > 8.0) continue;
    const MoverState s = w.mover_state(e);
    ASSERT_TRUE(s.on_floor);
    EXPECT_NEAR(std::sqrt(dot(s.displacement, s.displacement)), 3.0 * dt, 1e-9);
    EXPECT_NEAR(s.displacement.y, s.displacement.x, 1e-9);
    ++measured;
  }
  EXPECT_GT(measured, 30);
}

// A 60° slope is a wall to a mover whose floor angle is 50°: walking into it for 3 s it rises
// not at all and stops; on_wall.
TEST(Mover, MakesNoProgressUpA60DegreeSlope) {
  World w(WorldDef::empty(Precision::f64, settings()));
  const double rise = std::tan(std::numbers::pi / 3.0);
  const std::vector<Vec2> ground{{-10.0, 0.0}, {0.0, 0.0}, {5.0, 5.0 * rise}};
  w.add_polyline(ground, 0.0, 0.6);
  const Entity e = w.create_body(mover_def({-2.0, foot + skin}));
  double x_at_2s = 0.0;
  for (int t = 0; t < 180; ++t) {
    play(w, e, 3.0);
    EXPECT_LE(gap(w, e, 0.0), skin + 1e-5) << "tick " << t;
    if (t == 119) x_at_2s = w.body(e).position.x;
  }
  const MoverState s = w.mover_state(e);
  EXPECT_TRUE(s.on_floor);
  EXPECT_TRUE(s.on_wall);
  EXPECT_EQ(w.body(e).position.x, x_at_2s);
  EXPECT_LT(w.body(e).position.x, 0.0);
  EXPECT_EQ(w.body(e).velocity.x, 0.0);
}

/// Walks a mover at 2 m/s for 3 s towards a box step of height h at x >= 0; returns it. On the
/// flat ground and on the step's top it walks at 2 m/s (each tick 2 m/s · dt, to 10⁻⁹ m).
Entity walk_to_step(World& w, double h) {
  w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}});
  w.create_body(static_box({5.0, 0.5 * h}, 5.0, 0.5 * h));
  const Entity e = w.create_body(mover_def({-2.0, foot + skin}));
  for (int t = 0; t < 180; ++t) {
    play(w, e, 2.0);
    const double x = w.body(e).position.x;
    if (x < -1.0 || x > 1.0) {
      EXPECT_NEAR(w.mover_state(e).displacement.x, 2.0 * dt, 1e-9);
    }
  }
  return e;
}

// step_height 0.2 m: a step of 0.2 m is walked up (it ends on top, skin above it, far past
// the edge); one of 0.201 m stops it where its round bottom touches the step's corner (its
// lower end's centre skin + r from the corner), on the ground, on_wall.
TEST(Mover, StepsUpItsStepHeightButNotAMillimetreMore) {
  {
    World w(WorldDef::empty(Precision::f64, settings()));
    const Entity e = walk_to_step(w, 0.2);
    EXPECT_GT(w.body(e).position.x, 2.0);
    EXPECT_GE(gap(w, e, 0.2), skin - 1e-9);
    EXPECT_LE(gap(w, e, 0.2), 2.0 * skin);
    EXPECT_TRUE(w.mover_state(e).on_floor);
  }
  {
    World w(WorldDef::empty(Precision::f64, settings()));
    const Entity e = walk_to_step(w, 0.201);
    const double below = radius + skin - 0.201;  // the corner under the lower end's centre
    const double x = -std::sqrt((radius + skin) * (radius + skin) - below * below);
    EXPECT_NEAR(w.body(e).position.x, x, 1e-4);
    EXPECT_LE(gap(w, e, 0.0), skin + 1e-5);
    EXPECT_TRUE(w.mover_state(e).on_wall);
    EXPECT_TRUE(w.mover_state(e).on_floor);
  }
}

// Dropped onto a 40° slope and left standing for 2 s: it lands straight down (x unchanged to
// the bit) and then does not move at all; on_floor with the slope's normal.
TEST(Mover, StandsStillOnA40DegreeSlope) {
  World w(WorldDef::empty(Precision::f64, settings()));
  const double a = 40.0 * std::numbers::pi / 180.0;
  const std::vector<Vec2> ground{{-10.0, -10.0 * std::tan(a)}, {10.0, 10.0 * std::tan(a)}};
  w.add_polyline(ground, 0.0, 0.6);
  const Entity e = w.create_body(mover_def({0.0, 2.0}));
  Vec2 rest{};
  for (int t = 0; t < 180; ++t) {
    play(w, e, 0.0);
    EXPECT_EQ(w.body(e).position.x, 0.0);
    if (t == 59) rest = w.body(e).position;
  }
  const MoverState s = w.mover_state(e);
  ASSERT_TRUE(s.on_floor);
  EXPECT_EQ(w.body(e).position, rest);
  EXPECT_NEAR(s.floor_normal.x, -std::sin(a), 1e-12);
  EXPECT_NEAR(s.floor_normal.y, std::cos(a), 1e-12);
  EXPECT_EQ(s.velocity, (Vec2{0.0, 0.0}));
}

// On a kinematic platform moving at (1.5, 0.5) m/s, then at (−1, −0.5) m/s: every tick the
// mover moves as the platform does, to 10⁻⁹ m, and stands on it (floor_body).
TEST(Mover, RidesAMovingPlatform) {
  World w(WorldDef::empty(Precision::f64, settings()));
  BodyDef p;
  p.type = BodyType::kinematic;
  p.shapes = {make_box(2.0, 0.1)};
  const Entity platform = w.create_body(p);
  const Entity e = w.create_body(mover_def({0.5, 0.1 + foot + 0.1}));
  for (int t = 0; t < 30; ++t) play(w, e, 0.0);
  ASSERT_TRUE(w.mover_state(e).on_floor);
  for (const Vec2 u : {Vec2{1.5, 0.5}, Vec2{-1.0, -0.5}}) {
    w.set_velocity(platform, u);
    for (int t = 0; t < 60; ++t) {
      const Vec2 before = w.body(platform).position, mover = w.body(e).position;
      play(w, e, 0.0);
      const Vec2 moved = w.body(platform).position - before;
      const Vec2 carried = w.body(e).position - mover;
      EXPECT_NEAR(carried.x, moved.x, 1e-9);
      EXPECT_NEAR(carried.y, moved.y, 1e-9);
      ASSERT_TRUE(w.mover_state(e).on_floor) << "tick " << t;
      EXPECT_EQ(w.mover_state(e).floor_body, platform);
    }
  }
}

// On a platform turning at 0.5 rad/s about its centre (the origin) for 0.5 s: the point the
// mover stands on (the centre of its capsule's lower end; the capsule stays upright) turns
// with it about the centre, to 10⁻⁹ m, and it stays on it.
TEST(Mover, RidesATurningPlatformAroundItsCentre) {
  World w(WorldDef::empty(Precision::f64, settings()));
  BodyDef p;
  p.type = BodyType::kinematic;
  p.shapes = {make_box(3.0, 0.1)};
  const Entity platform = w.create_body(p);
  const Entity e = w.create_body(mover_def({1.5, 0.1 + foot + 0.1}));
  for (int t = 0; t < 30; ++t) play(w, e, 0.0);
  ASSERT_TRUE(w.mover_state(e).on_floor);
  const Vec2 p0 = w.body(e).position;
  const double omega = 0.5;
  TickInput turn;
  turn.bodies.push_back(BodyInput{platform, BodyInputKind::angular_velocity, {omega, 0.0}});
  w.step(turn);  // the first tick of the turn (the mover stood still)
  for (int t = 1; t < 30; ++t) play(w, e, 0.0);
  const double a = omega * 30 * dt;
  const Vec2 f0 = p0 - Vec2{0.0, half};  // the centre of the capsule's lower end
  const Vec2 expected =
      Vec2{std::cos(a) * f0.x - std::sin(a) * f0.y, std::sin(a) * f0.x + std::cos(a) * f0.y} +
      Vec2{0.0, half};
  EXPECT_NEAR(w.body(e).position.x, expected.x, 1e-9);
  EXPECT_NEAR(w.body(e).position.y, expected.y, 1e-9);
  EXPECT_TRUE(w.mover_state(e).on_floor);
  EXPECT_EQ(w.mover_state(e).floor_body, platform);
}

// A 20 kg crate (μ = 0.2 with the ground) pushed by a mover walking at 6 m/s with push_force
// 100 N: it accelerates at F/m − μ g = 3.038 m/s², to 1 %, never faster than F/m.
TEST(Mover, PushesACrateWithAtMostItsPushForce) {
  World w(WorldDef::empty(Precision::f64, settings()));
  w.create_body(static_box({0.0, -0.5}, 50.0, 0.5, 0.2));
  BodyDef crate;
  crate.body.mass = 20.0;
  crate.body.position = {1.0, 0.4};
  crate.shapes = {make_box(0.6, 0.4)};
  crate.shapes[0].friction = 0.2;
  crate.gravity = Gravity{{0.0, -g}};
  const Entity box = w.create_body(crate);
  MoverDef md;
  md.push_force = 100.0;
  const Entity e = w.create_body(mover_def({-1.0, foot + skin}, md));
  std::vector<double> speed;
  for (int t = 0; t < 90; ++t) {
    play(w, e, 6.0);
    speed.push_back(w.body(box).velocity.x);
  }
  int first = 0;
  while (first < 90 && speed[first] == 0.0) ++first;
  ASSERT_LT(first, 30);
  const int t1 = first + 10, t2 = first + 50;
  const double a = (speed[t2] - speed[t1]) / ((t2 - t1) * dt);
  EXPECT_NEAR(a, 100.0 / 20.0 - 0.2 * g, 0.01 * (100.0 / 20.0 - 0.2 * g));
  for (int t = 1; t < 90; ++t) EXPECT_LE(speed[t] - speed[t - 1], 100.0 / 20.0 * dt + 1e-12);
  EXPECT_LT(speed.back(), 6.0);
}

// Walking into a wall: on_wall with the wall's normal and no horizontal speed left; jumping
// into a ceiling: on_ceiling and no vertical speed left.
TEST(Mover, WallsAndCeilings) {
  World w(WorldDef::empty(Precision::f64, settings()));
  w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}});
  w.create_body(static_box({3.0, 2.0}, 0.5, 2.0));    // a wall from x = 2.5
  w.create_body(static_box({-3.0, 2.5}, 1.0, 0.25));  // a ceiling 2.25 m up over x = -3
  const Entity e = w.create_body(mover_def({0.0, foot + skin}));
  for (int t = 0; t < 90; ++t) play(w, e, 3.0);
  MoverState s = w.mover_state(e);
  EXPECT_TRUE(s.on_wall);
  EXPECT_NEAR(s.wall_normal.x, -1.0, 1e-12);
  EXPECT_NEAR(s.wall_normal.y, 0.0, 1e-12);
  EXPECT_EQ(s.velocity.x, 0.0);
  EXPECT_NEAR(w.body(e).position.x, 2.5 - radius - skin, 1e-4);
  w.set_position(e, {-3.0, foot + skin});
  bool ceiling = false;
  for (int t = 0; t < 60 && !ceiling; ++t) {
    play(w, e, 0.0, t == 2 ? 6.0 : 0.0);
    s = w.mover_state(e);
    if (s.on_ceiling) {
      ceiling = true;
      EXPECT_EQ(s.velocity.y, 0.0);
      EXPECT_NEAR(w.body(e).position.y + half + radius, 2.25 - skin, 1e-4);
    }
  }
  EXPECT_TRUE(ceiling);
}

// Walking off a ledge onto a 30° slope down: snapped to it every tick (on_floor throughout).
TEST(Mover, SnapsToTheFloorWalkingDownASlope) {
  World w(WorldDef::empty(Precision::f64, settings()));
  const double drop = std::tan(std::numbers::pi / 6.0);
  const std::vector<Vec2> ground{{-10.0, 0.0}, {0.0, 0.0}, {10.0, -10.0 * drop}};
  w.add_polyline(ground, 0.0, 0.6);
  const Entity e = w.create_body(mover_def({-1.0, foot + skin}));
  for (int t = 0; t < 120; ++t) {
    play(w, e, 4.0);
    ASSERT_TRUE(w.mover_state(e).on_floor) << "tick " << t;
  }
  EXPECT_GT(w.body(e).position.x, 5.0);
}

// A crate dropped onto a standing mover's head rests there (the mover is a kinematic capsule in
// the contact solver, its round top the crate's one support); the crate resting within the
// contact solver's slop does not stop the mover walking on (a dynamic body is not pushed out
// of, only not gone deeper into).
TEST(Mover, ACrateRestsOnItsHead) {
  World w(WorldDef::empty(Precision::f64, settings()));
  w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}});
  const Entity e = w.create_body(mover_def({0.0, foot + skin}));
  BodyDef crate;
  crate.body.mass = 2.0;
  crate.body.position = {0.0, 2.5};
  crate.shapes = {make_box(0.2, 0.2)};
  crate.shapes[0].friction = 1.0;
  crate.gravity = Gravity{{0.0, -g}};
  const Entity box = w.create_body(crate);
  for (int t = 0; t < 120; ++t) play(w, e, 0.0);
  const double top = w.body(e).position.y + half + radius;
  EXPECT_NEAR(w.body(box).position.y, top + 0.2, 0.01);  // within the contact slop
  EXPECT_NEAR(w.body(box).velocity.y, 0.0, 1e-3);
  EXPECT_EQ(w.body(box).position.x, 0.0);
  for (int t = 0; t < 30; ++t) play(w, e, 1.0);  // walking, it moves out from under the crate
  EXPECT_GT(w.body(e).position.x, 0.45);
}

// A crate sliding down a 20° slope (μ 0.1) comes to lean on a mover standing at its foot and
// stays pressed against it: the mover is not pushed away by it (it stays where it stood, to the
// bit) and holds it (a kinematic capsule).
TEST(Mover, ACrateLeaningOnItDoesNotPushItAway) {
  World w(WorldDef::empty(Precision::f64, settings()));
  const double a = 20.0 * std::numbers::pi / 180.0;
  const std::vector<Vec2> ground{{-10.0, 0.0}, {0.35, 0.0}, {10.0, 9.65 * std::tan(a)}};
  w.add_polyline(ground, 0.0, 0.1);
  const Entity e = w.create_body(mover_def({0.0, foot + skin}));
  BodyDef crate;
  crate.body.mass = 5.0;
  crate.body.position = {2.0, 1.65 * std::tan(a) + 0.25};
  crate.body.angle = a;
  crate.shapes = {make_box(0.2, 0.2)};
  crate.shapes[0].friction = 0.1;
  crate.gravity = Gravity{{0.0, -g}};
  const Entity box = w.create_body(crate);
  for (int t = 0; t < 60; ++t) play(w, e, 0.0);
  const Vec2 stood = w.body(e).position;
  for (int t = 0; t < 120; ++t) play(w, e, 0.0);
  EXPECT_EQ(w.body(e).position, stood);
  EXPECT_LT(w.body(box).position.x, 1.0);  // it came down to the mover
  EXPECT_NEAR(w.body(box).velocity.x, 0.0, 1e-2);
}

// One-way platforms (SegmentDef::one_way, ShapeDef::one_way), 1.5 m up over the mover: it jumps
// up through each from below (not stopped, no on_ceiling) and lands on it from above, standing
// skin above its top, on_floor; a jump from there and a fall land on it again.
TEST(Mover, JumpsUpThroughOneWayPlatformsAndLandsOnThem) {
  for (const bool shape : {false, true}) {
    SCOPED_TRACE(shape ? "a one-way box" : "a one-way segment");
    World w(WorldDef::empty(Precision::f64, settings()));
    w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}});
    double top = 1.5;
    if (shape) {
      BodyDef p = static_box({0.0, 1.4}, 2.0, 0.1);
      p.shapes[0].one_way = true;
      w.create_body(p);
    } else {
      w.add_segment(SegmentDef{.a = {-2.0, top}, .b = {2.0, top}, .one_way = true});
    }
    const Entity e = w.create_body(mover_def({0.0, foot + skin}));
    play(w, e, 0.0);
    bool ceiling = false;
    for (int t = 0; t < 120; ++t) {
      play(w, e, 0.0, t == 0 ? 7.0 : 0.0);  // up to 2.5 m
      ceiling = ceiling || w.mover_state(e).on_ceiling;
    }
    EXPECT_FALSE(ceiling);
    ASSERT_TRUE(w.mover_state(e).on_floor);
    EXPECT_GE(gap(w, e, top), skin - 1e-9);
    EXPECT_LE(gap(w, e, top), skin + 1e-5);
    for (int t = 0; t < 120; ++t) play(w, e, 0.0, t == 0 ? 3.0 : 0.0);
    EXPECT_TRUE(w.mover_state(e).on_floor);
    EXPECT_LE(gap(w, e, top), skin + 1e-5);
  }
}

// A jump whose top ends half-way up through a one-way box platform (its foot about 8 cm below
// the top) falls back through it to the ground: a surface it started the tick crossing is not
// met, so it is not lifted onto the platform from inside it.
TEST(Mover, AJumpEndingHalfWayThroughAOneWayBoxFallsBack) {
  World w(WorldDef::empty(Precision::f64, settings()));
  w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}});
  BodyDef p = static_box({0.0, 1.4}, 2.0, 0.1);  // from 1.3 to 1.5 m
  p.shapes[0].one_way = true;
  w.create_body(p);
  const Entity e = w.create_body(mover_def({0.0, foot + skin}));
  play(w, e, 0.0);
  double apex = 0.0;
  for (int t = 0; t < 120; ++t) {
    play(w, e, 0.0, t == 0 ? 5.2 : 0.0);
    apex = std::max(apex, gap(w, e, 0.0));
  }
  EXPECT_GT(apex, 1.35);
  EXPECT_LT(apex, 1.47);
  EXPECT_TRUE(w.mover_state(e).on_floor);
  EXPECT_LE(gap(w, e, 0.0), skin + 1e-5);  // back on the ground
}

/// A world with a mover walking over a step into a crate, and a platform going by.
World busy_world(int threads) {
  World w(WorldDef::empty(Precision::f64, settings(threads)));
  w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}, .friction = 0.4});
  w.create_body(static_box({5.0, 0.1}, 1.0, 0.1));
  BodyDef crate;
  crate.body.mass = 5.0;
  crate.body.position = {8.0, 0.4};
  crate.shapes = {make_box(0.4, 0.4)};
  crate.gravity = Gravity{{0.0, -g}};
  w.create_body(crate);
  MoverDef md;
  md.push_force = 60.0;
  w.create_body(mover_def({0.0, foot + 0.3}, md));
  return w;
}

void play_busy(World& w, int ticks) {
  const Entity e = w.find("mover");
  for (int t = 0; t < ticks; ++t) play(w, e, 3.0, (w.tick() % 70) == 60 ? 5.0 : 0.0);
}

// A snapshot taken mid-run steps on to the same bits; 1 and 2 threads give the same bits; the
// mover's state is in the hash (a restored world with another mover state hashes apart).
TEST(Mover, SnapshotsAndThreadsGiveTheSameBits) {
  World a = busy_world(1);
  play_busy(a, 40);
  WorldSnapshot snap;
  a.save(snap);
  play_busy(a, 200);
  const std::uint64_t end = a.state_hash();
  World b = busy_world(1);
  b.restore(snap);
  play_busy(b, 200);
  EXPECT_EQ(b.state_hash(), end);
  EXPECT_EQ(b.mover_state(b.find("mover")), a.mover_state(a.find("mover")));
  World c = busy_world(2);
  play_busy(c, 240);
  EXPECT_EQ(c.state_hash(), end);
  EXPECT_GT(a.body(a.find("mover")).position.x, 6.0);
}

// Once warm, a tick of the busy world (a mover walking, stepping, jumping and pushing a crate)
// allocates nothing.
TEST(Mover, AWarmTickAllocatesNothing) {
  World w = busy_world(1);
  const Entity e = w.find("mover");
  TickInput in;
  in.bodies.push_back(BodyInput{e, BodyInputKind::velocity, {3.0, 0.0}});
  auto tick = [&] {
    const MoverState s = w.mover_state(e);
    double vy = s.on_floor ? ((w.tick() % 70) == 60 ? 5.0 : 0.0) : s.velocity.y - g * dt;
    in.bodies[0].value = {3.0, vy};
    w.step(in);
  };
  for (int t = 0; t < 240; ++t) tick();
  counted_bytes = 0;
  counting = true;
  for (int t = 0; t < 120; ++t) tick();
  counting = false;
  EXPECT_EQ(counted_bytes.load(), 0u);
}

// tests/scenes/mover_walk.toml, with no rules: the mover walks at 2 m/s over the ground, up the
// step (on its top by 2 s), up the 30° slope, pushes the crate down the 20° one, and ends
// pressing it against the 60° wall; f64 and f32, 1 and 2 threads: the same bits each.
TEST(Mover, TheWalkSceneInBothPrecisions) {
  for (const Precision precision : {Precision::f64, Precision::f32}) {
    std::uint64_t hash = 0;
    for (const int threads : {1, 2}) {
      Scene scene = load_scene(FIXSTEP_SOURCE_DIR "/tests/scenes/mover_walk.toml");
      scene.def.precision = precision;
      scene.def.settings.threads = threads;
      World w(scene.def);
      const Entity hero = w.find("hero"), crate = w.find("crate");
      for (int t = 0; t < 240; ++t) w.step();
      EXPECT_NEAR(w.body(hero).position.y, 0.805 + 0.15, 1e-3);  // on the step
      for (int t = 0; t < 960; ++t) w.step();
      EXPECT_FALSE(w.fault());
      EXPECT_GT(w.body(crate).position.x, 7.5);  // pushed down to the 60° slope
      EXPECT_GT(w.body(hero).position.x, 7.0);
      EXPECT_LT(w.body(hero).position.x, w.body(crate).position.x);
      if (threads == 1) hash = w.state_hash();
      EXPECT_EQ(w.state_hash(), hash);
    }
  }
}

TEST(Mover, DefinitionsRefused) {
  World w(WorldDef::empty(Precision::f64, settings()));
  BodyDef b = mover_def({0.0, 0.0});
  b.type = BodyType::dynamic;
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  b = mover_def({0.0, 0.0});
  b.shapes = {make_box(0.3, 0.8)};
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  b = mover_def({0.0, 0.0}, MoverDef{.step_height = radius});
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  b = mover_def({0.0, 0.0}, MoverDef{.max_floor_angle = 2.0});
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  b = mover_def({0.0, 0.0}, MoverDef{.skin = 0.0});
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  b = mover_def({0.0, 0.0}, MoverDef{.push_force = NAN});
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  const Entity plain = w.create_body(static_box({0.0, -1.0}, 1.0, 1.0));
  EXPECT_THROW((void)w.mover_state(plain), std::invalid_argument);
}

}  // namespace mover_test
}  // namespace fixstep
