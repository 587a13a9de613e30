// read_regular_file (file_read.hpp) and the stale temporaries of killed runs
// (stale_temporaries.hpp): only regular files are read, with a bound; only a dead process's
// temporaries of the files asked about are removed.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fixstep/io/file_read.hpp>
#include <fixstep/io/stale_temporaries.hpp>
#include <fstream>
#include <string>

namespace fixstep {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("fixstep_file_read_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

FileReadError::Kind refusal(const fs::path& file, std::size_t max_bytes) {
  try {
    (void)read_regular_file(file, max_bytes);
  } catch (const FileReadError& e) {
    EXPECT_EQ(e.path(), file.string());
    return e.kind();
  }
  ADD_FAILURE() << file << " was read";
  return FileReadError::Kind::unreadable;
}

TEST(FileRead, ReadsARegularFileWholeAndThroughASymlink) {
  TempDir dir;
  const std::string text(200000, 'x');  // more than one read(2) of 64 KiB
  write(dir.path / "a.toml", text);
  EXPECT_EQ(read_regular_file(dir.path / "a.toml", text.size()), text);
  fs::create_symlink(dir.path / "a.toml", dir.path / "link.toml");
  EXPECT_EQ(read_regular_file(dir.path / "link.toml", text.size()), text);
}

TEST(FileRead, RefusesAFifoWithoutBlocking) {
  TempDir dir;
  const fs::path fifo = dir.path / "f.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(refusal(fifo, 1024), FileReadError::Kind::not_regular);  // a blocking open hangs here
  try {
    (void)read_regular_file(fifo, 1024);
  } catch (const FileReadError& e) {
    EXPECT_EQ(e.reason(), "is a FIFO (named pipe), not a regular file");
  }
  EXPECT_EQ(file_type_of(fifo), "a FIFO (named pipe)");
}

TEST(FileRead, RefusesDevicesAndDirectoriesBeforeReading) {
  TempDir dir;
  EXPECT_EQ(refusal("/dev/zero", 1u << 30), FileReadError::Kind::not_regular);  // never ends
  EXPECT_EQ(refusal("/dev/null", 1024), FileReadError::Kind::not_regular);
  EXPECT_EQ(refusal(dir.path, 1024), FileReadError::Kind::not_regular);
  EXPECT_EQ(file_type_of("/dev/zero"), "a character device");
  EXPECT_EQ(file_type_of(dir.path), "a directory");
}

TEST(FileRead, RefusesAFileOverTheBoundAndNamesMissingOnes) {
  TempDir dir;
  write(dir.path / "big", std::string(1025, 'x'));
  EXPECT_EQ(refusal(dir.path / "big", 1024), FileReadError::Kind::too_large);
  EXPECT_EQ(read_regular_file(dir.path / "big", 1025).size(), 1025u);  // the bound is inclusive
  EXPECT_EQ(refusal(dir.path / "none", 1024), FileReadError::Kind::missing);
  EXPECT_EQ(refusal(dir.path / "none" / "x", 1024), FileReadError::Kind::missing);
}

TEST(StaleTemporaries, ParsesOnlyTheAtomicWritersNames) {
  const auto t = parse_temporary_name(".frames.csv.tmp.4242");
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->target, "frames.csv");
  EXPECT_EQ(t->pid, 4242);
  EXPECT_EQ(parse_temporary_name(".a.tmp.tmp.7")->target, "a.tmp");
  for (const char* other : {"frames.csv.tmp.1", ".tmp.1", ".x.tmp.", ".x.tmp.12a", ".x.tmp.0",
                            ".x.tmp.-3", ".x.tmp.99999999999999999999", "x"}) {
    EXPECT_FALSE(parse_temporary_name(other).has_value()) << other;
  }
}

/// A PID that was a process and has exited (reaped): kill(pid, 0) is ESRCH until reused.
long dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

TEST(StaleTemporaries, RemovesADeadProcesssTemporariesOfOurFilesOnly) {
  TempDir dir;
  const long dead = dead_pid();
  ASSERT_FALSE(process_running(dead));
  ASSERT_TRUE(process_running(::getpid()));
  const auto tmp = [&](const std::string& target, long pid) {
    return dir.path / ("." + target + ".tmp." + std::to_string(pid));
  };
  for (const auto& f : {tmp("out.csv", dead), tmp("out.csv", ::getpid()), tmp("other.csv", dead)})
    write(f, "partial");
  const auto removed =
      remove_stale_temporaries(dir.path, [](std::string_view t) { return t == "out.csv"; });
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0], tmp("out.csv", dead));
  EXPECT_FALSE(fs::exists(tmp("out.csv", dead)));
  EXPECT_TRUE(fs::exists(tmp("out.csv", ::getpid())));  // a running writer's
  EXPECT_TRUE(fs::exists(tmp("other.csv", dead)));      // not a file this run writes
  EXPECT_TRUE(remove_stale_temporaries(dir.path / "missing", [](auto) { return true; }).empty());
}

}  // namespace
}  // namespace fixstep
