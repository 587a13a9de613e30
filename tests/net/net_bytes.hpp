// Test helper: packets built byte by byte, independently of fixstep::net's encoders.
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

namespace fixstep::net_test {

struct Bytes {
  std::vector<std::uint8_t> v;
  Bytes& u8(std::uint64_t x) { return put(x, 1); }
  Bytes& u16(std::uint64_t x) { return put(x, 2); }
  Bytes& u32(std::uint64_t x) { return put(x, 4); }
  Bytes& u64(std::uint64_t x) { return put(x, 8); }
  Bytes& f64(double x) { return put(std::bit_cast<std::uint64_t>(x), 8); }
  Bytes& zeros(std::size_t n) {
    v.insert(v.end(), n, 0);
    return *this;
  }
  /// The 12-byte header: "FXSN", version, kind, slot, reserved 0, sequence.
  Bytes& header(std::uint8_t kind, std::uint8_t slot, std::uint32_t sequence,
                std::uint8_t version = net::protocol_version) {
    v.insert(v.end(), {'F', 'X', 'S', 'N'});
    return u8(version).u8(kind).u8(slot).u8(0).u32(sequence);
  }

 private:
  Bytes& put(std::uint64_t x, int n) {
    for (int i = 0; i < n; ++i) v.push_back(static_cast<std::uint8_t>(x >> (8 * i)));
    return *this;
  }
};

}  // namespace fixstep::net_test
