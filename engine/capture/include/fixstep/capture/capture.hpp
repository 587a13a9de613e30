// Writing frames to disk: PNG via stb_image_write (deflate by libdeflate), atomically.
#pragma once

#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/capture/frame_pipeline.hpp"
#include "fixstep/io/atomic_output.hpp"

namespace fixstep {

/// A file could not be written. what() names the path and the system's reason.
class CaptureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file written atomically: core's AtomicOutput (atomic_output.hpp: a ".NAME.tmp.PID" file
/// beside `file`, or beside the file a symbolic link leads to, renamed over it by commit(),
/// removed when destroyed without commit(); a FIFO or device streamed to, a directory refused)
/// with its errors as CaptureError, the type render's callers catch. Errors (open, write, full
/// disk, rename, a second commit) throw CaptureError naming `file` and the reason.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path file);
  void append(std::span<const std::uint8_t> bytes);
  void append(std::string_view text);
  /// Flushes, closes and renames the temporary onto the final name.
  void commit();

 private:
  AtomicOutput out_;
};

/// Writes `bytes` to `file` atomically: into a temporary file in the same directory, which is
/// renamed over `file` only once fully written and closed. After a crash or a full disk, `file`
/// is either absent, its previous version, or complete — never partial. Throws CaptureError.
void write_file_atomic(const std::filesystem::path& file, std::span<const std::uint8_t> bytes);
void write_file_atomic(const std::filesystem::path& file, std::string_view text);

/// Compression levels of PngSettings::level: libdeflate's scale (libdeflate.h,
/// libdeflate_alloc_compressor): 0 stores the pixels uncompressed (a valid PNG about as large
/// as the raw image), 1 is the fastest that compresses, 6 is zlib's usual default, 12 the
/// smallest and slowest. See docs/perf/capture.md for measured speed and size per level.
inline constexpr int min_png_level = 0;
inline constexpr int max_png_level = 12;
/// 1: on fixstep's frames (flat colours, anti-aliased shapes) it is the fastest level and its
/// files are already smaller than stb_image_write's own deflate makes them.
inline constexpr int default_png_level = 1;

/// How PNGs are encoded. Every level writes a standard 8-bit RGBA PNG that decodes to exactly
/// the input pixels; the level only trades encoding time against file size.
struct PngSettings {
  int level = default_png_level;  ///< [min_png_level, max_png_level]
};

/// "PNG level L is outside MIN..MAX (...)" when `level` is out of range, else "".
[[nodiscard]] std::string png_level_error(int level);

/// A reusable PNG encoder: stb_image_write builds the PNG (rows filtered with PNG filter 0,
/// "None", on every row) and libdeflate compresses it (through stb's STBIW_ZLIB_COMPRESS hook)
/// at options.level. It owns one libdeflate compressor and its output buffer, so encoding a
/// sequence allocates no new buffers of its own after the first frame (stb_image_write still
/// mallocs its scratch rows per image).
///
/// Thread safety: one encoder must not be used by two threads at once; separate encoders may
/// encode concurrently on separate threads (no shared mutable state: the stb_image_write
/// globals are private to capture.cpp and set once, and the compressor is passed per thread).
class PngEncoder {
 public:
  /// Throws std::invalid_argument naming the level and the range if options.level is outside
  /// [min_png_level, max_png_level]; std::bad_alloc if libdeflate cannot allocate.
  explicit PngEncoder(PngSettings options = {});
  ~PngEncoder();
  PngEncoder(PngEncoder&& other) noexcept;
  PngEncoder& operator=(PngEncoder&& other) noexcept;
  PngEncoder(const PngEncoder&) = delete;
  PngEncoder& operator=(const PngEncoder&) = delete;

  [[nodiscard]] const PngSettings& options() const { return options_; }

  /// Encodes an RGBA8 image: `rgba` is height rows of width*4 bytes (R, G, B, A), top row
  /// first, width and height >= 1. An image whose every alpha is 255 (as every frame the
  /// renderer draws) is written as RGB (PNG colour type 2), any other as RGBA (type 6): both
  /// decode to the same RGBA. Returns the PNG file's bytes, valid until the next call on this
  /// encoder. Throws CaptureError (naming `name`, e.g. the file it is meant for) if the size
  /// does not match or encoding fails.
  [[nodiscard]] std::span<const std::uint8_t> encode(int width, int height,
                                                     std::span<const std::uint8_t> rgba,
                                                     std::string_view name = "image");
  /// encode() and write_file_atomic(file, ...). Throws CaptureError naming `file`.
  void write(const std::filesystem::path& file, int width, int height,
             std::span<const std::uint8_t> rgba);

 private:
  struct Compressor;
  PngSettings options_;
  std::unique_ptr<Compressor> compressor_;
  std::vector<std::uint8_t> rgb_;  ///< an opaque image packed as RGB8
  std::vector<std::uint8_t> png_;
};

/// Encodes an RGBA8 image (height rows of width*4 bytes, top row first) as PNG with
/// stb_image_write and libdeflate (see PngEncoder) and writes it with write_file_atomic.
/// Throws CaptureError naming `file`, or std::invalid_argument for a bad options.level. For a
/// sequence of frames, reuse a PngEncoder or use FrameWriter (this builds a new compressor).
void write_png(const std::filesystem::path& file, int width, int height,
               std::span<const std::uint8_t> rgba, PngSettings options = {});

/// DIR/frame_NNNNNN.png (six digits, zero-padded).
[[nodiscard]] std::filesystem::path frame_path(const std::filesystem::path& dir,
                                               std::uint64_t frame);

/// Writes a sequence of frames as DIR/frame_000000.png, frame_000001.png, ... (frame_path), each
/// named by its frame index (every frame, or every K-th: frame_000000.png, frame_000003.png, ...
/// when the caller submits frames 0, 3, ...), in submission order, each exactly once, encoding and
/// writing them on one worker thread while the caller renders the next frame. Every file is written
/// atomically (write_file_atomic) with a PngEncoder at `options`, so the files are byte-identical
/// to PngEncoder::write's.
///
/// Pipeline: submit() copies the pixels into one of `in_flight` buffers allocated up front
/// (in_flight * width * height * 4 bytes; no allocation per frame) and returns at once; it
/// blocks only while all `in_flight` buffers still wait for the worker.
///
/// Errors: the first frame the worker cannot write (unwritable directory, full disk, ...)
/// stops the worker; that frame and every later one are not written, frames before it stay
/// on disk, and the next submit() or finish() rethrows its CaptureError (naming the file).
///
/// Thread safety: call submit() and finish() from one thread (the producer).
class FrameWriter {
 public:
  /// Starts the worker. `dir` must exist (see prepare_output_dir). Throws std::invalid_argument
  /// for a bad options.level (as PngEncoder), a size below 1x1 or in_flight < 1.
  FrameWriter(std::filesystem::path dir, int width, int height, PngSettings options = {},
              int in_flight = 2);
  /// Waits until the worker has written every submitted frame (or failed), then stops it.
  /// Errors are not thrown from here: call finish() to see them.
  ~FrameWriter() = default;
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  /// Queues `rgba` (height rows of width*4 bytes, RGBA8, top row first; copied before this
  /// returns) as the frame after the last one submitted (frame 0 first) and returns the path it
  /// will be written to. Throws std::invalid_argument if the size does not match, or the
  /// worker's CaptureError if a frame has failed.
  std::filesystem::path submit(std::span<const std::uint8_t> rgba);
  /// The same for frame index `frame` (frame_path(dir, frame)): a capture of every K-th frame
  /// names each by its index. Throws std::invalid_argument as above, and when `frame` is not
  /// past the last frame submitted (each name is written once, in order).
  std::filesystem::path submit(std::span<const std::uint8_t> rgba, std::uint64_t frame);
  /// Blocks until every submitted frame is on disk. Throws the worker's CaptureError if one
  /// failed. More frames may be submitted afterwards.
  void finish();

  /// Frames submitted so far (the next frame's number when every frame is submitted).
  [[nodiscard]] std::uint64_t frames_submitted() const { return submitted_; }
  /// The index submit(rgba) gives the next frame: the last frame's plus one (0 before any).
  [[nodiscard]] std::uint64_t next_frame() const { return next_frame_; }
  [[nodiscard]] const std::filesystem::path& directory() const { return dir_; }

 private:
  std::filesystem::path dir_;
  int width_, height_;
  PngEncoder encoder_;            // used by the worker only
  std::uint64_t submitted_ = 0;   // producer only
  std::uint64_t next_frame_ = 0;  // producer only: the last frame's index + 1
  FramePipeline pipeline_;        // last: its worker starts once everything above is ready
};

/// Creates `dir` (and parents) if needed and checks it is a writable directory.
/// Throws CaptureError naming the directory and the reason.
void prepare_output_dir(const std::filesystem::path& dir);

}  // namespace fixstep
