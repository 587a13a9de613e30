// What a configuration costs: wall time per simulated second of stepping its world, measured
// warm, on its own, the way a benchmark measures it (compare's HUD and summary).
#pragma once

#include <fixstep/core/world.hpp>

namespace fixstep::cli {

/// Wall seconds per simulated second of stepping a copy of `world` from its state (the world
/// itself is not stepped). Steps batches of one simulated second, or of
/// as many ticks as take about 2 ms when that is fewer (a first tick estimates it; a batch
/// stops early if the runtime guard fires), from the initial state each time, repeated until a
/// sample has taken at least 2 ms; the median of 5 samples (1 when a
/// sample takes longer than 50 ms, so that large worlds do not stall the command). Includes
/// everything a tick does (World::step with the scene's settings), nothing else.
[[nodiscard]] double step_cost(const World& world);

}  // namespace fixstep::cli
