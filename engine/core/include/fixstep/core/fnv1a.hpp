// FNV-1a, 64-bit (Fowler, Noll and Vo; http://www.isthe.com/chongo/tech/comp/fnv/): the one
// hash of bytes fixstep uses where a hash must be the same on every platform and in every run
// (definition hashes, embedded-scene checksums, the name index of World::find).
#pragma once

#include <cstdint>
#include <string_view>

namespace fixstep {

/// FNV-1a's 64-bit offset basis (the hash of no bytes) and prime.
inline constexpr std::uint64_t fnv1a_basis = 14695981039346656037ull;
inline constexpr std::uint64_t fnv1a_prime = 1099511628211ull;

/// `hash` with one more byte. Never throws.
[[nodiscard]] constexpr std::uint64_t fnv1a_byte(std::uint64_t hash, unsigned char byte) noexcept {
  return (hash ^ byte) * fnv1a_prime;
}

/// FNV-1a of `bytes`, continuing from `hash` (fnv1a_basis to start). Never throws.
[[nodiscard]] constexpr std::uint64_t fnv1a(std::string_view bytes,
                                            std::uint64_t hash = fnv1a_basis) noexcept {
  for (const char c : bytes) hash = fnv1a_byte(hash, static_cast<unsigned char>(c));
  return hash;
}

}  // namespace fixstep
