// Random numbers for game rules that replay: a seeded generator whose whole state is two
// 64-bit integers, so a copy of it (a World's snapshot holds one, World::random()) rolls the
// same dice again after a restore, in a replay and on every platform.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace fixstep {

/// SplitMix64's output function: z ^= z >> 30, z *= 0xbf58476d1ce4e5b9, z ^= z >> 27,
/// z *= 0x94d049bb133111eb, z ^= z >> 31 (G. L. Steele, D. Lea, C. H. Flood, "Fast Splittable
/// Pseudorandom Number Generators", OOPSLA 2014; these constants are D. Stafford's "Mix13" as
/// S. Vigna's splitmix64.c uses them). A bijection of the 64-bit integers in which every input
/// bit flips each output bit with probability close to 1/2; mix_seed(0) = 0.
[[nodiscard]] constexpr std::uint64_t mix_seed(std::uint64_t z) {
  z = (z ^ (z >> 30u)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27u)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31u);
}

/// PCG32 (PCG-XSH-RR 64/32): a 64-bit linear congruential state, each 32-bit output a
/// permutation of it (xorshift high, random rotation). Period 2^64 per stream; 2^63 streams.
/// Source: M. E. O'Neill, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
/// Algorithms for Random Number Generation", Harvey Mudd College HMC-CS-2014-0905 (2014); the
/// multiplier is Knuth's MMIX one. Integer arithmetic only: the same numbers everywhere. Not
/// for cryptography.
///
/// Seeding: Random(seed, stream) is the paper's pcg32_srandom(mix_seed(seed), stream). The
/// paper's seeding alone adds the seed to the state, and an LCG state that differs only in its
/// top bits gives outputs that are bit rotations of each other (seeds 0 and 2^62 draw the same
/// values rotated); through mix_seed every seed bit changes about half of the state's bits.
/// Random::pcg32 is the paper's seeding itself (its published check vectors, and
/// Seeding::pcg32_srandom for recordings made before the mixing).
class Random {
 public:
  /// The generator seeded with `seed` on stream `stream` (any values; equal arguments give
  /// equal sequences, different seeds or streams independent ones; the top bit of `stream` is
  /// not used, as in the paper). Seed 0 is the same generator as pcg32(0, stream).
  explicit constexpr Random(std::uint64_t seed = 0, std::uint64_t stream = 0)
      : Random(Raw{}, mix_seed(seed), stream) {}

  /// The paper's pcg32_srandom(initstate, initseq), without mix_seed: the generator of PCG's
  /// published check vectors (pcg32(42, 54) first draws 0xa15c02b7) and the one a world with
  /// Seeding::pcg32_srandom uses. Seeds differing only in high bits give related streams.
  [[nodiscard]] static constexpr Random pcg32(std::uint64_t initstate, std::uint64_t initseq) {
    return Random(Raw{}, initstate, initseq);
  }

  /// The next 32 uniformly distributed bits.
  constexpr std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * multiplier + increment_;
    ++draws_;
    const auto shifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<std::uint32_t>(old >> 59u);
    return (shifted >> rotation) | (shifted << ((32u - rotation) & 31u));
  }

  /// A double uniform on [0, 1): 53 random bits (two draws) times 2^-53, exact.
  constexpr double uniform() {
    const std::uint64_t high = next_u32(), low = next_u32();
    return static_cast<double>(((high << 32u) | low) >> 11u) * 0x1p-53;
  }

  /// A double in [lo, hi): lo + (hi - lo)·uniform() (may round to hi when hi - lo is far
  /// above lo's ulp). Throws std::invalid_argument unless lo, hi and hi - lo are finite with
  /// lo ≤ hi (checked without raising an FP exception flag).
  double uniform(double lo, double hi) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || std::isgreater(lo, hi) ||
        !std::isfinite(hi - lo)) {
      throw std::invalid_argument("Random::uniform: needs finite lo <= hi");
    }
    return lo + (hi - lo) * uniform();
  }

  /// An integer uniform on [0, n), without bias: Lemire's multiply-and-reject (D. Lemire,
  /// "Fast Random Integer Generation in an Interval", ACM TOMACS 29(1), 2019). Draws one
  /// 32-bit value, rarely more. Throws std::invalid_argument for n = 0.
  constexpr std::uint32_t below(std::uint32_t n) {
    if (n == 0) throw std::invalid_argument("Random::below: n must be >= 1");
    std::uint64_t m = std::uint64_t{next_u32()} * n;
    if (static_cast<std::uint32_t>(m) < n) {
      const std::uint32_t threshold = (0u - n) % n;  // 2^32 mod n
      while (static_cast<std::uint32_t>(m) < threshold) m = std::uint64_t{next_u32()} * n;
    }
    return static_cast<std::uint32_t>(m >> 32u);
  }

  /// An integer uniform on [lo, hi] (both included; hi - lo < 2^32 - 1). Throws
  /// std::invalid_argument when lo > hi or the range is wider.
  constexpr std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    if (lo > hi || static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo) >= 0xffffffffu) {
      throw std::invalid_argument("Random::integer: needs lo <= hi, hi - lo < 4294967295");
    }
    const auto span = static_cast<std::uint32_t>(static_cast<std::uint64_t>(hi - lo) + 1u);
    return lo + static_cast<std::int64_t>(below(span));
  }

  /// True with probability p (uniform() < p): p ≤ 0 never, p ≥ 1 always. NaN throws
  /// std::invalid_argument.
  bool chance(double p) {
    if (std::isnan(p)) throw std::invalid_argument("Random::chance: p is NaN");
    return std::isless(uniform(), p);
  }

  /// 32-bit values drawn since seeding (uniform() draws two). A World mixes its generator's
  /// state into the state hash once this is not 0 (World::state_hash).
  [[nodiscard]] constexpr std::uint64_t draws() const { return draws_; }
  /// The 64-bit LCG state (for hashing and printing; two generators with equal state and
  /// stream give equal sequences).
  [[nodiscard]] constexpr std::uint64_t state() const { return state_; }
  friend constexpr bool operator==(const Random&, const Random&) = default;

 private:
  static constexpr std::uint64_t multiplier = 6364136223846793005ull;
  std::uint64_t state_ = 0;
  std::uint64_t increment_;
  std::uint64_t draws_ = 0;

  struct Raw {};
  constexpr Random(Raw /*unused*/, std::uint64_t initstate, std::uint64_t initseq)
      : increment_((initseq << 1u) | 1u) {
    next_u32();
    state_ += initstate;
    next_u32();
    draws_ = 0;
  }
};

}  // namespace fixstep
