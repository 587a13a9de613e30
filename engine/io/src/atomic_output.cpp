// An output written into a temporary file and renamed into place, or streamed
// (atomic_output.hpp).
#include "fixstep/io/atomic_output.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "fixstep/io/write_signals.hpp"

namespace fixstep {

namespace {
std::filesystem::path directory_of(const std::filesystem::path& file) {
  return file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
}
}  // namespace

std::filesystem::path temporary_file_for(const std::filesystem::path& file) {
  return directory_of(file) / fmt::format(".{}.tmp.{}", file.filename().string(), ::getpid());
}

AtomicOutput::AtomicOutput(std::filesystem::path file)
    : file_(std::move(file)), target_(classify_output(file_)) {
  ignore_file_size_signal();
  if (target_.kind == OutputKind::refused) {
    throw std::runtime_error(
        fmt::format("cannot write {}: {}", file_.string(), output_refusal(target_)));
  }
  if (target_.kind == OutputKind::stream) {
    open_stream();
  } else {
    open_temporary();
  }
}

void AtomicOutput::open_temporary() {
  tmp_ = temporary_file_for(target_.path).string();
  // O_NOFOLLOW: a symbolic link planted under the temporary's name is not followed.
  const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd < 0) fail(errno);
  // The replaced file's permission bits (umask does not apply to fchmod); a failure here
  // (a file system without modes) leaves the default ones.
  if (target_.mode) (void)::fchmod(fd, static_cast<mode_t>(*target_.mode));
  out_ = ::fdopen(fd, "wb");
  if (!out_) {
    const int err = errno;
    ::close(fd);
    fail(err);
  }
}

void AtomicOutput::open_stream() {
  const int fd = open_output_stream(target_);
  if (fd < 0) fail(errno);
  out_ = ::fdopen(fd, "wb");
  if (!out_) {
    const int err = errno;
    ::close(fd);
    fail(err);
  }
}

AtomicOutput::~AtomicOutput() {
  if (out_) {
    std::fclose(out_);
    if (!tmp_.empty()) ::unlink(tmp_.c_str());
  }
}

void AtomicOutput::fail(int err) {
  if (out_) std::fclose(out_), out_ = nullptr;
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
  const std::string file = file_.string();
  if (streamed()) {
    if (err == EBADF && target_.fd >= 0) {
      throw std::runtime_error(
          fmt::format("cannot write {}: {} is not open for writing", file, target_.what));
    }
    if (err == EPIPE) {
      throw std::runtime_error(fmt::format("cannot write {}: {} (the reader closed the pipe)", file,
                                           std::strerror(err)));
    }
    throw std::runtime_error(fmt::format("cannot write {}: {}", file, std::strerror(err)));
  }
  const std::filesystem::path dir = directory_of(target_.path);
  std::error_code ec;
  if (err == ENOENT && !std::filesystem::is_directory(dir, ec)) {
    throw std::runtime_error(
        fmt::format("cannot write {}: the directory {} does not exist", file, dir.string()));
  }
  throw std::runtime_error(fmt::format("cannot write {}: {}", file, std::strerror(err)));
}

void AtomicOutput::append(std::string_view text) {
  if (!out_) throw std::logic_error("AtomicOutput::append after commit");
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), out_) != text.size()) fail(errno ? errno : EIO);
  size_ += text.size();
}

void AtomicOutput::commit() {
  if (!out_) throw std::logic_error("AtomicOutput::commit twice");
  errno = 0;
  const bool flushed = std::fflush(out_) == 0 && !std::ferror(out_);
  const int flush_err = errno ? errno : EIO;
  std::FILE* out = std::exchange(out_, nullptr);
  if (std::fclose(out) != 0 || !flushed) fail(flushed ? (errno ? errno : EIO) : flush_err);
  if (!tmp_.empty() && ::rename(tmp_.c_str(), target_.path.c_str()) != 0) fail(errno);
}

}  // namespace fixstep
