// Classifying an output path and opening a stream target (output_target.hpp).
#include "fixstep/io/output_target.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <charconv>
#include <stdexcept>
#include <string_view>

#include "fixstep/io/file_read.hpp"

namespace fixstep {

namespace {

constexpr int max_link_hops = 40;  // Linux's own limit (MAXSYMLINKS, path_resolution(7))

std::atomic<int> standard_output{1};

OutputTarget target(OutputKind kind, std::filesystem::path path, std::string what) {
  OutputTarget t;
  t.kind = kind;
  t.path = std::move(path);
  t.what = std::move(what);
  return t;
}

/// N for "/dev/fd/N", "/proc/self/fd/N", "/proc/thread-self/fd/N" and "/proc/PID/fd/N" with
/// this process's PID; 0, 1, 2 for "/dev/stdin", "/dev/stdout", "/dev/stderr".
std::optional<int> descriptor_named(std::string_view name) {
  if (name == "/dev/stdin") return 0;
  if (name == "/dev/stdout") return 1;
  if (name == "/dev/stderr") return 2;
  const std::string own = fmt::format("/proc/{}/fd/", ::getpid());
  const std::array<std::string_view, 4> prefixes = {"/dev/fd/", "/proc/self/fd/",
                                                    "/proc/thread-self/fd/", own};
  for (const std::string_view prefix : prefixes) {
    if (!name.starts_with(prefix)) continue;
    const std::string_view digits = name.substr(prefix.size());
    int fd = -1;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), fd);
    if (!digits.empty() && ec == std::errc() && end == digits.data() + digits.size() && fd >= 0) {
      return fd;
    }
  }
  return std::nullopt;
}

OutputTarget descriptor_target(int fd) {
  static constexpr std::array<const char*, 3> standard = {"standard input", "standard output",
                                                          "standard error"};
  const std::string what = fd <= 2 ? standard[fd] : fmt::format("descriptor {}", fd);
  OutputTarget t = target(OutputKind::stream, {}, what);
  t.fd = fd == 1 ? standard_output_descriptor() : fd;
  return t;
}

/// The target of an existing file that is not a symbolic link.
OutputTarget existing_target(const std::filesystem::path& path, const struct stat& st) {
  const std::string what = file_type_of(path);
  if (S_ISREG(st.st_mode)) {
    OutputTarget t = target(OutputKind::file, path, what);
    t.mode = st.st_mode & 07777;
    return t;
  }
  const bool stream = S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode);
  return target(stream ? OutputKind::stream : OutputKind::refused, path,
                what.empty() ? "a special file" : what);
}

}  // namespace

OutputTarget classify_output(const std::filesystem::path& given) {
  if (given == "-") return descriptor_target(1);
  std::filesystem::path path = given;
  for (int hop = 0;; ++hop) {
    if (const auto fd = descriptor_named(path.native())) return descriptor_target(*fd);
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) {
      return target(OutputKind::file, path, "a new file");
    }
    if (!S_ISLNK(st.st_mode)) return existing_target(path, st);
    std::error_code ec;
    const std::filesystem::path next = std::filesystem::read_symlink(path, ec);
    if (ec) return target(OutputKind::file, path, "a new file");
    if (hop == max_link_hops) {
      return target(OutputKind::refused, given, "a loop of symbolic links");
    }
    path = next.is_absolute() ? next : path.parent_path() / next;
  }
}

std::string output_refusal(const OutputTarget& target) {
  if (target.kind != OutputKind::refused) return {};
  return fmt::format(
      "is {} (an output is a regular file, a new name, a FIFO, a character device or standard "
      "output)",
      target.what);
}

int open_output_stream(const OutputTarget& target) {
  if (target.fd >= 0) return ::fcntl(target.fd, F_DUPFD_CLOEXEC, 3);
  return ::open(target.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
}

int standard_output_descriptor() noexcept {
  return standard_output.load(std::memory_order_relaxed);
}

void set_standard_output_descriptor(int fd) noexcept {
  standard_output.store(fd, std::memory_order_relaxed);
}

void check_output_before_run(std::string_view flag, const std::string& path,
                             std::initializer_list<std::string_view> inputs) {
  if (path.empty()) return;
  const OutputTarget target = classify_output(path);
  if (std::string why = output_refusal(target); !why.empty()) {
    throw std::runtime_error(fmt::format("{} {} {}; nothing was run", flag, path, why));
  }
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (target.kind == OutputKind::file && !std::filesystem::is_directory(dir.empty() ? "." : dir)) {
    throw std::runtime_error(fmt::format("{} {}: the directory {} does not exist; nothing was run",
                                         flag, path, dir.string()));
  }
  for (const std::string_view input : inputs) {
    std::error_code ec;
    if (!input.empty() && std::filesystem::equivalent(path, input, ec) && !ec) {
      throw std::runtime_error(fmt::format(
          "{} {} is an input of this run: an output never overwrites an input; nothing was run",
          flag, path));
    }
  }
}

}  // namespace fixstep
