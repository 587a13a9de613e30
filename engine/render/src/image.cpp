// PNG images (image.hpp): decoded by stb_image (Debian's libstb-dev, header-only), PNG only.
#include "fixstep/render/image.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_FAILURE_USERMSG
// (A system header, natively and in the page: its own warnings are not ours.)
#include <stb/stb_image.h>

namespace fixstep {

ImageError::ImageError(std::string file, const std::string& reason)
    : std::runtime_error(fmt::format("image {}: {}", file, reason)), file_(std::move(file)) {}

Image decode_png(std::span<const std::uint8_t> bytes, const std::string& name) {
  if (bytes.size() < sizeof png_signature ||
      !std::equal(std::begin(png_signature), std::end(png_signature), bytes.begin())) {
    throw ImageError(name, "not a PNG file (it does not start with the PNG signature)");
  }
  if (bytes.size() > max_image_file_bytes) {
    throw ImageError(name, fmt::format("larger than {} bytes", max_image_file_bytes));
  }
  const auto size = static_cast<int>(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), size, &w, &h, &channels)) {
    throw ImageError(name, fmt::format("corrupt or truncated PNG ({})", stbi_failure_reason()));
  }
  if (w < 1 || h < 1 || w > max_image_side || h > max_image_side) {
    throw ImageError(
        name, fmt::format("{} x {} px: an image is at most {} px a side", w, h, max_image_side));
  }
  stbi_uc* data = stbi_load_from_memory(bytes.data(), size, &w, &h, &channels, 4);
  if (!data) {
    throw ImageError(name, fmt::format("corrupt or truncated PNG ({})", stbi_failure_reason()));
  }
  Image out;
  out.width = w;
  out.height = h;
  out.rgba.assign(data, data + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  stbi_image_free(data);
  return out;
}

Image load_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImageError(path, fmt::format("cannot open it ({})", std::strerror(errno)));
  std::vector<std::uint8_t> bytes;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    bytes.insert(bytes.end(), buffer, buffer + in.gcount());
    if (bytes.size() > max_image_file_bytes) {
      throw ImageError(path, fmt::format("larger than {} bytes", max_image_file_bytes));
    }
  }
  if (in.bad()) throw ImageError(path, "cannot read it");
  return decode_png(bytes, path);
}

std::size_t ImageCache::index(const std::string& path) {
  if (const auto it = by_path_.find(path); it != by_path_.end()) return it->second;
  if (images_.size() >= max_images) {
    throw ImageError(path, fmt::format("more than {} images", max_images));
  }
  auto image = std::make_unique<Image>(load_png(path));
  if (image->rgba.size() > max_image_bytes - bytes_) {
    throw ImageError(
        path, fmt::format("the images would take more than {} bytes of pixels", max_image_bytes));
  }
  bytes_ += image->rgba.size();
  images_.push_back(std::move(image));
  by_path_.emplace(path, images_.size() - 1);
  return images_.size() - 1;
}

}  // namespace fixstep
