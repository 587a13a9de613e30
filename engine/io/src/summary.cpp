// A simulation's state as text (summary.hpp).
#include "fixstep/io/summary.hpp"

#include <fmt/format.h>

#include "fixstep/core/step_results.hpp"

namespace fixstep {

std::string hex_hash(std::uint64_t hash) {
  return fmt::format("{:016x}", hash);
}

std::string summary_line(const World& sim, double initial_energy) {
  const double balance = energy_balance(sim, initial_energy);
  return fmt::format(
      "ticks={} t={:.6f} state_hash={} energy={:.9e} dissipated={:.9e} balance={:.6e}{}",
      sim.tick(), sim.time(), hex_hash(sim.state_hash()), sim.energy().total(),
      sim.dissipated_energy(), balance, initial_energy != 0.0 ? "" : "J");
}

}  // namespace fixstep
