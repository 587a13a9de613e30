// Per-body input in recordings: written, read back, replayed bit for bit; version 1's drag
// index; the angular kinds (torque=, angular_impulse=, angular_velocity=, target_angle=)
// written and read back as data.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/recording_file.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

using test::ball;

TEST(BodyInputRecording, PerBodyInputsRoundTripAndReplayBitForBit) {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef k = ball("paddle", {0, -1});
  k.type = BodyType::kinematic;
  def.bodies = {ball("ship", {0, 0}), k};
  World sim = World(def);
  Recorder recorder(def, "code-built", 5);
  for (std::uint64_t t = 0; t < 30; ++t) {
    TickInput in{.tick = t};
    if (t % 7 == 1)
      in.bodies.push_back({fixstep::defined_entity(0), BodyInputKind::impulse, {0.1, 1.0 / 3}});
    if (t >= 10 && t < 14)
      in.bodies.push_back({fixstep::defined_entity(0), BodyInputKind::force, {0, 4}});
    if (t == 12)
      in.bodies.push_back({fixstep::defined_entity(1), BodyInputKind::velocity, {1.5, 0}});
    sim.step(in);
    recorder.record(in, sim);
  }
  const Recording rec = recorder.finish(sim);
  const Recording back = parse_recording(format_recording(rec), "mem");
  EXPECT_EQ(back, rec);
  EXPECT_TRUE(replay(def, back).ok());
  // Without the impulses the replay diverges at the first stored hash after tick 1.
  Recording stripped = back;
  for (TickInput& in : stripped.inputs) in.bodies.clear();
  const ReplayReport r = replay(def, stripped);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.mismatch->tick, 5u);
}

TEST(BodyInputRecording, AVersion1DragIndexReadsAsTheBodysInitialHandle) {
  const std::string v1 =
      "fixstep-recording 1\nscene s.toml\ndefinition 0000000000000001\n"
      "integrator semi_implicit_euler\nprecision f64\ndt 0.01\nsubsteps 1\nhash_every 60\n"
      "tick 0 push=0,0 held=100 pressed=100 released=0 pointer=1,2 drag=3\n"
      "end 1 0000000000000002\n";
  const Recording rec = parse_recording(v1, "v1.rec");
  ASSERT_EQ(rec.inputs.size(), 1u);
  EXPECT_EQ(rec.inputs[0].drag_body, fixstep::defined_entity(3));
  // Per-body words belong to version 2 only.
  std::string extra = v1;
  extra.replace(extra.find("drag=3"), 6, "drag=3 impulse=1:1,0,1");
  EXPECT_THROW((void)parse_recording(extra, "v1.rec"), RecordingError);
  std::string v2 = extra;
  v2.replace(v2.find("recording 1"), 11, "recording 2");
  v2.replace(v2.find("drag=3"), 6, "drag=4:1");
  const Recording rec2 = parse_recording(v2, "v2.rec");
  ASSERT_EQ(rec2.inputs[0].bodies.size(), 1u);
  EXPECT_EQ(rec2.inputs[0].bodies[0], (BodyInput{{1, 1}, BodyInputKind::impulse, {0, 1}}));
  EXPECT_EQ(rec2.inputs[0].drag_body, (Entity{4, 1}));
  for (const char* bad :
       {"impulse=0:1,0,1", "impulse=1:1,0", "kick=1:1,0,1", "impulse=1:1,0,inf"}) {
    std::string b = v2;
    b.replace(b.find("impulse=1:1,0,1"), 15, bad);
    EXPECT_THROW((void)parse_recording(b, "v2.rec"), RecordingError) << bad;
  }
}

/// The tick 0 line of a recording holding one per-body input `word`.
std::string angular_word_recording(std::string_view word) {
  return fmt::format(
      "fixstep-recording 3\nscene s.toml\ndefinition 0000000000000001\n"
      "integrator semi_implicit_euler\nprecision f64\ndt 0.01\nsubsteps 1\nhash_every 60\n"
      "tick 0 push=0,0 held=0 pressed=0 released=0 pointer=0,0 drag=none {}\n"
      "end 1 0000000000000002\n",
      word);
}

// Each angular kind is written as its body_input_kind_name with X,Y as recorded and reads back
// equal (its bits too: -0.0 and an inexact third); the text of a recording is the same after a
// read and a write.
TEST(BodyInputRecording, AngularKindsRoundTripThroughTheText) {
  WorldDef def;
  def.settings.dt = 0.01;
  def.bodies = {ball("wheel", {0, 0}), ball("flipper", {2, 0})};
  World sim = World(def);
  Recorder recorder(def, "code-built", 5);
  for (std::uint64_t t = 0; t < 6; ++t) {
    sim.step(TickInput{.tick = t});
    recorder.record(TickInput{.tick = t}, sim);
  }
  Recording rec = recorder.finish(sim);
  rec.inputs.resize(1);
  rec.inputs.push_back({.tick = 2});
  rec.inputs.back().bodies = {{{1, 1}, BodyInputKind::torque, {5.0, 0.0}},
                              {{1, 1}, BodyInputKind::angular_impulse, {-1.0 / 3, 0.0}},
                              {{2, 1}, BodyInputKind::angular_velocity, {-0.0, 0.0}},
                              {{2, 1}, BodyInputKind::target_angle, {1.5707963267948966, 0.0}},
                              {{1, 1}, BodyInputKind::impulse, {0.5, 1.0}}};
  rec.inputs.push_back({.tick = 3});
  const std::string text = format_recording(rec);
  EXPECT_NE(text.find(" drag=none torque=1:1,5,0 angular_impulse=1:1,-0.3333333333333333,0 "
                      "angular_velocity=2:1,-0,0 target_angle=2:1,1.5707963267948966,0 "
                      "impulse=1:1,0.5,1\n"),
            std::string::npos)
      << text;
  const Recording back = parse_recording(text, "mem");
  EXPECT_EQ(back, rec);
  EXPECT_TRUE(std::signbit(back.inputs[1].bodies[2].value.x));
  EXPECT_EQ(format_recording(back), text);
  for (int k = 0; k <= static_cast<int>(last_body_input_kind); ++k) {
    const auto kind = static_cast<BodyInputKind>(k);
    const Recording one = parse_recording(
        angular_word_recording(fmt::format("{}=2:3,0.25,0", body_input_kind_name(kind))), "k");
    ASSERT_EQ(one.inputs[0].bodies.size(), 1u) << k;
    EXPECT_EQ(one.inputs[0].bodies[0], (BodyInput{{2, 3}, kind, {0.25, 0.0}})) << k;
  }
}

// An unknown kind names every kind the reader knows; an angular word is a KIND=SLOT:GEN,X,Y like
// the others (a lone value is refused).
TEST(BodyInputRecording, AWrongAngularWordIsACorruptRecording) {
  auto error = [](std::string_view word) -> std::string {
    try {
      (void)parse_recording(angular_word_recording(word), "bad.rec");
    } catch (const RecordingError& e) {
      EXPECT_EQ(e.kind(), RecordingError::Kind::corrupt) << word;
      return e.what();
    }
    return "(parsed)";
  };
  EXPECT_EQ(error("torq=1:1,5,0"),
            "bad.rec:9: tick: expected force=, impulse=, velocity=, torque=, angular_impulse=, "
            "angular_velocity= or target_angle=, found \"torq=1:1,5,0\"");
  EXPECT_EQ(error("torque=1:1,5"), "bad.rec:9: torque: expected X,Y, found \"5\"");
  EXPECT_EQ(error("target_angle=0:1,1,0"),
            "bad.rec:9: target_angle: slot and generation must be >= 1 (0:1)");
  EXPECT_EQ(error("angular_velocity=1:1,nan,0").find("bad.rec:9: angular_velocity: "), 0u);
}

}  // namespace
}  // namespace fixstep
