// Reading a whole input file (scene, input script, recording) safely: only a regular file, never
// more than a bound, never blocking on a FIFO or reading a device without end.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fixstep {

/// Why read_regular_file refused or failed. what() is "PATH: REASON"; the readers of scenes and
/// recordings turn it into their own error types (SceneError, RecordingError).
class FileReadError : public std::runtime_error {
 public:
  enum class Kind {
    missing,      ///< no such file (stat: ENOENT or ENOTDIR)
    not_regular,  ///< a directory, FIFO, device or socket: reason() says which
    too_large,    ///< larger than the bound given (by its size, or by what a read returned)
    unreadable,   ///< open or read failed for another reason: reason() is the system's
  };
  FileReadError(Kind kind, std::string path, std::string reason);
  [[nodiscard]] Kind kind() const { return kind_; }
  [[nodiscard]] const std::string& path() const { return path_; }
  /// E.g. "is a FIFO (named pipe), not a regular file", "Permission denied".
  [[nodiscard]] const std::string& reason() const { return reason_; }

 private:
  Kind kind_;
  std::string path_;
  std::string reason_;
};

/// What `file` is, for a message: "a regular file", "a directory", "a FIFO (named pipe)",
/// "a character device", "a block device", "a socket"; "" when it cannot be stat()ed.
/// Follows symbolic links, as opening does.
[[nodiscard]] std::string file_type_of(const std::filesystem::path& file);

/// The whole contents of the regular file `file` (a symbolic link to one is followed), at most
/// `max_bytes` bytes. Anything else is refused before it is opened: opening a FIFO for reading
/// blocks until a writer comes, and a device such as /dev/zero never ends. A file whose size is
/// over `max_bytes` is refused before it is read; one that grows past it while read is refused
/// when it does. The descriptor is opened O_NONBLOCK | O_CLOEXEC and fstat()ed, so a file
/// swapped for a FIFO between the stat and the open is refused too, without blocking.
/// Throws FileReadError: missing, not_regular ("is a FIFO (named pipe), not a regular file"),
/// too_large or unreadable (the system's reason: "Permission denied", a read error).
[[nodiscard]] std::string read_regular_file(const std::filesystem::path& file,
                                            std::size_t max_bytes);

}  // namespace fixstep
