// Two recordings compared (compare_recordings, diff_recordings): a world nudged between ticks
// on one side only (a peer's desync: equal inputs, stored hashes that part, that side's hashes
// not reproduced), inputs that differ at one tick (the replay names the body), identical
// recordings, other worlds, rules replayed on each side, inputs compared bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/recording_diff.hpp"
#include "fixstep/core/rules.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace {

/// Five named discs (p0 .. p4) sliding and falling onto a floor.
WorldDef pucks() {
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 0.5, .friction = 0.2};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.2});
  for (int i = 0; i < 5; ++i) {
    BodyDef b;
    b.name = "p" + std::to_string(i);
    b.body = Body{.mass = 1.0, .position = {0.5 * i, 0.5}, .velocity = {0.2 * i, 0.0}};
    b.collider = Collider{.radius = 0.1};
    b.gravity = Gravity{};
    def.bodies.push_back(b);
  }
  return def;
}

struct Session {
  std::optional<std::uint64_t> nudge_at =
      std::nullopt;  ///< body 2's vx one ulp up once the world is here
  std::optional<std::uint64_t> kick_at =
      std::nullopt;  ///< an impulse on body 3 from this tick's input on
  std::uint64_t hash_every = 1;
};

/// 100 ticks of pucks() recorded, every tick pushing a little.
Recording record(const Session& s, const TickRules& rules = {}) {
  const WorldDef def = pucks();
  World w(def);
  Recorder recorder(def, "pucks (built in code)", s.hash_every);
  for (std::uint64_t t = 0; t < 100; ++t) {
    if (s.nudge_at == t) {
      const Entity e = w.bodies()[2];
      const Body b = w.body(e);
      w.set_velocity(e, {std::nextafter(b.velocity.x, 1e9), b.velocity.y});
    }
    TickInput in;
    in.push = {0.0, t % 20 < 10 ? 1.0 : 0.0};
    if (s.kick_at && t >= *s.kick_at) {
      in.bodies.push_back(
          {.body = w.bodies()[3], .kind = BodyInputKind::impulse, .value = {0.01, 0}});
    }
    w.step(in);
    if (rules) rules.after_tick(w, in);
    recorder.record(in, w);
  }
  return recorder.finish(w);
}

TEST(RecordingDiff, APeerNudgedBetweenTicksDivergedInStateNotInputs) {
  const Recording a = record({}), b = record({.nudge_at = 30});
  const RecordingDiff d = diff_recordings(pucks(), a, pucks(), b);
  ASSERT_TRUE(d.world_difference.empty()) << d.world_difference;
  EXPECT_FALSE(d.input_tick.has_value());
  // The nudge came after the hash of tick 30 was stored: the state after 31 ticks differs.
  ASSERT_TRUE(d.hashes.has_value());
  EXPECT_EQ(d.hashes->tick, 31u);
  EXPECT_EQ(d.hashes->last_equal, 30u);
  EXPECT_TRUE(d.hashes->exact());
  ASSERT_TRUE(d.replay.has_value());
  EXPECT_EQ(d.replay->ticks, 31u);
  EXPECT_FALSE(d.replay->state.has_value());  // the inputs are equal: so are the replays
  EXPECT_FALSE(d.replay->a.mismatch.has_value());
  EXPECT_EQ(d.replay->a.verified, 31u);
  ASSERT_TRUE(d.replay->b.mismatch.has_value());
  EXPECT_EQ(d.replay->b.mismatch->tick, 31u);
  EXPECT_EQ(d.replay->b.mismatch->last_match, 30u);
  const auto lines = describe(d, "a.rec", "b.rec");
  EXPECT_EQ(lines.back(),
            "verdict: the recordings' inputs are equal up to tick 31; their stored hashes first "
            "differ at tick 31 (exact); replayed here both step to identical states, and a.rec's "
            "hashes are reproduced here, b.rec's are not from tick 31 on: the state of b.rec's "
            "peer diverged at tick 31, not its inputs");
  // Swapped, A is the one whose peer diverged.
  const RecordingDiff swapped = diff_recordings(pucks(), b, pucks(), a);
  EXPECT_NE(describe(swapped, "b.rec", "a.rec").back().find("the state of b.rec's peer diverged"),
            std::string::npos);
}

TEST(RecordingDiff, HashesEveryTenTicksGiveAWindow) {
  const Recording a = record({.hash_every = 10}), b = record({.nudge_at = 30, .hash_every = 10});
  const RecordingDiff d = compare_recordings(a, b);
  ASSERT_TRUE(d.hashes.has_value());
  EXPECT_EQ(d.hashes->tick, 40u);
  EXPECT_EQ(d.hashes->last_equal, 30u);
  EXPECT_FALSE(d.hashes->exact());
  EXPECT_FALSE(d.replay.has_value());  // compare_recordings replays nothing
}

TEST(RecordingDiff, InputsThatDifferAtTick40NameTheBodyTheyMove) {
  const Recording a = record({}), b = record({.kick_at = 40});
  const RecordingDiff d = diff_recordings(pucks(), a, pucks(), b);
  ASSERT_TRUE(d.input_tick.has_value());
  EXPECT_EQ(*d.input_tick, 40u);
  ASSERT_TRUE(d.hashes.has_value());
  EXPECT_EQ(d.hashes->tick, 41u);
  ASSERT_TRUE(d.replay.has_value());
  ASSERT_TRUE(d.replay->state.has_value());
  EXPECT_EQ(d.replay->state->tick, 41u);
  EXPECT_EQ(d.replay->state->body, 3u);
  EXPECT_EQ(d.replay->state->field, "x");  // semi-implicit Euler moves x by the new v
  EXPECT_NE(d.replay->state_text.find("body 3 (\"p3\") x: "), std::string::npos);
  EXPECT_FALSE(d.replay->a.mismatch.has_value());
  EXPECT_FALSE(d.replay->b.mismatch.has_value());
  EXPECT_NE(describe(d, "a.rec", "b.rec").back().find("the inputs first differ at tick 40"),
            std::string::npos);
}

TEST(RecordingDiff, IdenticalRecordingsReplayToTheEnd) {
  const Recording a = record({});
  const RecordingDiff d = diff_recordings(pucks(), a, pucks(), a);
  EXPECT_TRUE(d.identical());
  EXPECT_EQ(d.hashes_compared, 100u);
  ASSERT_TRUE(d.replay.has_value());
  EXPECT_EQ(d.replay->ticks, 100u);
  EXPECT_EQ(d.replay->a.verified, 100u);
  EXPECT_EQ(describe(d, "a", "b").back(),
            "verdict: identical: equal inputs and stored hashes over 100 ticks");
}

TEST(RecordingDiff, OtherWorldsStopTheComparison) {
  Recording a = record({});
  WorldDef other = pucks();
  other.bodies[0].body.mass = 2.0;
  Recording b = Recorder(other, "other", 1).finish(World(other));
  const RecordingDiff d = compare_recordings(a, b);
  EXPECT_NE(d.world_difference.find("their worlds differ: definition hash"), std::string::npos);
  EXPECT_FALSE(d.identical());
  EXPECT_THROW((void)diff_recordings(pucks(), a, pucks(), b), std::invalid_argument);
  b = a;
  b.rules_name = "game", b.rules_version = 2;
  EXPECT_NE(compare_recordings(a, b).world_difference.find("their rules differ"),
            std::string::npos);
}

TEST(RecordingDiff, EachSideRunsItsOwnRules) {
  // Rules that roll a die every tick and kick body 1 on a six: their state is the world's.
  auto dice = [](World& w, const TickInput&) {
    if (w.random().below(6) == 5) {
      const Entity e = w.bodies()[1];
      w.set_velocity(e, w.body(e).velocity + Vec2{0.0, 0.5});
    }
  };
  TickRules rules;
  rules.after_tick = dice;
  const Recording a = record({}, rules), b = record({}, rules);
  const RecordingDiff with = diff_recordings(pucks(), a, pucks(), b, rules, rules);
  EXPECT_TRUE(with.identical());
  EXPECT_FALSE(with.replay->a.mismatch.has_value());
  const RecordingDiff without = diff_recordings(pucks(), a, pucks(), b);
  ASSERT_TRUE(without.replay.has_value());
  ASSERT_TRUE(without.replay->a.mismatch.has_value());  // the recorded hashes carry the dice
  EXPECT_EQ(without.replay->a.mismatch->tick, 1u);
}

TEST(RecordingDiff, InputsAreComparedBitForBit) {
  TickInput a, b;
  b.push = {-0.0, 0.0};
  EXPECT_TRUE(a == b);  // operator== says equal
  EXPECT_FALSE(same_input(a, b));
  b.push = {};
  b.tick = 7;
  EXPECT_TRUE(same_input(a, b));  // the tick field aside
  b.bodies.push_back({});
  EXPECT_FALSE(same_input(a, b));
}

}  // namespace
}  // namespace fixstep
