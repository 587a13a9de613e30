// PNG files written byte by byte for the image tests (test_images, test_scene_sprites): every
// chunk's CRC-32 right unless a test breaks it, the pixels stored without compression (zlib's
// stored blocks), so the tests need no encoder.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fixstep::testing {

inline std::uint32_t png_crc32(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xffffffffu;
}

inline void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

inline void put_chunk(std::vector<std::uint8_t>& out, const char* type,
                      const std::vector<std::uint8_t>& data) {
  put_be32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_be32(out, png_crc32(out.data() + start, out.size() - start));
}

/// A PNG of w x h RGBA8 pixels (`rgba`, top row first; empty: all zero), its IHDR saying
/// `ihdr_w` x `ihdr_h` when given (a size the data does not hold).
inline std::vector<std::uint8_t> png_bytes(int w, int h, std::vector<std::uint8_t> rgba = {},
                                           int ihdr_w = 0, int ihdr_h = 0) {
  if (rgba.empty()) rgba.assign(std::size_t(w) * std::size_t(h) * 4, 0);
  std::vector<std::uint8_t> raw;  // each row: filter 0, then its pixels
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgba.begin() + std::ptrdiff_t(y) * w * 4,
               rgba.begin() + std::ptrdiff_t(y + 1) * w * 4);
  }
  std::vector<std::uint8_t> z = {0x78, 0x01};  // zlib header; stored blocks of <= 65535 bytes
  for (std::size_t at = 0; at < raw.size() || at == 0;) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z.push_back(at + n == raw.size() ? 1 : 0);
    z.push_back(std::uint8_t(n & 0xff)), z.push_back(std::uint8_t(n >> 8));
    z.push_back(std::uint8_t(~n & 0xff)), z.push_back(std::uint8_t((~n >> 8) & 0xff));
    z.insert(z.end(), raw.begin() + std::ptrdiff_t(at), raw.begin() + std::ptrdiff_t(at + n));
    at += n;
    if (n == 0) break;
  }
  std::uint32_t a = 1, b = 0;  // Adler-32
  for (const std::uint8_t c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  put_be32(z, (b << 16) | a);
  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> ihdr;
  put_be32(ihdr, std::uint32_t(ihdr_w ? ihdr_w : w));
  put_be32(ihdr, std::uint32_t(ihdr_h ? ihdr_h : h));
  for (const std::uint8_t v : {8, 6, 0, 0, 0}) ihdr.push_back(v);  // 8-bit RGBA
  put_chunk(out, "IHDR", ihdr);
  put_chunk(out, "IDAT", z);
  put_chunk(out, "IEND", {});
  return out;
}

inline void write_bytes(const std::filesystem::path& file, const std::vector<std::uint8_t>& b) {
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

}  // namespace fixstep::testing
