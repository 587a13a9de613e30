// Recordings and their messages: CRLF line ends read as LF; control
// characters and NUL in a field or path are printed escaped (printable.hpp), never raw or cut
// short; a scene path with a newline is refused when recording starts, naming the path; a
// recording that names a body the scene does not have is a bad recording before replaying.
#include <gtest/gtest.h>

#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/printable.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fixstep/io/recording_file.hpp"

namespace fixstep {
namespace {

WorldDef two_bodies() {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef a, b;
  a.body = {1.0, {0.0, 0.0}, {0.0, 0.0}};
  b.body = {1.0, {1.0, 0.0}, {0.0, 0.0}};
  def.bodies = {a, b};
  return def;
}

Recording short_run(const WorldDef& def) {
  World sim = World(def);
  Recorder rec(def, "two.toml", 1);
  for (std::uint64_t t = 0; t < 5; ++t) {
    TickInput in{.tick = t};
    in.push = {0.5 * double(t), 0.0};
    sim.step(in);
    rec.record(in, sim);
  }
  return rec.finish(sim);
}

std::string message_of(std::string_view text) {
  try {
    (void)parse_recording(text, "x.rec");
  } catch (const RecordingError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Printable, ControlCharactersAndNulAreEscapedTheRestKept) {
  using namespace std::string_literals;
  EXPECT_EQ(printable("a\nb\rc\td"s), "a\\nb\\rc\\td");
  EXPECT_EQ(printable("x\0y"s), "x\\0y");
  EXPECT_EQ(printable("\x1b[31m\x7f"s), "\\x1b[31m\\x7f");
  EXPECT_EQ(printable("pfad/ä\\b.toml"), "pfad/ä\\b.toml");
}

TEST(RecordingMessages, CrlfLineEndsReadAsTheSameRecording) {
  const Recording rec = short_run(two_bodies());
  const std::string lf = format_recording(rec);
  std::string crlf;
  for (const char c : lf) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(parse_recording(crlf, "crlf.rec"), rec);
  EXPECT_EQ(parse_recording(crlf, "crlf.rec").scene, "two.toml");  // no \r kept in the path
}

TEST(RecordingMessages, ControlCharactersInAFieldArePrintedEscapedNotRawNorCut) {
  using namespace std::string_literals;
  // Before: `found "2` and the message ended at the NUL; a lone \r printed raw.
  std::string e = message_of("fixstep-recording 2\0junk\n"s);
  EXPECT_NE(e.find("found \"2\\0junk\""), std::string::npos) << e;
  e = message_of("fixstep-recording 2\rx\n"s);
  EXPECT_NE(e.find("found \"2\\rx\""), std::string::npos) << e;
  EXPECT_EQ(e.find('\r'), std::string::npos) << e;
  e = message_of("fixstep-recording 2\nscene a\nb\n"s);  // a newline cannot be in a line
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  e = message_of("fixstep-recording 2\nscene a\x01.toml\n"s);
  EXPECT_NE(e.find("the path \"a\\x01.toml\" holds a control character"), std::string::npos) << e;
}

TEST(RecordingMessages, TheRecordingFileNameIsPrintedEscaped) {
  using namespace std::string_literals;
  try {
    (void)parse_recording("nope\n", "bad\nname\0.rec"s);
    FAIL();
  } catch (const RecordingError& e) {
    EXPECT_EQ(std::string_view(e.what()).substr(0, 17), "bad\\nname\\0.rec:1");
  }
}

TEST(RecordingMessages, AScenePathWithANewlineIsRefusedWhenRecordingStartsAndLocated) {
  // Before: the whole run, then "format_recording: the scene path holds a control character".
  try {
    Recorder rec(two_bodies(), "a\nb.toml", 1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string_view(e.what()).find("control character (0x0a at byte 1 of 8)"),
              std::string::npos)
        << e.what();
  }
}

TEST(RecordingMessages, ABodyTheSceneDoesNotHaveIsABadRecording) {
  Recording rec = short_run(two_bodies());
  EXPECT_NO_THROW(check_recorded_bodies(rec, 2, 0, "ok.rec"));
  rec.inputs[1].drag_body = Entity{3, 1};
  try {
    check_recorded_bodies(rec, 2, 0, "edited.rec");
    FAIL();
  } catch (const RecordingError& e) {
    EXPECT_EQ(e.kind(), RecordingError::Kind::corrupt);
    EXPECT_NE(std::string_view(e.what()).find("edited.rec: drag: the tick 1 line names body 3:1"),
              std::string::npos)
        << e.what();
  }
  rec.inputs[1].drag_body = null_entity;
  rec.inputs[1].bodies.push_back({Entity{1, 2}, BodyInputKind::impulse, {1.0, 0.0}});
  EXPECT_THROW(check_recorded_bodies(rec, 2, 0, "edited.rec"), RecordingError);  // a stale handle
  rec.inputs[1].bodies.back().body = Entity{2, 1};
  EXPECT_NO_THROW(check_recorded_bodies(rec, 2, 0, "ok.rec"));
  // An angular input names its kind as the recording spells it.
  rec.inputs[1].bodies.push_back({Entity{3, 1}, BodyInputKind::angular_velocity, {1.0, 0.0}});
  try {
    check_recorded_bodies(rec, 2, 0, "edited.rec");
    FAIL();
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string_view(e.what()).find(
                  "edited.rec: angular_velocity: the tick 1 line names body 3:1"),
              std::string::npos)
        << e.what();
  }  // A joint input names a joint of the scene's (1:1 .. N:1), or the recording is bad.
  rec.inputs[1].bodies.pop_back();
  rec.inputs[1].joints.push_back({Joint{2, 1}, JointInputKind::motor_speed, {1.0, 0.0}});
  EXPECT_NO_THROW(check_recorded_bodies(rec, 2, 2, "ok.rec"));
  for (const Joint bad : {Joint{3, 1}, Joint{1, 2}, Joint{0, 1}}) {
    rec.inputs[1].joints.back().joint = bad;
    try {
      check_recorded_bodies(rec, 2, 2, "edited.rec");
      ADD_FAILURE() << "joint " << bad.index1 << ":" << bad.generation << " accepted";
    } catch (const RecordingError& e) {
      EXPECT_EQ(e.kind(), RecordingError::Kind::corrupt);
      EXPECT_NE(std::string_view(e.what()).find("edited.rec: motor_speed: the tick 1 line names "
                                                "joint"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace fixstep
