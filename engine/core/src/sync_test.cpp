#include "fixstep/core/sync_test.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/input.hpp"

namespace fixstep {

SyncTest::SyncTest(World& sim, int rollback_ticks, TickRules rules)
    : sim_(sim),
      rules_(std::move(rules)),
      rollback_(static_cast<std::uint64_t>(std::max(rollback_ticks, 1))),
      first_tick_(sim.tick()) {
  if (rollback_ticks < 1) {
    throw std::invalid_argument(
        fmt::format("sync test: rollback must be >= 1 tick (got {})", rollback_ticks));
  }
  if (rules_.attach) rules_.attach(sim_);
  slots_.resize(rollback_ + 1);
  remember(first_tick_);
}

void SyncTest::remember(std::uint64_t tick) {
  Slot& s = slot(tick);
  sim_.save(s.state);
  s.hash = sim_.state_hash();
  s.dissipated = sim_.dissipated_energy();
  if (rules_.save) s.rules = rules_.save();
}

void SyncTest::tick_with_rules(const TickInput& input) {
  rules_.tick(sim_, input);
}

bool SyncTest::check(std::uint64_t tick) {
  const Slot& s = slot(tick);
  const std::uint64_t hash = sim_.state_hash();
  const bool same_dissipated = same_bits(sim_.dissipated_energy(), s.dissipated);
  if (hash == s.hash && same_dissipated) return true;
  mismatch_ = Mismatch{tick, s.hash, hash, hash == s.hash};
  return false;
}

bool SyncTest::step(const TickInput& input) {
  const std::uint64_t t = sim_.tick();
  slot(t).input = input;
  tick_with_rules(input);
  if (mismatch_) return false;
  remember(t + 1);
  const std::uint64_t back = std::min(rollback_, t + 1 - first_tick_);
  const Slot& from = slot(t + 1 - back);
  sim_.restore(from.state);
  if (rules_.restore) rules_.restore(from.rules);
  for (std::uint64_t k = t + 1 - back; k <= t; ++k) {
    tick_with_rules(slot(k).input);
    ++resimulated_;
    if (!check(k + 1)) return false;
    sim_.save(slot(k + 1).state);
    if (rules_.save) slot(k + 1).rules = rules_.save();
  }
  return true;
}

}  // namespace fixstep
