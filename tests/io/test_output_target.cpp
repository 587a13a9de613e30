// What an output path names (classify_output) and how AtomicOutput writes each kind: a file
// atomically with its permission bits, through symbolic links; a FIFO or device streamed; a
// directory or socket refused; SIGXFSZ ignored (output_target.hpp, atomic_output.hpp,
// write_signals.hpp). Real devices are only classified, never written: a private node (mknod,
// root only) is written instead.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fixstep/io/atomic_output.hpp>
#include <fixstep/io/output_target.hpp>
#include <fixstep/io/write_signals.hpp>
#include <fstream>
#include <iterator>
#include <string>

namespace fixstep {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path =
      fs::temp_directory_path() / ("fixstep_output_target_" + std::to_string(::getpid()));
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  [[nodiscard]] std::size_t entries() const {
    return std::size_t(std::distance(fs::directory_iterator(path), fs::directory_iterator()));
  }
};

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void write(const fs::path& file, const std::string& text) {
  AtomicOutput out(file);
  out.append(text);
  out.commit();
}

/// The message AtomicOutput's constructor throws for `file`, or "".
std::string refusal(const fs::path& file) {
  try {
    AtomicOutput out(file);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(OutputTarget, ARegularFileIsReplacedAtomicallyKeepingItsMode) {
  const TempDir dir;
  const fs::path file = dir.path / "out.csv";
  std::ofstream(file) << "old";
  ::chmod(file.c_str(), 0640);
  const OutputTarget t = classify_output(file);
  EXPECT_EQ(t.kind, OutputKind::file);
  EXPECT_EQ(t.mode, 0640U);
  {
    AtomicOutput out(file);
    out.append("new");
    EXPECT_FALSE(out.streamed());
    EXPECT_EQ(read(file), "old");  // until commit
    EXPECT_EQ(dir.entries(), 2U);  // and the temporary beside it
    out.commit();
  }
  EXPECT_EQ(read(file), "new");
  EXPECT_EQ(fs::status(file).permissions(), fs::perms(0640));
  EXPECT_EQ(dir.entries(), 1U);
  EXPECT_EQ(classify_output(dir.path / "absent.csv").mode, std::nullopt);
}

TEST(OutputTarget, LinksAreFollowedToTheirFinalTargetAndStayLinks) {
  const TempDir dir;
  std::ofstream(dir.path / "c") << "old";
  fs::create_symlink("c", dir.path / "b");
  fs::create_symlink(dir.path / "b", dir.path / "a");    // absolute, then relative
  fs::create_symlink("sub/new", dir.path / "dangling");  // into a directory that exists
  fs::create_directories(dir.path / "sub");
  EXPECT_EQ(classify_output(dir.path / "a").path, dir.path / "c");
  write(dir.path / "a", "through a chain");
  write(dir.path / "dangling", "made at the target");
  EXPECT_TRUE(fs::is_symlink(dir.path / "a"));
  EXPECT_TRUE(fs::is_symlink(dir.path / "b"));
  EXPECT_TRUE(fs::is_symlink(dir.path / "dangling"));
  EXPECT_EQ(read(dir.path / "c"), "through a chain");
  EXPECT_EQ(read(dir.path / "sub" / "new"), "made at the target");
  fs::create_symlink("loop2", dir.path / "loop1");
  fs::create_symlink("loop1", dir.path / "loop2");
  EXPECT_EQ(classify_output(dir.path / "loop1").kind, OutputKind::refused);
  EXPECT_NE(refusal(dir.path / "loop1").find("is a loop of symbolic links"), std::string::npos);
}

TEST(OutputTarget, DescriptorNamesAreStreamsToTheirDescriptor) {
  EXPECT_EQ(classify_output("-").fd, 1);
  EXPECT_EQ(classify_output("-").what, "standard output");
  EXPECT_EQ(classify_output("/dev/stdout").fd, 1);
  EXPECT_EQ(classify_output("/dev/stderr").fd, 2);
  EXPECT_EQ(classify_output("/dev/fd/5").fd, 5);
  EXPECT_EQ(classify_output("/proc/self/fd/3").fd, 3);
  EXPECT_EQ(classify_output("/proc/" + std::to_string(::getpid()) + "/fd/4").fd, 4);
  EXPECT_EQ(classify_output("/dev/fd/5").kind, OutputKind::stream);
  EXPECT_EQ(classify_output("/dev/fd/x").fd, -1);
  set_standard_output_descriptor(7);  // a program that moved its standard output aside
  EXPECT_EQ(classify_output("-").fd, 7);
  EXPECT_EQ(classify_output("/dev/fd/1").fd, 7);
  set_standard_output_descriptor(1);
  EXPECT_NE(refusal("/dev/fd/999").find("/dev/fd/999: descriptor 999 is not open"),
            std::string::npos);
}

TEST(OutputTarget, AFifoIsStreamedToAndStaysAFifo) {
  const TempDir dir;
  const fs::path fifo = dir.path / "p";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // The reader opens first, without waiting for a writer; the few bytes fit the pipe's
  // buffer, so they are read after the writer has closed.
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  write(fifo, "streamed\n");
  char got[64] = {};
  EXPECT_EQ(::read(reader, got, sizeof got), 9);
  ::close(reader);
  EXPECT_STREQ(got, "streamed\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(dir.entries(), 1U);  // no temporary
}

TEST(OutputTarget, CharacterDevicesAreStreamsAndAFullOneIsAnError) {
  EXPECT_EQ(classify_output("/dev/null").kind, OutputKind::stream);  // classified, not written
  EXPECT_EQ(classify_output("/dev/null").what, "a character device");
  const TempDir dir;
  const fs::path full = dir.path / "full";  // a private /dev/full: every write fails, ENOSPC
  if (::mknod(full.c_str(), S_IFCHR | 0600, makedev(1, 7)) != 0) {
    GTEST_SKIP() << "mknod needs root: " << std::strerror(errno);
  }
  try {
    write(full, std::string(100000, 'x'));
    ADD_FAILURE() << "a write to a full device succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("full: No space left on device"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::is_character_file(full));
  EXPECT_EQ(dir.entries(), 1U);
}

TEST(OutputTarget, DirectoriesAndSocketsAreRefusedAndNothingIsMade) {
  const TempDir dir;
  fs::create_directories(dir.path / "d");
  EXPECT_NE(refusal(dir.path / "d").find("d: is a directory (an output is"), std::string::npos);
  const fs::path sock = dir.path / "s";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, sock.c_str(), sizeof addr.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  EXPECT_NE(refusal(sock).find("s: is a socket"), std::string::npos);
  ::close(fd);
  EXPECT_TRUE(fs::is_socket(sock));
  EXPECT_EQ(dir.entries(), 2U);
}

TEST(OutputTarget, OpeningAnOutputIgnoresTheFileSizeSignalUnlessHandled) {
  std::signal(SIGXFSZ, SIG_DFL);
  const TempDir dir;
  write(dir.path / "a", "x");
  struct sigaction now {};
  ::sigaction(SIGXFSZ, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_IGN);
  const auto handler = +[](int) {};
  std::signal(SIGXFSZ, handler);  // a program's own handler is kept
  ignore_write_signals();
  ::sigaction(SIGXFSZ, nullptr, &now);
  EXPECT_EQ(now.sa_handler, handler);
  ::sigaction(SIGPIPE, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_IGN);
  std::signal(SIGXFSZ, SIG_DFL);
  std::signal(SIGPIPE, SIG_DFL);
}

}  // namespace
}  // namespace fixstep
