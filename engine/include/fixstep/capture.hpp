// Writing frames to disk: PNG via stb_image_write, atomically.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string_view>

namespace fixstep {

/// A file could not be written. what() names the path and the system's reason.
class CaptureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file written atomically: bytes go to a temporary file beside `file` (same directory, so
/// the final rename cannot cross file systems), which commit() renames over `file`. Destroyed
/// without commit() — an error, an exception, a stop — the temporary is removed; after a hard
/// kill only a ".NAME.tmp.PID" file can remain, never a partial file under the final name.
/// Errors (open, write, full disk, rename) throw CaptureError naming `file` and the reason.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path file);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  void append(std::span<const std::uint8_t> bytes);
  void append(std::string_view text);
  /// Flushes, closes and renames the temporary onto the final name.
  void commit();

 private:
  [[noreturn]] void fail(int err);
  std::filesystem::path file_;
  std::string tmp_;
  std::FILE* out_ = nullptr;
};

/// Writes `bytes` to `file` atomically: into a temporary file in the same directory, which is
/// renamed over `file` only once fully written and closed. After a crash or a full disk, `file`
/// is either absent, its previous version, or complete — never partial. Throws CaptureError.
void write_file_atomic(const std::filesystem::path& file, std::span<const std::uint8_t> bytes);
void write_file_atomic(const std::filesystem::path& file, std::string_view text);

/// Encodes an RGBA8 image (height rows of width*4 bytes, top row first) as PNG with
/// stb_image_write and writes it with write_file_atomic. Throws CaptureError.
void write_png(const std::filesystem::path& file, int width, int height,
               std::span<const std::uint8_t> rgba);

/// DIR/frame_NNNNNN.png (six digits, zero-padded).
[[nodiscard]] std::filesystem::path frame_path(const std::filesystem::path& dir,
                                               std::uint64_t frame);

/// Creates `dir` (and parents) if needed and checks it is a writable directory.
/// Throws CaptureError naming the directory and the reason.
void prepare_output_dir(const std::filesystem::path& dir);

}  // namespace fixstep
