// Joints in recordings: a world with jointed bodies whose motor is driven by joint inputs is
// recorded, written, read back to the same Recording and replayed bit for bit; without the
// joint inputs the replay differs; malformed joint words are refused.
#include <gtest/gtest.h>

#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/io/recording_file.hpp"

namespace fixstep {
namespace {

/// A box hinged to the world at its end, its motor driven by the recorded input.
WorldDef flapper() {
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{};
  BodyDef box;
  box.body = Body{.mass = 1.0, .position = {0.5, 0.0}};
  box.gravity = Gravity{{0.0, -9.81}};
  box.shapes = {make_box(0.5, 0.1)};
  const Entity e = def.add_body(box);
  def.joints.push_back({.type = JointType::revolute,
                        .body_b = e,
                        .anchor = {0.0, 0.0},
                        .lower = -1.0,
                        .upper = 1.0,
                        .max_motor_torque = 50.0,
                        .name = "flipper"});
  return def;
}

TEST(JointRecording, JointInputsRoundTripAndReplayBitForBit) {
  const WorldDef def = flapper();
  World sim(def);
  const Joint j = sim.find_joint("flipper");
  Recorder recorder(def, "code-built", 5);
  for (std::uint64_t t = 0; t < 40; ++t) {
    TickInput in{.tick = t};
    if (t % 10 == 3)
      in.joints.push_back({j, JointInputKind::motor_speed, {t % 20 == 3 ? 12.0 : -12.0, 0.0}});
    if (t == 25) in.joints.push_back({j, JointInputKind::enable_motor, {0.0, 0.0}});
    sim.check_input(in);
    sim.step(in);
    recorder.record(in, sim);
  }
  const Recording rec = recorder.finish(sim);
  const std::string text = format_recording(rec);
  EXPECT_NE(text.find(" joint.motor_speed=1:1,12,0"), std::string::npos) << text;
  const Recording back = parse_recording(text, "mem");
  EXPECT_EQ(back, rec);
  EXPECT_TRUE(replay(def, back).ok());
  Recording stripped = back;
  for (TickInput& in : stripped.inputs) in.joints.clear();
  EXPECT_FALSE(replay(def, stripped).ok()) << "the motor's input changes the states";
}

TEST(JointRecording, MalformedJointWordsAreRefused) {
  const std::string good =
      "fixstep-recording 3\nscene s.toml\ndefinition 0000000000000001\n"
      "integrator semi_implicit_euler\nprecision f64\ndt 0.01\nsubsteps 1\nhash_every 60\n"
      "tick 0 push=0,0 held=0 pressed=0 released=0 pointer=0,0 drag=none WORD\n"
      "end 1 0000000000000002\n";
  auto with = [&](const std::string& word) {
    std::string s = good;
    s.replace(s.find("WORD"), 4, word);
    return s;
  };
  const Recording rec = parse_recording(with("joint.target=2:1,0.5,0"), "ok.rec");
  ASSERT_EQ(rec.inputs[0].joints.size(), 1u);
  EXPECT_EQ(rec.inputs[0].joints[0], (JointInput{{2, 1}, JointInputKind::target, {0.5, 0.0}}));
  for (const char* bad : {"joint.spin=1:1,0,0", "joint.target=0:1,0,0", "joint.target=1:1,0",
                          "joint.target=1:1,nan,0", "joint.target=1:1,0,0 impulse=1:1,0,1"}) {
    EXPECT_THROW((void)parse_recording(with(bad), "bad.rec"), RecordingError) << bad;
  }
}

}  // namespace
}  // namespace fixstep
