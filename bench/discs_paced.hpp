// bench_discs --paced SCENE N TICKS: fixstep on 1 and 2 threads and Box2D v3.2 on 1 and 2
// workers (where built) stepping a disc scene (discs.hpp) one tick a frame at 60 Hz, as a game
// does, each tick timed; prints the mean, median and 90th percentile of a tick. Internal to
// bench/.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "discs.hpp"

namespace discs {

/// A game's frame at 60 frames a second.
inline constexpr std::chrono::duration<double> paced_frame{1.0 / 60.0};
/// Ticks a stepper takes in a row before the next one takes its turn.
inline constexpr int paced_block = 20;

/// Steps `scene` ("pile", "gas" or "pile_settled") of `n` discs (2 to 10^5), after its warm-up,
/// for `ticks` ticks a stepper (paced_block to 36 000, rounded down to whole blocks), paced
/// at paced_frame, and prints a Markdown table of the tick times to stdout. Throws
/// std::invalid_argument for a scene, N or tick count out of range. Returns 0.
int paced(const std::string& scene, std::size_t n, int ticks);

}  // namespace discs
