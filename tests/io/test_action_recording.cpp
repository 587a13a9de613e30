// A game's actions and axes in recordings and input scripts: all 32 action bits and the axes
// written and read back exactly in a recording with rules (fixstep's default buttons only
// without rules); scripts press actions and set axes by the names a program declares, and
// ScriptPlayer::feed plays them into a program's own sampler.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/recording_diff.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/scene/input_script.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {
namespace {

WorldDef action_ball() {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef ball;
  ball.name = "ball";
  ball.body = Body{.mass = 1.0, .position = {0.0, 1.0}};
  def.add_body(ball);
  return def;
}

Recording record(const WorldDef& def, bool with_rules) {
  World sim(def);
  Recorder recorder(def, "code-built", 1);
  if (with_rules) recorder.set_rules("mygame", 2);
  for (std::uint64_t t = 0; t < 6; ++t) {
    TickInput in{.tick = t};
    in.held = t >= 2 ? (1u << 31) | (1u << 12) : 0u;
    in.pressed = t == 2 ? (1u << 31) | (1u << 12) : 0u;
    in.axes = {t * 0.1, 0.0, -1.0 / 3.0, t == 4 ? -0.0 : 1.0};
    sim.step(in);
    recorder.record(in, sim);
  }
  return recorder.finish(sim);
}

TEST(ActionRecording, EveryActionBitAndAxisRoundTripsExactly) {
  const Recording rec = record(action_ball(), true);
  const std::string text = format_recording(rec);
  EXPECT_NE(text.find(" held=80001000 "), std::string::npos) << text;
  EXPECT_NE(text.find(" axis.2=-0.3333333333333333 axis.3=1\n"), std::string::npos) << text;
  const Recording back = parse_recording(text, "mem");
  ASSERT_EQ(back.inputs.size(), rec.inputs.size());
  for (std::size_t i = 0; i < rec.inputs.size(); ++i) {
    EXPECT_EQ(back.inputs[i].held, rec.inputs[i].held);
    for (std::size_t a = 0; a < max_axes; ++a) {
      // -0.0 is not written: it reads back as 0.0, the value InputSampler gives for it.
      EXPECT_EQ(back.inputs[i].axes[a], rec.inputs[i].axes[a]) << i << " " << a;
    }
  }
  EXPECT_TRUE(same_input(back.inputs[3], rec.inputs[3]));
}

TEST(ActionRecording, WithoutRulesOnlyTheDefaultButtons) {
  const std::string text = format_recording(record(action_ball(), false));
  try {
    (void)parse_recording(text, "mem");
    FAIL() << "a recording without rules carrying a game's action bits was read";
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find("bits 80001000 are not buttons"), std::string::npos)
        << e.what();
  }
}

TEST(ActionRecording, TheSamplerKeepsAxesAsLevelsAndReadsMinusZeroAsZero) {
  InputSampler sampler;
  sampler.set_axis(1, -0.0);
  sampler.set_axis(2, 0.75);
  sampler.set_axis(max_axes, 1.0);  // ignored
  const TickInput a = sampler.sample(0), b = sampler.sample(1);
  EXPECT_FALSE(std::signbit(a.axes[1]));
  EXPECT_EQ(a.axes[2], 0.75);
  EXPECT_EQ(b.axes[2], 0.75);  // a level
}

TEST(ActionScript, ActionsAndAxesByTheProgramsNames) {
  const WorldDef def = action_ball();
  const ScriptNames names{{{"jump", 1u << 5}, {"fire", 1u << 30}}, {{"walk", 2}}};
  const InputScript script = parse_input_script(R"([[at]]
tick = 2
press = ["jump", "fire"]
axes = { walk = -0.5 }
[[at]]
tick = 4
release = ["fire"]
axes = { walk = 0.0 }
)",
                                                "s.toml", def.bodies, names);
  ASSERT_EQ(script.events.size(), 2u);
  EXPECT_EQ(script.events[0].press, (1u << 5) | (1u << 30));
  // Played into a program's own sampler (app::run --input), tick by tick.
  ScriptPlayer player(script);
  InputSampler sampler;
  std::vector<TickInput> ticks;
  for (std::uint64_t t = 0; t < 6; ++t) {
    player.feed(t, sampler);
    ticks.push_back(sampler.sample(t));
  }
  EXPECT_EQ(ticks[1].held, 0u);
  EXPECT_EQ(ticks[2].pressed, (1u << 5) | (1u << 30));
  EXPECT_EQ(ticks[3].axes[2], -0.5);
  EXPECT_EQ(ticks[4].released, 1u << 30);
  EXPECT_EQ(ticks[5].held, 1u << 5);
  EXPECT_EQ(ticks[5].axes[2], 0.0);
  // The same script through next() gives the same inputs.
  const std::vector<TickInput> next = script_inputs(script, 6);
  for (std::size_t t = 0; t < 6; ++t) EXPECT_EQ(next[t], ticks[t]) << t;
}

TEST(ActionScript, UnknownNamesAndValuesAreLocated) {
  const WorldDef def = action_ball();
  const ScriptNames names{{{"jump", 1u << 5}}, {{"walk", 0}}};
  auto error = [&](const char* text) {
    try {
      (void)parse_input_script(text, "s.toml", def.bodies, names);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("[[at]]\ntick = 1\npress = [\"jmp\"]"),
            "s.toml:3:10: at[0].press[0]: unknown action \"jmp\"; did you mean \"jump\"? "
            "(valid: jump)");
  EXPECT_EQ(error("[[at]]\ntick = 1\naxes = { walk = 1.5 }"),
            "s.toml:3:17: at[0].axes.walk: must be in [-1, 1] (got 1.5)");
  EXPECT_EQ(error("[[at]]\ntick = 1\naxes = { wlk = 1 }"),
            "s.toml:3:16: at[0].axes.wlk: unknown axis \"wlk\"; did you mean \"walk\"? (valid: "
            "walk)");
}

}  // namespace
}  // namespace fixstep
