// A state's fields as state_hash() covers them (state_fields) and their first difference
// (first_difference): the fields hash back to World::state_hash() exactly (worlds with rolling
// discs, sleeping islands, a drawn generator, f32), every field changed alone changes the hash and
// is named, and bit patterns are what is compared (one ulp, -0.0 against 0.0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/state_difference.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace {

/// A row of `n` discs falling onto a floor (restitution 0.2, friction 0.4), every other one
/// moving sideways, named d0 .. d(n-1); rolling and sleeping as asked.
WorldDef falling_discs(int n, bool rolling, bool sleep, Precision precision = Precision::f64) {
  WorldDef def;
  def.precision = precision;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{
      .restitution = 0.2, .friction = 0.4, .rolling = rolling, .sleep = sleep, .sleep_time = 0.1};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.4});
  for (int i = 0; i < n; ++i) {
    BodyDef b;
    b.name = "d" + std::to_string(i);
    b.body = Body{.mass = 1.0,
                  .position = {0.25 * i, 0.1 + 0.05 * i},
                  .velocity = {i % 2 == 0 ? 0.3 : 0.0, 0.0}};
    b.collider = Collider{.radius = 0.1};
    b.gravity = Gravity{};
    def.bodies.push_back(b);
  }
  return def;
}

TEST(StateFields, HashBackToTheWorldsStateHash) {
  for (const bool rolling : {false, true}) {
    for (const bool sleep : {false, true}) {
      for (const Precision p : {Precision::f64, Precision::f32}) {
        World w(falling_discs(6, rolling, sleep, p));
        for (int t = 0; t < 90; ++t) {
          w.step();
          if (t == 40) (void)w.random().next_u32();  // the generator enters the hash
          const StateFields f = state_fields(w);
          ASSERT_EQ(state_hash(f), w.state_hash()) << "tick " << w.tick();
          ASSERT_EQ(f.rolling, rolling);
          ASSERT_EQ(f.sleep, sleep);
          ASSERT_EQ(f.random_state.has_value(), t >= 40);
        }
      }
    }
  }
}

TEST(StateFields, SleepingWorldsCountTicksAndIslands) {
  World w(falling_discs(4, false, true));
  bool counted = false, islanded = false;
  for (int t = 0; t < 300; ++t) {
    w.step();
    for (const BodyState& b : state_fields(w).bodies) {
      counted = counted || b.sleep_ticks > 0;
      islanded = islanded || b.island > 0;
    }
  }
  EXPECT_TRUE(counted);
  EXPECT_TRUE(islanded);  // else the island field would go untested below
}

/// Changes one field of body j and checks it is named and changes the hash.
void expect_named(const StateFields& base, std::size_t j, const std::string& field,
                  void (*change)(BodyState&)) {
  StateFields other = base;
  change(other.bodies[j]);
  const auto d = first_difference(base, other);
  ASSERT_TRUE(d.has_value()) << field;
  EXPECT_EQ(d->body, j) << field;
  EXPECT_EQ(d->field, field);
  EXPECT_NE(state_hash(other), state_hash(base)) << field;
}

TEST(FirstDifference, NamesEveryFieldTheHashCovers) {
  World w(falling_discs(5, true, true));
  for (int t = 0; t < 200; ++t) w.step();
  (void)w.random().next_u32();
  const StateFields f = state_fields(w);
  ASSERT_TRUE(f.rolling && f.sleep);
  expect_named(f, 3, "x", [](BodyState& b) { b.x = std::nextafter(b.x, 1e9); });
  expect_named(f, 3, "y", [](BodyState& b) { b.y = std::nextafter(b.y, 1e9); });
  expect_named(f, 3, "vx", [](BodyState& b) { b.vx = std::nextafter(b.vx, 1e9); });
  expect_named(f, 3, "vy", [](BodyState& b) { b.vy = std::nextafter(b.vy, 1e9); });
  expect_named(f, 3, "theta", [](BodyState& b) { b.theta = std::nextafter(b.theta, 1e9); });
  expect_named(f, 3, "omega", [](BodyState& b) { b.omega = std::nextafter(b.omega, 1e9); });
  expect_named(f, 3, "sleep_ticks", [](BodyState& b) { ++b.sleep_ticks; });
  expect_named(f, 3, "island", [](BodyState& b) { ++b.island; });
  StateFields other = f;
  *other.random_state += 1;
  const auto d = first_difference(f, other);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->field, "random");
  EXPECT_EQ(d->body, no_body);
  EXPECT_NE(state_hash(other), state_hash(f));
  other = f;
  other.bodies.pop_back();
  ASSERT_TRUE(first_difference(f, other).has_value());
  EXPECT_EQ(first_difference(f, other)->field, "bodies");
  EXPECT_FALSE(first_difference(f, f).has_value());
}

TEST(FirstDifference, OneUlpOfOneBodysVelocityNamesThatBody) {
  const WorldDef def = falling_discs(6, false, false);
  World ours(def), theirs(def);
  for (int t = 0; t < 20; ++t) ours.step(), theirs.step();
  EXPECT_FALSE(first_difference(state_fields(ours), state_fields(theirs)).has_value());
  const Entity e = theirs.bodies()[4];
  const Body b = theirs.body(e);
  const double nudged = std::nextafter(b.velocity.x, std::numeric_limits<double>::infinity());
  theirs.set_velocity(e, {nudged, b.velocity.y});
  ASSERT_NE(ours.state_hash(), theirs.state_hash());
  const auto d = first_difference(state_fields(ours), state_fields(theirs));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->tick, 20u);
  EXPECT_EQ(d->body, 4u);
  EXPECT_EQ(d->field, "vx");
  EXPECT_EQ(d->theirs, nudged);
  // One ulp apart: the bit patterns of neighbouring doubles of one sign differ by 1.
  EXPECT_EQ(std::max(d->bits_ours, d->bits_theirs) - std::min(d->bits_ours, d->bits_theirs), 1u);
  const std::string text = describe(*d, &ours);
  EXPECT_NE(text.find("body 4 (\"d4\") vx: "), std::string::npos) << text;
  EXPECT_NE(text.find(" m/s (bits 0x"), std::string::npos) << text;
  EXPECT_NE(text.find("at tick 20"), std::string::npos) << text;
}

TEST(FirstDifference, NegativeZeroDiffersFromZero) {
  WorldDef def = falling_discs(2, false, false);
  def.bodies[1].gravity.reset();
  World ours(def), theirs(def);
  const Entity e = theirs.bodies()[1];
  ours.set_velocity(e, {0.0, 0.0});
  theirs.set_velocity(e, {-0.0, 0.0});
  ASSERT_NE(ours.state_hash(), theirs.state_hash());
  const auto d = first_difference(state_fields(ours), state_fields(theirs));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->body, 1u);
  EXPECT_EQ(d->field, "vx");
  EXPECT_EQ(describe(*d),
            "body 1 vx: 0 against -0 m/s (bits 0x0000000000000000 against 0x8000000000000000) at "
            "tick 0");
}

TEST(FirstDifference, F32WorldsShowTheFloatsBits) {
  World ours(falling_discs(3, false, false, Precision::f32));
  World theirs = ours;
  const Entity e = theirs.bodies()[2];
  const Body b = theirs.body(e);
  theirs.set_position(
      e,
      {static_cast<double>(std::nextafter(static_cast<float>(b.position.x), 1e9f)), b.position.y});
  const auto d = first_difference(state_fields(ours), state_fields(theirs));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->field, "x");
  EXPECT_TRUE(d->f32);
  EXPECT_EQ(d->bits_theirs, d->bits_ours + 1);
  EXPECT_LT(d->bits_theirs, std::uint64_t{1} << 32);
}

}  // namespace
}  // namespace fixstep
