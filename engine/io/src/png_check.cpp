// A PNG file's structure checked without inflating it (png_check.hpp).
#include "fixstep/io/png_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "fixstep/core/components.hpp"
#include "fixstep/io/file_read.hpp"

namespace fixstep {

namespace {

// CRC-32 of PNG (ISO 3309, polynomial 0xedb88320 reflected; PNG specification annex D).
std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

std::uint32_t png_crc(std::span<const std::uint8_t> bytes) {
  static const std::array<std::uint32_t, 256> table = make_crc_table();
  std::uint32_t c = 0xffffffffu;
  for (const std::uint8_t b : bytes) c = table[(c ^ b) & 0xffu] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

std::uint32_t big_endian(std::span<const std::uint8_t> b) {
  return (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) |
         std::uint32_t{b[3]};
}

[[noreturn]] void refuse(const std::string& why) {
  throw std::runtime_error(why);
}

}  // namespace

PngSize check_png(std::span<const std::uint8_t> bytes) {
  constexpr std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || !std::equal(std::begin(signature), std::end(signature), bytes.begin())) {
    refuse("not a PNG file (it does not start with the PNG signature)");
  }
  PngSize size;
  bool idat = false;
  std::size_t at = 8;
  for (int chunk = 0;; ++chunk) {
    if (bytes.size() - at < 12) {
      refuse(fmt::format("truncated (the file ends inside chunk {}, before IEND)", chunk));
    }
    const std::uint32_t length = big_endian(bytes.subspan(at, 4));
    const std::string type(reinterpret_cast<const char*>(bytes.data() + at + 4), 4);
    if (length > bytes.size() - at - 12) {
      refuse(fmt::format("truncated (chunk {} {} of {} bytes ends beyond the file)", chunk, type,
                         length));
    }
    const std::span<const std::uint8_t> data = bytes.subspan(at + 8, length);
    if (png_crc(bytes.subspan(at + 4, length + 4)) !=
        big_endian(bytes.subspan(at + 8 + length, 4))) {
      refuse(fmt::format("corrupt (chunk {} {}'s CRC-32 does not match its data)", chunk, type));
    }
    if (chunk == 0) {
      if (type != "IHDR" || length != 13) refuse("corrupt (its first chunk is not a 13-byte IHDR)");
      const std::uint32_t w = big_endian(data.subspan(0, 4)), h = big_endian(data.subspan(4, 4));
      if (w < 1 || h < 1 || w > std::uint32_t(max_image_side) ||
          h > std::uint32_t(max_image_side)) {
        refuse(fmt::format("{} x {} px: an image is 1 to {} px a side", w, h, max_image_side));
      }
      size = {static_cast<int>(w), static_cast<int>(h)};
    }
    idat = idat || type == "IDAT";
    at += 12 + length;
    if (type == "IEND") break;
  }
  if (!idat) refuse("corrupt (no IDAT chunk: no pixels)");
  return size;
}

PngSize check_png_file(const std::filesystem::path& file) {
  const std::string text = read_regular_file(file, max_image_file_bytes);
  return check_png(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace fixstep
