// The IEEE-754 bit patterns of float and double values: what a state hash is fed, and what
// "the same state" means when fixstep compares states bit for bit (sync test, FSAL reuse,
// scene writing). memcpy, not std::bit_cast: emscripten 3.1.6's libc++ 13 has no bit_cast.
// Compilers turn each into a register move.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace fixstep {

/// The bits of `value`: a std::uint64_t for a double, a std::uint32_t for a float
/// (IEEE-754 binary64 / binary32). Never throws.
template <class Real>
requires std::is_same_v<Real, double> || std::is_same_v<Real, float>
[[nodiscard]] auto bits_of(Real value) noexcept {
  std::conditional_t<sizeof(Real) == 8, std::uint64_t, std::uint32_t> bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

/// The double whose bits are `bits` (IEEE-754 binary64). Never throws.
[[nodiscard]] inline double double_from_bits(std::uint64_t bits) noexcept {
  double value = 0.0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// Bitwise equality: -0 and +0 differ, and two NaNs are equal only with the same payload
/// (unlike ==). Never throws.
template <class Real>
[[nodiscard]] bool same_bits(Real a, Real b) noexcept {
  return bits_of(a) == bits_of(b);
}

}  // namespace fixstep
