#include "fixstep/capture/capture.hpp"

#include <fmt/format.h>
#include <libdeflate.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>
#include <vector>

namespace {

// The compressor of the PngEncoder encoding on this thread, set for the duration of one
// stbi_write_png_to_func call (stb's compress hook has no context argument).
thread_local libdeflate_compressor* current_compressor = nullptr;

// stb_image_write's STBIW_ZLIB_COMPRESS hook: a zlib stream (2-byte header, deflate data,
// Adler-32) of data[0, data_len). stb frees the result with STBIW_FREE (free), so it is
// malloc'd. `quality` is stb's global stbi_write_png_compression_level, ignored: the level is
// the compressor's. Returns nullptr on failure, which stb reports as an encoding failure.
unsigned char* zlib_compress_hook(unsigned char* data, int data_len, int* out_len,
                                  int /*quality*/) {
  libdeflate_compressor* c = current_compressor;
  if (c == nullptr || data_len < 0) return nullptr;
  const std::size_t in = static_cast<std::size_t>(data_len);
  const std::size_t bound = libdeflate_zlib_compress_bound(c, in);
  auto* out = static_cast<unsigned char*>(std::malloc(bound));
  if (out == nullptr) return nullptr;
  const std::size_t n = libdeflate_zlib_compress(c, data, in, out, bound);
  if (n == 0 || n > static_cast<std::size_t>(INT_MAX)) {  // 0: did not fit (cannot happen)
    std::free(out);
    return nullptr;
  }
  *out_len = static_cast<int>(n);
  return out;
}

// stb_image_write's STBIW_CRC32 hook: the CRC-32 of each PNG chunk (PNG's CRC is the standard
// CRC-32, the one libdeflate_crc32 computes when started from 0, per libdeflate.h). stb's own is
// a byte-at-a-time table loop over the whole IDAT chunk; libdeflate's is vectorised
// (PCLMULQDQ where the CPU has it).
unsigned int png_crc32(const unsigned char* buffer, int len) {
  return libdeflate_crc32(0, buffer, len > 0 ? static_cast<std::size_t>(len) : 0);
}

}  // namespace

// stb_image_write with its private copy of every function and global (STB_IMAGE_WRITE_STATIC):
// nothing outside this file can change stbi_write_force_png_filter under a running encoder.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO  // we do the file I/O ourselves, atomically
#define STBIW_ZLIB_COMPRESS zlib_compress_hook
#define STBIW_CRC32(buffer, len) png_crc32(buffer, len)
#include <stb/stb_image_write.h>

namespace fixstep {

namespace {

std::string reason(int err) {
  return std::strerror(err);
}

// PNG row filter for every row. stb's default (-1) tries all five filters on each row and
// keeps the one with the smallest sum of absolute values: 5x the filtering work. On fixstep's
// frames (flat backgrounds, anti-aliased shapes) filter 0 "None" with libdeflate level 1 is
// 3.3x faster than that choice and its files are within 0.5 % of the same size; Sub, Up,
// Average and Paeth are all slower, and Sub and Average also larger (docs/perf/capture.md).
constexpr int png_filter_none = 0;

// Sets the stb_image_write globals once per process, before the first encoder exists (a
// function-local static: initialised exactly once even when threads race here). They are
// only read afterwards, so concurrent encoders on several threads see one constant value.
void configure_stb_once() {
  static const bool configured = [] {
    stbi_write_force_png_filter = png_filter_none;
    return true;
  }();
  (void)configured;
}

/// Packs the RGBA8 pixels of `rgba` as RGB8 into `rgb` (3/4 of its size) when every alpha is
/// 255, and returns whether it was so (`rgb` is then the image); false for any other alpha.
/// Each pixel is copied as 4 bytes 3 bytes apart, the next one overwriting its alpha: one load
/// and one store a pixel (`rgb` keeps a byte of room past the image for the last).
bool pack_opaque_rgb(std::span<const std::uint8_t> rgba, std::vector<std::uint8_t>& rgb) {
  const std::size_t pixels = rgba.size() / 4;
  rgb.resize(pixels * 3 + 1);
  const std::uint8_t* in = rgba.data();
  std::uint8_t* out = rgb.data();
  std::uint32_t all = 0xffffffffu;  // every pixel's bytes ANDed: byte 3 is the alphas'
  for (std::size_t i = 0; i < pixels; ++i, in += 4, out += 3) {
    std::uint32_t p = 0;
    std::memcpy(&p, in, 4);
    all &= p;
    std::memcpy(out, &p, 4);
  }
  rgb.pop_back();  // the room; the capacity stays for the next image
  std::uint8_t bytes[4];
  std::memcpy(bytes, &all, 4);
  return bytes[3] == 0xffu;
}

}  // namespace

namespace {

/// Runs `write` on the core AtomicOutput, reporting its errors as CaptureError.
template <class Write>
void as_capture_error(Write&& write) {
  try {
    write();
  } catch (const std::exception& e) {  // runtime_error (I/O) or logic_error (a second commit)
    throw CaptureError(e.what());
  }
}

AtomicOutput open_output(std::filesystem::path file) {
  try {
    return AtomicOutput(std::move(file));
  } catch (const std::exception& e) {
    throw CaptureError(e.what());
  }
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path file) : out_(open_output(std::move(file))) {}

void AtomicFile::append(std::span<const std::uint8_t> bytes) {
  append(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void AtomicFile::append(std::string_view text) {
  as_capture_error([&] { out_.append(text); });
}

void AtomicFile::commit() {
  as_capture_error([&] { out_.commit(); });
}

void write_file_atomic(const std::filesystem::path& file, std::span<const std::uint8_t> bytes) {
  AtomicFile f(file);
  f.append(bytes);
  f.commit();
}

void write_file_atomic(const std::filesystem::path& file, std::string_view text) {
  write_file_atomic(file,
                    std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

std::string png_level_error(int level) {
  if (level >= min_png_level && level <= max_png_level) return {};
  return fmt::format(
      "PNG level {} is outside {}..{} (libdeflate levels: 0 = no compression, 1 = fastest, "
      "12 = smallest)",
      level, min_png_level, max_png_level);
}

struct PngEncoder::Compressor {
  libdeflate_compressor* c;
  explicit Compressor(int level) : c(libdeflate_alloc_compressor(level)) {
    if (c == nullptr) throw std::bad_alloc();
  }
  ~Compressor() { libdeflate_free_compressor(c); }
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;
};

PngEncoder::PngEncoder(PngSettings options) : options_(options) {
  if (const std::string error = png_level_error(options.level); !error.empty()) {
    throw std::invalid_argument(error);
  }
  configure_stb_once();
  compressor_ = std::make_unique<Compressor>(options.level);
}

PngEncoder::~PngEncoder() = default;
PngEncoder::PngEncoder(PngEncoder&& other) noexcept = default;
PngEncoder& PngEncoder::operator=(PngEncoder&& other) noexcept = default;

std::span<const std::uint8_t> PngEncoder::encode(int width, int height,
                                                 std::span<const std::uint8_t> rgba,
                                                 std::string_view name) {
  if (width <= 0 || height <= 0 ||
      rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    throw CaptureError(fmt::format("cannot write {}: image is {}x{} but has {} bytes", name, width,
                                   height, rgba.size()));
  }
  if (!compressor_) {
    throw CaptureError(fmt::format("cannot write {}: PNG encoder was moved from", name));
  }
  png_.clear();
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* p = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), p, p + size);
  };
  struct Bind {  // current_compressor = ours for this call only, even if `append` throws
    explicit Bind(libdeflate_compressor* c) { current_compressor = c; }
    ~Bind() { current_compressor = nullptr; }
    Bind(const Bind&) = delete;
    Bind& operator=(const Bind&) = delete;
  } bind(compressor_->c);
  // An opaque image (a rendered frame always is) as RGB: a quarter fewer bytes to compress.
  const bool opaque = pack_opaque_rgb(rgba, rgb_);
  const int ok =
      opaque ? stbi_write_png_to_func(append, &png_, width, height, 3, rgb_.data(), width * 3)
             : stbi_write_png_to_func(append, &png_, width, height, 4, rgba.data(), width * 4);
  if (!ok) throw CaptureError(fmt::format("cannot write {}: PNG encoding failed", name));
  return png_;
}

void PngEncoder::write(const std::filesystem::path& file, int width, int height,
                       std::span<const std::uint8_t> rgba) {
  write_file_atomic(file, encode(width, height, rgba, file.string()));
}

void write_png(const std::filesystem::path& file, int width, int height,
               std::span<const std::uint8_t> rgba, PngSettings options) {
  PngEncoder(options).write(file, width, height, rgba);
}

std::filesystem::path frame_path(const std::filesystem::path& dir, std::uint64_t frame) {
  return dir / fmt::format("frame_{:06}.png", frame);
}

namespace {

// Bytes of a width x height RGBA8 frame, after FrameWriter's checks of its arguments.
std::size_t checked_frame_bytes(int width, int height, int in_flight) {
  if (width < 1 || height < 1) {
    throw std::invalid_argument(
        fmt::format("FrameWriter: frame size {}x{} is below 1x1", width, height));
  }
  if (in_flight < 1) {
    throw std::invalid_argument(
        fmt::format("FrameWriter: in_flight is {}, must be >= 1", in_flight));
  }
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
}

}  // namespace

FrameWriter::FrameWriter(std::filesystem::path dir, int width, int height, PngSettings options,
                         int in_flight)
    : dir_(std::move(dir)),
      width_(width),
      height_(height),
      encoder_(options),
      pipeline_(
          checked_frame_bytes(width, height, in_flight), static_cast<std::size_t>(in_flight),
          [this](std::span<const std::uint8_t> rgba, std::uint64_t frame) {
            encoder_.write(frame_path(dir_, frame), width_, height_, rgba);
          },
          FramePipeline::Pending::consume) {}

std::filesystem::path FrameWriter::submit(std::span<const std::uint8_t> rgba) {
  return submit(rgba, next_frame_);
}

std::filesystem::path FrameWriter::submit(std::span<const std::uint8_t> rgba, std::uint64_t frame) {
  const std::size_t bytes =
      static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4;
  if (rgba.size() != bytes) {
    throw std::invalid_argument(fmt::format("FrameWriter: frame {} has {} bytes, {}x{} RGBA8 is {}",
                                            frame, rgba.size(), width_, height_, bytes));
  }
  if (submitted_ > 0 && frame < next_frame_) {
    throw std::invalid_argument(
        fmt::format("FrameWriter: frame {} submitted after frame {}: frames go in increasing order",
                    frame, next_frame_ - 1));
  }
  pipeline_.submit(rgba, frame);
  ++submitted_;
  next_frame_ = frame + 1;
  return frame_path(dir_, frame);
}

void FrameWriter::finish() {
  pipeline_.drain();
}

void prepare_output_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw CaptureError(fmt::format(
        "output directory {} is a file, not a directory: give a new or existing directory",
        dir.string()));
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    throw CaptureError(
        fmt::format("cannot create output directory {}: {}", dir.string(), ec.message()));
  }
  if (!std::filesystem::is_directory(dir, ec)) {
    throw CaptureError(fmt::format("output path {} exists and is not a directory", dir.string()));
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw CaptureError(
        fmt::format("output directory {} is not writable: {}", dir.string(), reason(errno)));
  }
}

}  // namespace fixstep
