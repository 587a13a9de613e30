// The rules a recording needs (Recording::rules_name, rules_version; format version 4): written
// and read back, absent from recordings of physics alone (still version 3, byte for byte as
// before), validated by the recorder and the reader, and refused by a physics-only replay.
#include <gtest/gtest.h>

#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/recording_file.hpp"

// A named namespace: this file shares a unity build with the other recording tests.
namespace recording_rules_test {

using namespace fixstep;

Recording three_ticks(const std::string& rules, std::uint32_t version) {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef ball;
  ball.body = {.mass = 1.0, .position = {0.0, 2.0}, .velocity = {}};
  ball.gravity = Gravity{};
  def.add_body(ball);
  World world(def);
  Recorder recorder(def, "level.toml", 1);
  if (!rules.empty()) recorder.set_rules(rules, version);
  for (std::uint64_t t = 0; t < 3; ++t) {
    world.step(TickInput{.tick = t});
    recorder.record(TickInput{.tick = t}, world);
  }
  return recorder.finish(world);
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_recording(text, "x.rec");
  } catch (const RecordingError& e) {
    return std::string(recording_error_name(e.kind())) + ": " + e.what();
  }
  return "(parsed)";
}

TEST(RecordingRules, AreWrittenAsVersion4AndReadBack) {
  const Recording rec = three_ticks("peggle-like_2.0", 3);
  const std::string text = format_recording(rec);
  EXPECT_TRUE(text.starts_with("fixstep-recording 4\n")) << text;
  EXPECT_NE(text.find("\nhash_every 1\nrules peggle-like_2.0 3\ntick 0 "), std::string::npos)
      << text;
  const Recording back = parse_recording(text, "x.rec");
  EXPECT_EQ(back.rules_name, "peggle-like_2.0");
  EXPECT_EQ(back.rules_version, 3u);
  EXPECT_EQ(back, rec);
}

TEST(RecordingRules, ARecordingOfPhysicsAloneIsVersion3WithNoRulesLine) {
  const std::string text = format_recording(three_ticks("", 0));
  EXPECT_TRUE(text.starts_with("fixstep-recording 3\n")) << text;
  EXPECT_EQ(text.find("rules"), std::string::npos) << text;
  EXPECT_NO_THROW(check_physics_only(parse_recording(text, "x.rec"), "x.rec"));
}

TEST(RecordingRules, TheRecorderAndTheReaderRefuseABadNameOrVersion) {
  WorldDef def;
  BodyDef body;
  body.body.mass = 1.0;
  def.add_body(body);
  Recorder recorder(def, "s.toml", 1);
  EXPECT_THROW(recorder.set_rules("", 1), std::invalid_argument);
  EXPECT_THROW(recorder.set_rules("two words", 1), std::invalid_argument);
  EXPECT_THROW(recorder.set_rules(std::string(max_rules_name_bytes + 1, 'a'), 1),
               std::invalid_argument);
  EXPECT_THROW(recorder.set_rules("game", 0), std::invalid_argument);
  EXPECT_NO_THROW(recorder.set_rules(std::string(max_rules_name_bytes, 'a'), 1));

  const std::string good = format_recording(three_ticks("game", 1));
  auto with_rules_line = [&](const std::string& line) {
    std::string t = good;
    t.replace(t.find("rules game 1\n"), 13, line);
    return t;
  };
  EXPECT_EQ(error_of(with_rules_line("rules game\n")),
            "corrupt: x.rec:10: rules: expected `rules NAME VERSION`");
  EXPECT_EQ(error_of(with_rules_line("rules ga/me 1\n")),
            "corrupt: x.rec:10: rules: the name holds byte 0x2f; use letters, digits, '.', '_' "
            "and '-'");
  EXPECT_EQ(error_of(with_rules_line("rules game 0\n")),
            "corrupt: x.rec:10: rules: the version must be >= 1");
  // A version 3 file has no rules line: one there is not read as rules.
  std::string v3 = good;
  v3.replace(0, 20, "fixstep-recording 3\n");
  EXPECT_NE(error_of(v3).find("corrupt: x.rec:10: "), std::string::npos) << error_of(v3);
}

TEST(RecordingRules, APhysicsOnlyReplayRefusesARecordingThatNeedsRulesNamingThem) {
  const Recording rec = three_ticks("slingshot", 2);
  try {
    check_physics_only(rec, "shot.rec");
    ADD_FAILURE() << "a rules recording passed check_physics_only";
  } catch (const RecordingError& e) {
    EXPECT_EQ(e.kind(), RecordingError::Kind::needs_rules);
    EXPECT_EQ(std::string(e.what()),
              "shot.rec: rules: recorded by slingshot with its game rules (version 2); physics "
              "alone would step another game: replay it with that program's --replay shot.rec");
  }
}

}  // namespace recording_rules_test
