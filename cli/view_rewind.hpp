// How much of the past `fixstep view` keeps for rewinding (Backspace): one state per tick, for
// rewind_seconds of simulated time, within rewind_max_bytes of states.
#pragma once

#include <cstddef>
#include <fixstep/core/rewind.hpp>
#include <fixstep/core/world.hpp>

namespace fixstep::cli {

/// Rewind keeps this much of the past, s of simulated time (one state per tick), in at most
/// rewind_max_bytes of states: a 300 x 300 grid of bodies and links holds about 48 MB a state,
/// so 10 s at 60 Hz would take 29 GB.
inline constexpr double rewind_seconds = 10.0;
inline constexpr std::size_t rewind_max_bytes = std::size_t{512} << 20;

/// The rewind buffer a world gets, decided from a measured state.
struct RewindPlan {
  std::size_t capacity = 1;     ///< ticks kept (>= 1)
  std::size_t state_bytes = 0;  ///< bytes of one state, after one tick (its scratch included)
  double dt = 0.0;              ///< s, the world's tick
};

/// The plan for `sim`'s world. Measures a copy stepped once (a tick builds force terms and
/// scratch arrays that every later state holds too: the scratch of a 90 000-body grid doubles
/// its state), so it takes about a tick and a copy of the world: seconds for 10^6 bodies. Polls
/// stop requests (throws StopRequested: fixstep/core/stop_request.hpp).
[[nodiscard]] RewindPlan plan_rewind(const World& sim);

/// A RewindBuffer of plan.capacity ticks; when that is less than rewind_seconds, says so once on
/// standard error, with what it keeps.
[[nodiscard]] RewindBuffer make_rewind(const RewindPlan& plan);

}  // namespace fixstep::cli
