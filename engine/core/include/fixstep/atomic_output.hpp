// A file written piece by piece and published whole: what a long `run --record` streams its
// recording into, so that memory stays O(1) however long the run (issue 21, class 6).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace fixstep {

/// Appends go to a temporary file beside `file` (".NAME.tmp.PID", as write_file_atomically);
/// commit() renames it over `file`. Until then `file` keeps its old contents (or stays absent):
/// a run killed half-way leaves only the temporary file, and one abandoned by an exception or
/// an early return removes it (the destructor). Errors throw std::runtime_error "cannot write
/// FILE: REASON" with the system's reason, or naming the directory when it does not exist; the
/// temporary file is removed.
class AtomicOutput {
 public:
  /// Creates the temporary file. Throws as above (a missing directory, no permission).
  explicit AtomicOutput(std::filesystem::path file);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  /// Appends `text` (buffered). Throws as above (a full disk: "No space left on device").
  void append(std::string_view text);
  /// Flushes, closes and renames the temporary file over `file`. Once only (std::logic_error
  /// after the first).
  void commit();
  /// Bytes appended so far.
  [[nodiscard]] std::uint64_t size() const { return size_; }
  [[nodiscard]] const std::filesystem::path& file() const { return file_; }

 private:
  [[noreturn]] void fail(int err);
  std::filesystem::path file_;
  std::string tmp_;
  std::FILE* out_ = nullptr;
  std::uint64_t size_ = 0;
};

}  // namespace fixstep
