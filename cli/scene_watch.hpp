// Hot reload for `fixstep view`: noticing that the scene file was saved, and the HUD lines that
// say a save is loading or could not be used.
//
// The watch polls the file's modification time, size and inode from the frame loop, at most
// once per interval of wall time: portable, no notification API, and an editor that saves by
// writing a new file and renaming it over the old one (a new inode) is seen like one that
// rewrites the file in place.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace fixstep::cli {

/// What tells one saved version of a file from the next. A file that cannot be read (missing,
/// mid-rename) has a stamp of its own (exists = false).
struct FileStamp {
  bool exists = false;
  std::int64_t mtime_ns = 0;  ///< modification time, ns since the file clock's epoch
  std::uintmax_t size = 0;    ///< bytes
  std::uint64_t inode = 0;    ///< 0 where the platform has none
  bool operator==(const FileStamp&) const = default;
};

/// The stamp of `path` now.
[[nodiscard]] FileStamp stamp_of(const std::string& path);

/// Polls a file for changes: changed() is true once for each new stamp it sees.
class FileWatch {
 public:
  using Clock = std::chrono::steady_clock;
  /// Takes the file's stamp now (take it before reading the file, so that a save made while
  /// it is read is not missed).
  explicit FileWatch(std::string path,
                     std::chrono::milliseconds interval = std::chrono::milliseconds(200));
  /// Whether the file's stamp differs from the one seen last; looks at the file only when
  /// `interval` has passed since it last looked (else false). A half-written file is a change
  /// like any other: the write that completes it is the next change.
  [[nodiscard]] bool changed(Clock::time_point now = Clock::now());
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::chrono::milliseconds interval_;
  Clock::time_point last_look_;
  FileStamp stamp_;
};

/// HUD lines for a reload that failed: `heading`, then `message` (a located scene error,
/// "file:line:col: key: message"), both made ASCII (the bitmap font has no other letters: ω
/// is spelled omega) and wrapped to fit a frame `frame_width` px wide at HUD text scale
/// `scale`. The message takes at most `max_lines` (>= 1) lines, the last of them saying that
/// the rest is on standard error when it is cut, so that the HUD grows by a few lines only and
/// the bodies stay in sight.
[[nodiscard]] std::vector<std::string> reload_error_lines(const std::string& heading,
                                                          const std::string& message,
                                                          int frame_width, float scale,
                                                          std::size_t max_lines = 3);

/// HUD lines while a saved scene loads: "LOADING `file`..." and that the world shown is the one
/// before the save, then `progress` (what the load does now, e.g. "stability guard: iteration
/// 310/10000 (3 %), 4.2 s"); made ASCII and wrapped as reload_error_lines does.
[[nodiscard]] std::vector<std::string> loading_lines(const std::string& file,
                                                     const std::string& progress, int frame_width,
                                                     float scale);

}  // namespace fixstep::cli
