// fixstep::net: SipHash-2-4 and the gate's keys and tokens (fixstep/net/net_gate.hpp).
#include <bit>
#include <random>

#include "fixstep/net/net_gate.hpp"

namespace fixstep::net {

namespace {

std::uint64_t load_le(const std::uint8_t* p, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t{p[i]} << (8 * i);
  return v;
}

/// One SipRound (Aumasson and Bernstein 2012, section 2) on the state v0..v3.
void sip_round(std::array<std::uint64_t, 4>& v) {
  v[0] += v[1];
  v[1] = std::rotl(v[1], 13);
  v[1] ^= v[0];
  v[0] = std::rotl(v[0], 32);
  v[2] += v[3];
  v[3] = std::rotl(v[3], 16);
  v[3] ^= v[2];
  v[0] += v[3];
  v[3] = std::rotl(v[3], 21);
  v[3] ^= v[0];
  v[2] += v[1];
  v[1] = std::rotl(v[1], 17);
  v[1] ^= v[2];
  v[2] = std::rotl(v[2], 32);
}

void sip_compress(std::array<std::uint64_t, 4>& v, std::uint64_t m) {
  v[3] ^= m;
  sip_round(v);
  sip_round(v);
  v[0] ^= m;
}

}  // namespace

std::uint64_t siphash24(const GateKey& key, std::span<const std::uint8_t> bytes) {
  const std::uint64_t k0 = load_le(key.data(), 8), k1 = load_le(key.data() + 8, 8);
  // The initialization constants are the ASCII of "somepseudorandomlygeneratedbytes".
  std::array<std::uint64_t, 4> v{k0 ^ 0x736f6d6570736575ull, k1 ^ 0x646f72616e646f6dull,
                                 k0 ^ 0x6c7967656e657261ull, k1 ^ 0x7465646279746573ull};
  const std::size_t whole = bytes.size() / 8 * 8;
  for (std::size_t i = 0; i < whole; i += 8) sip_compress(v, load_le(bytes.data() + i, 8));
  // The last block: the remaining bytes, and the length mod 256 in the top byte.
  const std::uint64_t last =
      load_le(bytes.data() + whole, bytes.size() - whole) | (std::uint64_t{bytes.size()} << 56);
  sip_compress(v, last);
  v[2] ^= 0xff;
  for (int i = 0; i < 4; ++i) sip_round(v);
  return v[0] ^ v[1] ^ v[2] ^ v[3];
}

GateKey random_gate_key() {
  std::random_device device;
  GateKey key{};
  for (std::size_t i = 0; i < key.size(); i += 4) {
    const std::uint32_t word = device();
    for (std::size_t j = 0; j < 4; ++j) key[i + j] = static_cast<std::uint8_t>(word >> (8 * j));
  }
  return key;
}

std::string format_token(const GateKey& token) {
  static constexpr char digits[] = "0123456789abcdef";
  std::string out;
  for (std::uint8_t b : token) {
    out.push_back(digits[b >> 4]);
    out.push_back(digits[b & 15]);
  }
  return out;
}

std::optional<GateKey> parse_token(std::string_view text) {
  if (text.size() != 32) return std::nullopt;
  auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  GateKey key{};
  for (std::size_t i = 0; i < key.size(); ++i) {
    const int hi = nibble(text[2 * i]), lo = nibble(text[2 * i + 1]);
    if (hi < 0 || lo < 0) return std::nullopt;
    key[i] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  return key;
}

}  // namespace fixstep::net
