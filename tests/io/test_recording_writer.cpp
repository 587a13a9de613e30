// The streaming recorder (RecordingWriter) as the games use it: the rules named in its header as
// Recorder names them, and its bytes on disk while it records, so that its memory stays O(1)
// however long the session (what a game's --record holds).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/atomic_output.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/recording_writer.hpp"

namespace recording_writer_test {
namespace {

using namespace fixstep;

WorldDef one_ball() {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef ball;
  ball.body = {.mass = 1.0, .position = {0.0, 2.0}, .velocity = {}};
  ball.gravity = Gravity{};
  def.add_body(ball);
  return def;
}

/// A pointer that moves every tick: an input line a tick, as a game's (the pointer aims).
TickInput moving(std::uint64_t t) {
  return TickInput{.tick = t, .pointer = {static_cast<double>(t % 1000) * 0.001, 0.0}};
}

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct TempDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("fixstep_writer_" + std::to_string(::getpid()));
  TempDir() { std::filesystem::create_directories(path); }
  ~TempDir() { std::filesystem::remove_all(path); }
};

TEST(RecordingWriter, NamesTheRulesAsTheRecorderDoes) {
  const TempDir dir;
  const WorldDef def = one_ball();
  World world(def);
  Recorder recorder(def, "peggle (built in code)", 1);
  recorder.set_rules("peggle", 2);
  RecordingWriter writer(def, "peggle (built in code)", 1, dir.path / "r.rec");
  writer.set_rules("peggle", 2);
  for (std::uint64_t t = 0; t < 50; ++t) {
    world.step(moving(t));
    recorder.record(moving(t), world);
    writer.record(moving(t), world);
  }
  EXPECT_THROW(writer.set_rules("peggle", 3), std::logic_error);  // the header is written
  const Recording in_memory = recorder.finish(world);
  writer.finish(world);
  const std::string text = slurp(dir.path / "r.rec");
  EXPECT_EQ(text, format_recording(in_memory));
  EXPECT_NE(text.find("\nrules peggle 2\n"), std::string::npos) << text;
}

TEST(RecordingWriter, RefusesABadRulesNameOrVersion) {
  const TempDir dir;
  RecordingWriter writer(one_ball(), "s.toml", 1, dir.path / "r.rec");
  EXPECT_THROW(writer.set_rules("a b", 1), std::invalid_argument);
  EXPECT_THROW(writer.set_rules("", 1), std::invalid_argument);
  EXPECT_THROW(writer.set_rules("peggle", 0), std::invalid_argument);
}

// The cause of a game's memory growing with its --record (a Recorder holds every tick's input
// and hash): the writer's bytes go to its temporary file as it records, and what it holds back
// stays under a fixed bound whatever the length.
TEST(RecordingWriter, HoldsABoundedBufferAndStreamsTheRestToItsTemporaryFile) {
  const TempDir dir;
  const WorldDef def = one_ball();
  World world(def);
  const std::filesystem::path file = dir.path / "long.rec";
  RecordingWriter writer(def, "s.toml", 1, file);
  constexpr std::uint64_t held_at_most = std::uint64_t{1} << 17;  // twice its flush size
  std::uint64_t most_held = 0;
  for (std::uint64_t t = 0; t < 40000; ++t) {
    world.step(moving(t));
    writer.record(moving(t), world);
    if (t % 1000 == 999) {
      std::error_code ec;
      const std::uint64_t on_disk = std::filesystem::file_size(temporary_file_for(file), ec);
      ASSERT_FALSE(ec) << "no temporary file at tick " << t;
      most_held = std::max(most_held, writer.bytes() - on_disk);
    }
  }
  EXPECT_GT(writer.bytes(), 20 * held_at_most);  // a long recording: megabytes
  EXPECT_LE(most_held, held_at_most);
  EXPECT_FALSE(std::filesystem::exists(file));  // its name only once finished
  writer.finish(world);
  EXPECT_TRUE(replay(def, parse_recording(slurp(file), "long.rec")).ok());
}

}  // namespace
}  // namespace recording_writer_test
