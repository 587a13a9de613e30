// A body edited and found by a program (world.hpp): find by name against a linear scan through
// creates, destroys, copies and restores; user data kept with its body and out of the state
// hash; set_position and set_velocity one field at a time.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace {

using namespace fixstep;

BodyDef named(std::string name, double x, std::uint64_t user_data = 0) {
  BodyDef d;
  d.name = std::move(name);
  d.body.position = {x, 0.0};
  d.user_data = user_data;
  return d;
}

/// The reference: the first body in bodies() order with that name, by a linear scan.
Entity scan(const World& w, const std::string& name) {
  if (name.empty()) return null_entity;
  for (const Entity e : w.bodies()) {
    if (w.name(e) == name) return e;
  }
  return null_entity;
}

TEST(FindByName, AgreesWithALinearScanThroughCreatesDestroysCopiesAndRestores) {
  // 2000 random edits over 40 names, several bodies sharing a name; every name is asked after
  // every edit, of the world, of a copy and after a restore.
  World w(WorldDef::empty(Precision::f64, WorldSettings{}));
  std::mt19937 rng(7);
  std::vector<Entity> live;
  WorldSnapshot snap;
  const auto check_all = [](const World& world) {
    for (int k = 0; k < 40; ++k) {
      const std::string name = "n" + std::to_string(k);
      ASSERT_EQ(world.find(name), scan(world, name)) << name;
    }
    ASSERT_EQ(world.find(""), null_entity);
  };
  for (int edit = 0; edit < 2000; ++edit) {
    const unsigned r = rng() % 10;
    if (r < 6 || live.empty()) {
      live.push_back(w.create_body(named("n" + std::to_string(rng() % 40), 0.001 * edit)));
    } else if (r < 9) {
      const std::size_t i = rng() % live.size();
      w.destroy(live[i]);
      live.erase(live.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      w.save(snap);
    }
    ASSERT_NO_FATAL_FAILURE(check_all(w));
    if (edit % 250 == 0) {
      const World copy = w;
      ASSERT_NO_FATAL_FAILURE(check_all(copy));
    }
  }
  if (!snap.empty()) {
    w.restore(snap);
    ASSERT_NO_FATAL_FAILURE(check_all(w));
  }
}

TEST(FindByName, ABodyDestroyedAndItsNameReusedIsNeverFound) {
  // The new body takes the freed slot (a new generation) and the same name.
  World w(WorldDef::empty(Precision::f64, WorldSettings{}));
  const Entity old = w.create_body(named("ball", 0.0));
  ASSERT_EQ(w.find("ball"), old);
  w.destroy(old);
  EXPECT_EQ(w.find("ball"), null_entity);
  const Entity fresh = w.create_body(named("ball", 1.0));
  ASSERT_EQ(fresh.slot(), old.slot());
  EXPECT_EQ(w.find("ball"), fresh);
}

TEST(UserData, StaysWithItsBodyAndInSnapshotsButNotInTheStateHash) {
  World w(WorldDef::empty(Precision::f32, WorldSettings{}));
  const Entity a = w.create_body(named("a", 0.0, 11));
  const Entity b = w.create_body(named("b", 1.0, 22));
  const Entity c = w.create_body(named("c", 2.0, 33));
  w.destroy(a);  // c moves into a's place in the arrays: its value must move with it
  EXPECT_EQ(w.user_data(b), 22u);
  EXPECT_EQ(w.user_data(c), 33u);

  const std::uint64_t hash = w.state_hash();
  WorldSnapshot snap;
  w.save(snap);
  w.set_user_data(c, 0xffff'ffff'ffff'ffffull);
  EXPECT_EQ(w.state_hash(), hash);  // a program's value is not physics
  EXPECT_EQ(w.user_data(c), 0xffff'ffff'ffff'ffffull);
  w.restore(snap);
  EXPECT_EQ(w.user_data(c), 33u);
  EXPECT_THROW((void)w.user_data(a), std::invalid_argument);
}

TEST(BodyEdits, SetPositionKeepsVelocityAndMassAndSetVelocityKeepsPosition) {
  World w(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.5}));
  BodyDef d = named("ball", 1.0);
  d.body = {.mass = 2.0, .position = {1.0, 2.0}, .velocity = {3.0, 4.0}};
  const Entity e = w.create_body(d);
  w.set_position(e, {-5.0, 6.0});
  EXPECT_EQ(w.body(e).position.x, -5.0);
  EXPECT_EQ(w.body(e).position.y, 6.0);
  EXPECT_EQ(w.body(e).velocity.x, 3.0);
  EXPECT_EQ(w.body(e).mass, 2.0);
  w.set_velocity(e, {0.25, -0.5});
  EXPECT_EQ(w.body(e).position.x, -5.0);
  // No force: one semi-implicit Euler tick moves it by v dt exactly.
  w.step();
  EXPECT_EQ(w.body(e).position.x, -5.0 + 0.25 * 0.5);
  EXPECT_EQ(w.body(e).position.y, 6.0 - 0.5 * 0.5);
}

TEST(BodyEdits, AKinematicBodyMovesAtTheVelocitySetAndAStaticOneRefusesOne) {
  World w(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.1}));
  BodyDef k = named("bucket", 0.0);
  k.type = BodyType::kinematic;  // no mass given: kinematic bodies need none
  BodyDef s = named("peg", 3.0);
  s.type = BodyType::static_body;
  const Entity bucket = w.create_body(k), peg = w.create_body(s);
  w.set_velocity(bucket, {2.0, 0.0});
  for (int t = 0; t < 10; ++t) w.step();
  EXPECT_NEAR(w.body(bucket).position.x, 2.0, 1e-12);  // 10 ticks of 0.1 s at 2 m/s
  EXPECT_THROW(w.set_velocity(peg, {1.0, 0.0}), std::invalid_argument);
  EXPECT_NO_THROW(w.set_velocity(peg, {0.0, 0.0}));
  EXPECT_NO_THROW(w.set_position(peg, {4.0, 0.0}));
  EXPECT_EQ(w.body(peg).position.x, 4.0);
}

TEST(BodyEdits, NonFiniteOrStaleIsRefusedNamingTheField) {
  World w(WorldDef::empty(Precision::f32, WorldSettings{}));
  const Entity e = w.create_body(named("ball", 0.0));
  try {
    w.set_position(e, {1e300, 0.0});  // not representable in f32
    FAIL();
  } catch (const std::invalid_argument& err) {
    EXPECT_NE(std::string(err.what()).find("position"), std::string::npos) << err.what();
  }
  EXPECT_THROW(w.set_velocity(e, {0.0, std::nan("")}), std::invalid_argument);
  EXPECT_EQ(w.body(e).position.x, 0.0);  // a refused edit changes nothing
  w.destroy(e);
  EXPECT_THROW(w.set_position(e, {0.0, 0.0}), std::invalid_argument);
}

}  // namespace
