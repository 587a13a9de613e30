// Reading a whole regular file with a bound (file_read.hpp).
#include "fixstep/io/file_read.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace fixstep {

namespace {

std::string type_name(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void refuse_type(const std::string& path, mode_t mode) {
  throw FileReadError(FileReadError::Kind::not_regular, path,
                      fmt::format("is {}, not a regular file", type_name(mode)));
}

[[noreturn]] void too_large(const std::string& path, std::size_t max_bytes) {
  throw FileReadError(FileReadError::Kind::too_large, path,
                      fmt::format("is larger than {} bytes", max_bytes));
}

/// Closes the descriptor on every way out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

FileReadError::FileReadError(Kind kind, std::string path, std::string reason)
    : std::runtime_error(fmt::format("{}: {}", path, reason)),
      kind_(kind),
      path_(std::move(path)),
      reason_(std::move(reason)) {}

std::string file_type_of(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return {};
  return type_name(st.st_mode);
}

std::string read_regular_file(const std::filesystem::path& file, std::size_t max_bytes) {
  const std::string path = file.string();
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    const int err = errno;
    const auto kind = err == ENOENT || err == ENOTDIR ? FileReadError::Kind::missing
                                                      : FileReadError::Kind::unreadable;
    throw FileReadError(kind, path, std::strerror(err));
  }
  if (!S_ISREG(st.st_mode)) refuse_type(path, st.st_mode);  // before open: a FIFO would block
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) too_large(path, max_bytes);
  const Descriptor in{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (in.fd < 0) {
    const int err = errno;
    throw FileReadError(FileReadError::Kind::unreadable, path, std::strerror(err));
  }
  if (::fstat(in.fd, &st) != 0) {
    const int err = errno;
    throw FileReadError(FileReadError::Kind::unreadable, path, std::strerror(err));
  }
  if (!S_ISREG(st.st_mode)) refuse_type(path, st.st_mode);  // swapped since the stat
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(in.fd, buf, sizeof buf);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      throw FileReadError(FileReadError::Kind::unreadable, path,
                          fmt::format("read error: {}", std::strerror(err)));
    }
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) too_large(path, max_bytes);
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace fixstep
