// An output written piece by piece: a file published whole (what a long `run --record` streams
// its recording into, so that memory stays O(1) however long the run), or a stream written as
// it goes (a pipe, a device, standard output). What the path names decides which, once, when
// the output is opened (output_target.hpp).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "fixstep/io/output_target.hpp"

namespace fixstep {

/// ".NAME.tmp.PID" beside `file`: the temporary file an atomic write of `file` fills before
/// renaming it over `file` (parse_temporary_name takes such names apart).
[[nodiscard]] std::filesystem::path temporary_file_for(const std::filesystem::path& file);

/// An output opened by what its path names (classify_output):
/// - a regular file or a new name: appends go to a temporary file beside it
///   (temporary_file_for), created with the replaced file's permission bits; commit() renames
///   it over the file. Until then the file keeps its old contents (or stays absent): a run
///   killed half-way leaves only the temporary file, and one abandoned by an exception or an
///   early return removes it (the destructor).
/// - a symbolic link (or a chain of them, or a dangling one): its final target is written as
///   above, the temporary file beside the target; the link stays a link.
/// - a FIFO, a character device or a descriptor name ("-", "/dev/stdout", "/dev/fd/N"):
///   appends are written to it directly (buffered), commit() flushes; no temporary, no rename.
///   A reader sees every byte written, also those of an output abandoned half-way.
/// - a directory, block device, socket or other special file: refused by the constructor.
/// Errors throw std::runtime_error "cannot write FILE: REASON", FILE as given, with the
/// system's reason ("No space left on device", "File too large" past `ulimit -f`, "Broken
/// pipe" when a pipe's reader has gone), naming the directory when it does not exist; the
/// temporary file is removed.
class AtomicOutput {
 public:
  /// Classifies `file` and creates the temporary file or opens the stream (a FIFO: waits for
  /// its reader). Ignores SIGXFSZ first (ignore_file_size_signal). Throws as above (a missing
  /// directory, no permission, a refused kind: "cannot write d: is a directory (...)").
  explicit AtomicOutput(std::filesystem::path file);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  /// Appends `text` (buffered). Throws as above (a full disk: "No space left on device").
  void append(std::string_view text);
  /// Flushes and closes the output; for a file, renames the temporary file over it. Once only
  /// (std::logic_error after the first).
  void commit();
  /// Bytes appended so far.
  [[nodiscard]] std::uint64_t size() const { return size_; }
  /// The path as given.
  [[nodiscard]] const std::filesystem::path& file() const { return file_; }
  /// Whether the output is streamed (written in place) rather than replaced atomically.
  [[nodiscard]] bool streamed() const { return target_.kind == OutputKind::stream; }

 private:
  void open_temporary();
  void open_stream();
  [[noreturn]] void fail(int err);
  std::filesystem::path file_;
  OutputTarget target_;
  std::string tmp_;  // the temporary file; empty for a stream
  std::FILE* out_ = nullptr;
  std::uint64_t size_ = 0;
};

}  // namespace fixstep
