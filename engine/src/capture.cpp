#include "fixstep/capture.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO  // we do the file I/O ourselves, atomically
#include <stb/stb_image_write.h>

namespace fixstep {

namespace {
std::string reason(int err) { return std::strerror(err); }
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path file) : file_(std::move(file)) {
  const std::filesystem::path dir = file_.has_parent_path() ? file_.parent_path() : ".";
  tmp_ = (dir / fmt::format(".{}.tmp.{}", file_.filename().string(), ::getpid())).string();
  out_ = std::fopen(tmp_.c_str(), "wbe");
  if (!out_) {
    throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), reason(errno)));
  }
}

AtomicFile::~AtomicFile() {
  if (out_) {
    std::fclose(out_);
    ::unlink(tmp_.c_str());
  }
}

void AtomicFile::fail(int err) {
  if (out_) std::fclose(out_);
  out_ = nullptr;
  ::unlink(tmp_.c_str());
  throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), reason(err)));
}

void AtomicFile::append(std::span<const std::uint8_t> bytes) {
  if (!out_) throw CaptureError(fmt::format("cannot write {}: already closed", file_.string()));
  if (std::fwrite(bytes.data(), 1, bytes.size(), out_) != bytes.size()) fail(errno ? errno : EIO);
}

void AtomicFile::append(std::string_view text) {
  append(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void AtomicFile::commit() {
  if (!out_) throw CaptureError(fmt::format("cannot write {}: already closed", file_.string()));
  errno = 0;
  if (std::fflush(out_) != 0 || std::ferror(out_)) fail(errno ? errno : EIO);
  std::FILE* f = out_;
  out_ = nullptr;
  if (std::fclose(f) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), reason(err)));
  }
  if (::rename(tmp_.c_str(), file_.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), reason(err)));
  }
}

void write_file_atomic(const std::filesystem::path& file, std::span<const std::uint8_t> bytes) {
  AtomicFile f(file);
  f.append(bytes);
  f.commit();
}

void write_file_atomic(const std::filesystem::path& file, std::string_view text) {
  write_file_atomic(file, std::span(reinterpret_cast<const std::uint8_t*>(text.data()),
                                    text.size()));
}

void write_png(const std::filesystem::path& file, int width, int height,
               std::span<const std::uint8_t> rgba) {
  if (width <= 0 || height <= 0 ||
      rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    throw CaptureError(fmt::format("cannot write {}: image is {}x{} but has {} bytes",
                                   file.string(), width, height, rgba.size()));
  }
  std::vector<std::uint8_t> png;
  png.reserve(rgba.size() / 4);
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* p = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), p, p + size);
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 4, rgba.data(), width * 4)) {
    throw CaptureError(fmt::format("cannot write {}: PNG encoding failed", file.string()));
  }
  write_file_atomic(file, png);
}

std::filesystem::path frame_path(const std::filesystem::path& dir, std::uint64_t frame) {
  return dir / fmt::format("frame_{:06}.png", frame);
}

void prepare_output_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    throw CaptureError(fmt::format("cannot create output directory {}: {}", dir.string(),
                                   ec.message()));
  }
  if (!std::filesystem::is_directory(dir, ec)) {
    throw CaptureError(fmt::format("output path {} exists and is not a directory", dir.string()));
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw CaptureError(fmt::format("output directory {} is not writable: {}", dir.string(),
                                   reason(errno)));
  }
}

}  // namespace fixstep
