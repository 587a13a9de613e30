// A simulation's state as text: the summary line the programs print and state hashes in hex.
#pragma once

#include <cstdint>
#include <string>

#include "fixstep/core/world.hpp"

namespace fixstep {

/// "ticks=N t=T state_hash=HHHHHHHHHHHHHHHH energy=E dissipated=D balance=B": the summary
/// `run` and `render` print. energy and dissipated in J; balance = energy_balance() (suffixed
/// "J" when E0 = 0).
[[nodiscard]] std::string summary_line(const World& sim, double initial_energy);

/// 16 lowercase hex digits.
[[nodiscard]] std::string hex_hash(std::uint64_t hash);

}  // namespace fixstep
