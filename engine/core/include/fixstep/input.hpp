// The input a tick receives: sampled once per frame and handed to every tick of that frame,
// so a run can be recorded as (tick, input) pairs and replayed bit for bit.
#pragma once

#include <cstdint>

#include "fixstep/types.hpp"

namespace fixstep {

struct TickInput {
  std::uint64_t tick = 0;  ///< index of the tick this input is for (0 = the first tick)
  /// An extra acceleration applied to every body during this tick (m/s², like gravity, so it
  /// moves light and heavy bodies alike); (0, 0) costs nothing. The window maps the arrow keys
  /// to it.
  Vec2 push{};
  friend constexpr bool operator==(const TickInput&, const TickInput&) = default;
};

}  // namespace fixstep
