// fixstep::Random (random.hpp) against PCG's published check vector and by counting, and the
// World's generator: seeded from WorldSettings::seed, saved and restored with snapshots, in
// the state hash once drawn from, in the definition hash and scene files when set.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_writer.hpp"

// A named namespace: this file shares a unity build with test_snapshot.cpp.
namespace random_test {

using fixstep::Random;

// pcg32-demo (pcg-c-basic) with initstate 42, initseq 54 prints these six values first
// (pcg-random.org, "Using the Basic C Implementation").
TEST(Random, MatchesPcg32sPublishedCheckVector) {
  Random r(42, 54);
  constexpr std::array<std::uint32_t, 6> expected = {0xa15c02b7, 0x7b47f409, 0xba1d3330,
                                                     0x83d2f293, 0xbfa4784b, 0xcbed606e};
  for (const std::uint32_t e : expected) EXPECT_EQ(r.next_u32(), e);
  EXPECT_EQ(r.draws(), 6u);
  static_assert(Random(42, 54).next_u32() == 0xa15c02b7);  // usable at compile time
}

// 600 000 rolls of a die: each face within 4.5 standard deviations of 100 000 (a biased
// modulo of a 32-bit draw would still pass; the check is that below() is uniform and in range).
TEST(Random, BelowAndIntegerAreUniformAndInRange) {
  Random r(7);
  std::array<int, 6> faces{};
  for (int i = 0; i < 600'000; ++i) ++faces.at(r.below(6));
  for (const int count : faces) EXPECT_NEAR(count, 100'000, 4.5 * 288.7);  // sqrt(n p (1-p))
  bool low = false, high = false;
  for (int i = 0; i < 1000; ++i) {
    const std::int64_t v = r.integer(-3, 3);
    ASSERT_GE(v, -3);
    ASSERT_LE(v, 3);
    low = low || v == -3, high = high || v == 3;
  }
  EXPECT_TRUE(low && high) << "both ends of [lo, hi] are drawn";
  EXPECT_EQ(r.below(1), 0u);
  EXPECT_THROW((void)r.below(0), std::invalid_argument);
  EXPECT_THROW((void)r.integer(2, 1), std::invalid_argument);
  EXPECT_THROW((void)r.integer(0, 1ll << 40), std::invalid_argument);
}

TEST(Random, UniformLiesInItsIntervalWithTheRightMean) {
  Random r(9);
  double sum = 0.0;
  for (int i = 0; i < 100'000; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / 100'000, 0.5, 4.5 * 0.2887 / std::sqrt(100'000.0));
  const double v = r.uniform(-2.0, 3.0);
  EXPECT_TRUE(v >= -2.0 && v < 3.0);
  EXPECT_THROW((void)r.uniform(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW((void)r.uniform(0.0, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  EXPECT_THROW((void)r.chance(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_FALSE(r.chance(0.0));
  EXPECT_TRUE(r.chance(1.0));
}

fixstep::World seeded_world(std::uint64_t seed) {
  fixstep::WorldDef def;
  def.settings.seed = seed;
  fixstep::BodyDef body;
  body.body = {.mass = 1.0, .position = {0.0, 1.0}, .velocity = {}};
  def.add_body(body);
  return fixstep::World(def);
}

TEST(WorldRandom, IsSeededFromTheSettingsAndRollsTheSameDiceAfterARestore) {
  fixstep::World world = seeded_world(11);
  EXPECT_EQ(world.random(), Random(11));
  (void)world.random().below(100);
  fixstep::WorldSnapshot snap;
  world.save(snap);
  std::array<std::uint32_t, 5> first{}, again{};
  for (auto& v : first) v = world.random().next_u32();
  world.step();
  world.restore(snap);
  for (auto& v : again) v = world.random().next_u32();
  EXPECT_EQ(first, again);
}

TEST(WorldRandom, EntersTheStateHashOnlyOnceDrawnFrom) {
  fixstep::World a = seeded_world(1), b = seeded_world(2);
  EXPECT_EQ(a.state_hash(), b.state_hash()) << "no draw yet: the bodies' hash alone";
  const std::uint64_t before = a.state_hash();
  (void)a.random().next_u32();
  EXPECT_NE(a.state_hash(), before);
  (void)b.random().next_u32();
  EXPECT_NE(a.state_hash(), b.state_hash()) << "different seeds, different generator states";
  fixstep::World c = seeded_world(1);
  (void)c.random().next_u32();
  EXPECT_EQ(a.state_hash(), c.state_hash());
}

TEST(WorldRandom, TheSeedIsInTheDefinitionHashAndTheSceneFileWhenSet) {
  fixstep::WorldDef def;
  fixstep::BodyDef body;
  body.body.mass = 1.0;
  def.add_body(body);
  const std::uint64_t unseeded = fixstep::definition_hash(def);
  def.settings.seed = 0;
  EXPECT_EQ(fixstep::definition_hash(def), unseeded);
  def.settings.seed = 1234567890123ull;
  EXPECT_NE(fixstep::definition_hash(def), unseeded);
  const std::string text = fixstep::format_scene(def);
  EXPECT_NE(text.find("seed = 1234567890123\n"), std::string::npos) << text;
  EXPECT_EQ(fixstep::parse_scene(text, "seeded.toml").def.settings.seed, 1234567890123ull);
  def.settings.seed = 1ull << 63;  // above TOML's largest integer
  EXPECT_THROW((void)fixstep::format_scene(def), std::invalid_argument);
}

}  // namespace random_test
