// The choices every four-lane kernel makes (lane_types.hpp): a result chosen lane by lane by a
// mask, with bitwise operations and no branch, and whether a mask holds any lane. Every
// function here is inlined; include this only from a source built with -Wno-psabi
// (engine/CMakeLists.txt). Internal: not installed.
#pragma once

#include <cstdint>

#include "lane_types.hpp"

namespace fixstep::detail::four_lanes {

/// yes where m's lane is all ones, no where it is zero.
[[gnu::always_inline]] inline Lane choose(Mask m, Lane yes, Lane no) {
  return reinterpret_cast<Lane>((reinterpret_cast<Mask>(yes) & m) |
                                (reinterpret_cast<Mask>(no) & ~m));
}

/// Whether any lane of m is set.
[[gnu::always_inline]] inline bool any(Mask m) {
  std::int64_t all = 0;
  for (int l = 0; l < width; ++l) all |= m[l];
  return all != 0;
}

}  // namespace fixstep::detail::four_lanes
