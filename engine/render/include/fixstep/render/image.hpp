// Images the renderer draws (sprites, a tiled background, a game's overlay images): PNG files
// decoded to RGBA8 pixels, each loaded once per renderer (ImageCache), within fixed bounds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "fixstep/core/components.hpp"

namespace fixstep {

/// An image that cannot be used: missing, unreadable, not a PNG, corrupt or truncated, larger
/// than max_image_side, or beyond the cache's count or byte budget. what() reads
/// "image FILE: REASON"; file() is the path as given.
class ImageError : public std::runtime_error {
 public:
  ImageError(std::string file, const std::string& reason);
  [[nodiscard]] const std::string& file() const { return file_; }

 private:
  std::string file_;
};

/// Decoded pixels: height rows of width RGBA8 pixels (straight alpha), the top row first.
struct Image {
  int width = 0, height = 0;  ///< px, 1 .. max_image_side
  std::vector<std::uint8_t> rgba;
};

/// The 8 bytes every PNG file starts with (PNG specification, section 5.2).
inline constexpr std::uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

/// Decodes `bytes`, a PNG file's content (any PNG colour type and bit depth; 16-bit samples
/// rounded to 8), to RGBA8. Throws ImageError naming `name` when the bytes do not start with
/// the PNG signature (JPEG, GIF and the rest are refused), when the image is wider or taller
/// than max_image_side, or when the data is corrupt or truncated (the decoder's reason).
[[nodiscard]] Image decode_png(std::span<const std::uint8_t> bytes, const std::string& name);

/// Reads and decodes the PNG file at `path` (decode_png). Throws ImageError naming `path` when
/// it cannot be opened or read (the system's reason), is larger than max_image_file_bytes, or
/// decode_png refuses it.
[[nodiscard]] Image load_png(const std::string& path);

/// The images a renderer has loaded, each once, by path (the string as given: "a.png" and
/// "./a.png" are two entries). At most max_images of them, together at most max_image_bytes of
/// pixels; a refused path is not remembered (asking again tries again).
class ImageCache {
 public:
  /// The index of the image at `path`, loading it on first use (load_png). Throws ImageError
  /// as load_png, or naming `path` when it would be image max_images + 1 or take the pixels
  /// beyond max_image_bytes.
  std::size_t index(const std::string& path);
  /// Image `i` (an index() returned).
  [[nodiscard]] const Image& at(std::size_t i) const { return *images_[i]; }
  [[nodiscard]] std::size_t size() const { return images_.size(); }
  /// Bytes of pixels held.
  [[nodiscard]] std::size_t bytes() const { return bytes_; }

 private:
  std::unordered_map<std::string, std::size_t> by_path_;
  std::vector<std::unique_ptr<Image>> images_;
  std::size_t bytes_ = 0;
};

}  // namespace fixstep
