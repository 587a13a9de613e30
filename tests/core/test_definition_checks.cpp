// The checks World(def) makes on a WorldDef before building it (definition_checks.hpp): the
// stability guard's warnings, the overlap of discs at tick 0.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

using test::ball;

TEST(GuardWarnings, CheckStabilityReturnsANearLimitWarningWhereAProgramCanReadIt) {
  // Semi-implicit Euler is stable for ω dt < 2; ω dt = 1.9 is within 10 % of the bound.
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef b = ball("spring", {1, 0});
  const double omega = 1.9 / def.settings.dt;
  b.spring = SpringDamper{.stiffness = omega * omega};
  def.bodies.push_back(b);
  EXPECT_EQ(check_definition(def).size(), 1u);
  const World near(def);  // built, its finding kept where a program reads its warnings
  ASSERT_EQ(near.warnings().size(), 1u);
  EXPECT_EQ(near.warnings()[0].verdict, Stability::near_limit);
  def.bodies[0].spring->stiffness = 1.0;
  EXPECT_TRUE(check_definition(def).empty());
  EXPECT_TRUE(World(def).warnings().empty());
}

TEST(DefinitionChecks, WorldRefusesDiscsThatOverlapAtTickZero) {
  WorldDef def;
  def.settings.contacts = ContactSettings{};
  BodyDef left;
  left.name = "left";
  left.collider = Collider{.radius = 1.0};
  BodyDef right = left;
  right.name = "right";
  right.body.position = {1.5, 0.0};  // 0.5 m into the left disc
  (void)def.add_body(left);
  (void)def.add_body(right);
  try {
    (void)World(def);  // World(def) makes the checks (check_definition)
    FAIL() << "overlapping discs accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 'left' and body 'right' overlap by 0.5 m at tick 0"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(check_overlaps(def), std::invalid_argument);
  EXPECT_THROW((void)check_definition(def), std::invalid_argument);
  def.settings.contacts.reset();  // discs that never meet may start anywhere
  EXPECT_NO_THROW(check_overlaps(def));
  EXPECT_TRUE(check_definition(def).empty());
  EXPECT_EQ(World(def).body_count(), 2u);
}

}  // namespace
}  // namespace fixstep
