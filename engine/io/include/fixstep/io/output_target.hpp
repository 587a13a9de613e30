// What an output path names, decided once when the output is opened: a file that is replaced
// atomically, a stream that is written in place (a pipe, a device, standard output), or
// something no output may be written to (a directory, a disk, a socket).
#pragma once

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace fixstep {

/// How an output is written.
enum class OutputKind {
  /// A regular file, or a name that does not exist yet: written into a temporary file beside
  /// it (".NAME.tmp.PID") that is renamed over it when complete.
  file,
  /// A FIFO, a character device (/dev/null, a terminal), or an open descriptor named as
  /// standard output ("-", "/dev/stdout", "/dev/fd/N", "/proc/self/fd/N"): written to
  /// directly, no temporary and no rename; a reader sees the bytes as they are written.
  stream,
  /// A directory, a block device, a socket, any other special file, or a loop of symbolic
  /// links: never written.
  refused,
};

/// An output path classified (classify_output).
struct OutputTarget {
  OutputKind kind = OutputKind::file;
  /// file: the file to replace, symbolic links followed (the last link's target, which may
  /// not exist yet); stream: the file to open; refused: the file refused. Empty when `fd` is
  /// set.
  std::filesystem::path path;
  /// stream: the open descriptor the path names ("-" and "/dev/stdout": 1, "/dev/stderr": 2,
  /// "/dev/fd/N" and "/proc/self/fd/N": N), or -1 for a file to open.
  int fd = -1;
  /// What the path is, for messages: "a regular file", "a new file", "a FIFO (named pipe)",
  /// "a character device", "standard output", "descriptor 3", "a directory", "a block
  /// device", "a socket", "a loop of symbolic links".
  std::string what;
  /// file: the permission bits (st_mode & 07777) of the file replaced; none for a new file.
  std::optional<unsigned> mode;
};

/// Classifies `path` without opening or creating anything (lstat and readlink only): symbolic
/// links are followed one by one (at most 40), each name checked for the names of open
/// descriptors; the final name decides the kind. A name that cannot be examined (no
/// permission, a missing directory) counts as a new file: creating it reports the reason.
[[nodiscard]] OutputTarget classify_output(const std::filesystem::path& path);

/// "" when `target` may be written; for a refused one why not, e.g. "is a directory (an output
/// is a regular file, a new name, a FIFO, a character device or standard output)".
[[nodiscard]] std::string output_refusal(const OutputTarget& target);

/// Refuses, before anything runs, the output `path` a program was given as `flag` (named in
/// the message): one output_refusal() refuses, a new file in a directory that does not exist,
/// or the same file as one of `inputs` (an output never overwrites an input; empty names are
/// skipped). Throws std::runtime_error "FLAG PATH WHY; nothing was run". An empty `path` (no
/// such output) passes.
void check_output_before_run(std::string_view flag, const std::string& path,
                             std::initializer_list<std::string_view> inputs);

/// Opens a stream target (kind stream) for writing: a new descriptor (O_CLOEXEC) that the
/// caller closes; for a descriptor name, a duplicate of it. Opening a FIFO waits until a
/// process opens it for reading, as every writer of a FIFO does. Returns -1 and sets errno
/// (EBADF: the descriptor named is not open) on failure.
[[nodiscard]] int open_output_stream(const OutputTarget& target);

/// The descriptor that "-", "/dev/stdout", "/dev/fd/1" and "/proc/self/fd/1" name: 1, unless
/// a program moved its standard output aside (set_standard_output_descriptor).
[[nodiscard]] int standard_output_descriptor() noexcept;

/// Makes the names of standard output ("-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1")
/// stand for descriptor `fd` (a duplicate of the original descriptor 1), so that a program
/// whose data goes to standard output can point descriptor 1 elsewhere (its messages to
/// standard error) without changing where the data goes.
void set_standard_output_descriptor(int fd) noexcept;

}  // namespace fixstep
