// Internal to fixstep::net: little-endian bytes written and read with bounds checked, so a
// decoder never reads past its packet (a short read sets a flag instead).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace fixstep::net::detail {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { uint(v, 2); }
  void u32(std::uint32_t v) { uint(v, 4); }
  void u64(std::uint64_t v) { uint(v, 8); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  /// LEB128: 7 bits a byte, low bits first, the top bit set on every byte but the last.
  void varint(std::uint64_t v) {
    while (v >= 0x80u) {
      out_.push_back(static_cast<std::uint8_t>(v | 0x80u));
      v >>= 7;
    }
    out_.push_back(static_cast<std::uint8_t>(v));
  }
  void zeros(std::size_t n) { out_.insert(out_.end(), n, 0); }
  [[nodiscard]] std::size_t size() const { return out_.size(); }
  /// Overwrites the 16-bit value at byte `at` (a length known only after what follows).
  void patch_u16(std::size_t at, std::uint16_t v) {
    out_[at] = static_cast<std::uint8_t>(v);
    out_[at + 1] = static_cast<std::uint8_t>(v >> 8);
  }

 private:
  void uint(std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t>& out_;
};

/// Reads from a span; past its end every read returns 0 and ok() turns false for good.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> in) : in_(in) {}
  std::uint8_t u8() { return static_cast<std::uint8_t>(uint(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(uint(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(uint(4)); }
  std::uint64_t u64() { return uint(8); }
  double f64() { return std::bit_cast<double>(u64()); }
  /// A LEB128 varint of at most `max_bytes` bytes (<= 9: 63 bits); a longer one or one that
  /// ends past the span sets ok() false and returns 0.
  std::uint64_t varint(int max_bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < max_bytes; ++i) {
      const std::uint8_t b = u8();
      v |= std::uint64_t{b & 0x7fu} << (7 * i);
      if ((b & 0x80u) == 0) return ok_ ? v : 0;
    }
    ok_ = false;
    return 0;
  }
  [[nodiscard]] bool ok() const { return ok_; }
  [[nodiscard]] std::size_t remaining() const { return ok_ ? in_.size() - at_ : 0; }
  [[nodiscard]] std::size_t position() const { return at_; }
  /// Whether the next n bytes are all zero (n <= remaining()); skips them.
  bool zeros(std::size_t n) {
    bool all = true;
    for (std::size_t i = 0; i < n; ++i) all = (u8() == 0) && all;
    return all && ok_;
  }

 private:
  std::uint64_t uint(int bytes) {
    if (!ok_ || in_.size() - at_ < static_cast<std::size_t>(bytes)) {
      ok_ = false;
      return 0;
    }
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t{in_[at_ + i]} << (8 * i);
    at_ += static_cast<std::size_t>(bytes);
    return v;
  }
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

}  // namespace fixstep::net::detail
