// The scene a recording carries (Recording::scene_text, format version 3): any bytes come back
// exactly, through a CRLF conversion too; every cut, edit, oversize claim and bad escape is a
// located error; older versions still read; the damping split is recorded.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/recording_writer.hpp>
#include <string>

#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "text_edit.hpp"

namespace fixstep {
namespace {

using namespace std::string_literals;

WorldDef one_body() {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef a;
  a.body = {1.0, {1.0, 0.0}, {0.0, 0.5}};
  a.spring = SpringDamper{{0.0, 0.0}, 15.0, 0.1, 0.0};
  def.bodies = {a};
  return def;
}

/// A recording of 3 ticks carrying `scene_text`.
Recording recorded(const std::string& scene_text) {
  const WorldDef def = one_body();
  World sim = World(def);
  Recorder rec(def, "s.toml", 1, scene_text);
  for (std::uint64_t t = 0; t < 3; ++t) {
    sim.step(TickInput{.tick = t});
    rec.record(TickInput{.tick = t}, sim);
  }
  return rec.finish(sim);
}

std::string kind_and_message(const std::string& text) {
  try {
    (void)parse_recording(text, "x.rec");
  } catch (const RecordingError& e) {
    return std::string(recording_error_name(e.kind())) + ": " + e.what();
  }
  return "(parsed)";
}

using testing::replaced;

const std::string scene =
    "[world]\ndt = 0.01\n\n[[body]]\nmass = 1.0 # kg\nposition = [1.0, 0.0]\n";

/// FNV-1a, 64-bit, of the bytes of `text` (the reference: offset basis 14695981039346656037,
/// prime 1099511628211; Fowler, Noll, Vo).
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : text) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

TEST(RecordingSceneText, IsWrittenAsLinesAfterTheSceneLine) {
  const std::string text = format_recording(recorded(scene));
  EXPECT_EQ(text.substr(0, text.find("definition ")),
            "fixstep-recording 3\nscene s.toml\nscene_text 66 " + hex_hash(fnv1a(scene)) +
                "\n|[world]\n|dt = 0.01\n|\n|[[body]]\n|mass = 1.0 # kg\n|position = [1.0, 0.0]\n");
  EXPECT_EQ(parse_recording(text, "x.rec").scene_text, scene);
  EXPECT_EQ(scene.size(), 66u);
}

TEST(RecordingSceneText, AnyBytesComeBackExactly) {
  std::string every_byte;
  for (int c = 0; c < 256; ++c) every_byte += static_cast<char>(c);
  const std::string texts[] = {
      scene,
      "no newline at the end",
      "\n",
      "\n\n\n",
      "a\r\nb\r\n",                     // a CRLF scene keeps its \r
      "ends in cr\r",                   // a \r before the end, no newline
      "back\\slash \\r \\x41 |bar|\n",  // what looks like an escape is escaped
      "tab\there\x7f\x01\n",
      "x",
      every_byte,
      every_byte + every_byte + "\n",
  };
  for (const std::string& t : texts) {
    const Recording rec = recorded(t);
    const std::string text = format_recording(rec);
    const Recording back = parse_recording(text, "x.rec");
    EXPECT_EQ(back.scene_text, t);
    EXPECT_EQ(back, rec);
    EXPECT_EQ(format_recording(back), text);
    // Every line of the section but the first starts with '|' and holds no raw control
    // character but the tab.
    std::size_t lines = 0;
    for (std::size_t at = text.find("\n|"); at != std::string::npos;
         at = text.find("\n|", at + 1)) {
      ++lines;
    }
    EXPECT_GE(lines, 1u);
    for (const char c : text) {
      const auto u = static_cast<unsigned char>(c);
      EXPECT_FALSE((u < 0x20 && c != '\n' && c != '\t') || u == 0x7f) << int(u);
    }
  }
}

TEST(RecordingSceneText, ARecordingConvertedToCrlfReadsTheSame) {
  for (const std::string& t : {scene, "a\r\nb\r\n"s, "last line\\"s}) {
    const Recording rec = recorded(t);
    std::string crlf;
    for (const char c : format_recording(rec)) crlf += c == '\n' ? "\r\n"s : std::string(1, c);
    EXPECT_EQ(parse_recording(crlf, "x.rec"), rec);
  }
}

TEST(RecordingSceneText, EveryCutInsideTheSceneIsTruncated) {
  const std::string text = format_recording(recorded(scene));
  const std::size_t from = text.find("scene_text"), to = text.find("definition");
  for (std::size_t n = from; n < to; ++n) {
    const std::string e = kind_and_message(text.substr(0, n));
    EXPECT_TRUE(e.starts_with("truncated: x.rec:")) << n << " " << e;
  }
  // Whole lines cut: the reader names the section and what it read.
  const std::string e = kind_and_message(text.substr(0, text.find("|[[body]]")));
  EXPECT_EQ(e,
            "truncated: x.rec:6: scene_text: the file ends inside the embedded scene (19 of "
            "its 66 bytes read): the recording was cut short")
      << e;
}

TEST(RecordingSceneText, AnEditedOrDamagedSceneIsCorruptNamingItsLine) {
  const std::string text = format_recording(recorded(scene));
  // One byte changed: the checksum, located at the section's last line.
  std::string e = kind_and_message(replaced(text, "|mass = 1.0", "|mass = 2.0"));
  EXPECT_TRUE(
      e.starts_with("corrupt: x.rec:9: scene_text: the embedded scene's bytes do not "
                    "match its checksum"))
      << e;
  // A line dropped: the next header line is not a scene line.
  e = kind_and_message(replaced(text, "|\n|[[body]]\n", "|[[body]]\n"));
  EXPECT_TRUE(
      e.starts_with("corrupt: x.rec:9: scene_text: expected a line of the embedded scene "
                    "(`|` and the line), found \"definition"))
      << e;
  // A line added: more bytes than the header gives.
  e = kind_and_message(replaced(text, "|[[body]]\n", "|[[body]]\n|extra = 1\n"));
  EXPECT_TRUE(
      e.starts_with("corrupt: x.rec:10: scene_text: the embedded scene's lines hold more "
                    "than its 66 bytes"))
      << e;
  e = kind_and_message(replaced(text, "|dt = 0.01", "|dt = \\q.01"));
  EXPECT_EQ(e,
            "corrupt: x.rec:5: scene_text: an unknown escape at column 7 (the embedded scene "
            "has \\\\, \\r and \\xHH only)");
  e = kind_and_message(replaced(text, "|dt = 0.01", "|dt = \\x0"));
  EXPECT_TRUE(e.starts_with("corrupt: x.rec:5: scene_text: an unknown escape")) << e;
  e = kind_and_message(replaced(text, "|dt = 0.01", "|dt = \x01.01"));
  EXPECT_TRUE(
      e.starts_with("corrupt: x.rec:5: scene_text: a control character (byte 0x01) at "
                    "column 7"))
      << e;
  e = kind_and_message(replaced(text, "scene_text 66 ", "scene_text 0 "));
  EXPECT_TRUE(e.starts_with("corrupt: x.rec:3: scene_text: an embedded scene of 0 bytes")) << e;
  e = kind_and_message(replaced(text, "scene_text 66 ", "scene_text 66x "));
  EXPECT_TRUE(e.starts_with("corrupt: x.rec:3: scene_text: expected an integer")) << e;
}

TEST(RecordingSceneText, IsBoundedByTheSceneSizeLimit) {
  const std::string text = format_recording(recorded(scene));
  const std::string e = kind_and_message(replaced(text, "scene_text 66 ", "scene_text 4194305 "));
  EXPECT_TRUE(
      e.starts_with("corrupt: x.rec:3: scene_text: an embedded scene of 4194305 bytes; a "
                    "scene may have at most 4194304 bytes (the scene size limit)"))
      << e;
  EXPECT_TRUE(
      kind_and_message(replaced(text, "scene_text 66 ", "scene_text 99999999999999999999999 "))
          .starts_with("corrupt: x.rec:3: scene_text: expected an integer"));
  // At the limit a scene is carried; past it the recorder refuses it before the first tick.
  const std::string largest(max_recording_scene_bytes, 'x');
  EXPECT_EQ(parse_recording(format_recording(recorded(largest)), "x.rec").scene_text, largest);
  EXPECT_THROW(Recorder(one_body(), "s.toml", 1, largest + "x"), std::invalid_argument);
  Recording too_large = recorded(scene);
  too_large.scene_text = largest + "x";
  EXPECT_THROW((void)format_recording(too_large), std::invalid_argument);
}

TEST(RecordingSceneText, OlderVersionsReadWithoutAScene) {
  std::string v2 = format_recording(recorded(""));
  EXPECT_EQ(v2.find("scene_text"), std::string::npos);  // no text: no section
  v2 = replaced(replaced(v2, "fixstep-recording 3", "fixstep-recording 2"),
                "damping_split per_stage\n", "");
  const Recording rec = parse_recording(v2, "x.rec");
  EXPECT_EQ(rec.version, 2);
  EXPECT_TRUE(rec.scene_text.empty());
  EXPECT_FALSE(rec.settings.damping_split);  // the scene's own applies
  // The version 3 lines are not read in a version 2 file.
  const std::string with_scene =
      replaced(format_recording(recorded(scene)), "fixstep-recording 3", "fixstep-recording 2");
  EXPECT_TRUE(kind_and_message(with_scene)
                  .starts_with("corrupt: x.rec:3: definition: expected the "
                               "`definition` line, found \"scene_text 66"))
      << kind_and_message(with_scene);
}

TEST(RecordingSceneText, TheDampingSplitIsRecordedAndApplied) {
  WorldDef def = one_body();
  def.settings.damping_split = DampingSplit::per_step;
  Recorder recorder(def, "s.toml", 1, scene);
  World sim = World(def);
  const Recording rec = recorder.finish(sim);
  EXPECT_EQ(rec.settings.damping_split, DampingSplit::per_step);
  const Recording back = parse_recording(format_recording(rec), "x.rec");
  EXPECT_EQ(back.settings.damping_split, DampingSplit::per_step);
  WorldDef replayed = one_body();  // the scene's default: per_stage
  apply_settings(replayed, back.settings);
  EXPECT_EQ(definition_hash(replayed), rec.definition_hash);
  // The streaming writer writes the same header.
  const auto file = std::filesystem::temp_directory_path() /
                    ("fixstep_scene_text_" + std::to_string(::getpid()) + ".rec");
  RecordingWriter writer(def, "s.toml", 1, file, scene);
  writer.finish(sim);
  EXPECT_EQ(read_recording(file), rec);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace fixstep
