// The sync test of rollback netcode (GGRS's SyncTestSession): every tick, roll the simulation
// back K ticks, re-simulate them with the same inputs and compare the states, so any state a
// snapshot misses (or any nondeterminism) shows up at the first tick it matters.
#pragma once

#include <any>
#include <cstdint>
#include <optional>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/rules.hpp"
#include "fixstep/core/world.hpp"

namespace fixstep {

class SyncTest {
 public:
  /// Where a re-simulated tick differed from the first run.
  struct Mismatch {
    std::uint64_t tick = 0;           ///< the tick count after the differing tick
    std::uint64_t expected = 0;       ///< first run's state hash (World::state_hash)
    std::uint64_t actual = 0;         ///< the re-simulation's
    bool dissipated_differs = false;  ///< hashes equal, dissipated energy's bits differ
  };

  /// Tests `sim` (kept by reference: it must outlive the SyncTest) with rollbacks of
  /// `rollback_ticks` K >= 1 ticks (std::invalid_argument otherwise), running `rules` after
  /// every tick, first and re-simulated alike (their state is saved and restored with the
  /// world's when they give save and restore; see TickRules). Memory: K + 1 snapshots.
  SyncTest(World& sim, int rollback_ticks, TickRules rules = {});

  /// Steps one tick with `input` (then the rules), restores the snapshot of min(K, ticks
  /// stepped) ticks ago and re-simulates up to now with the recorded inputs, comparing the
  /// state hash and the dissipated energy (bit for bit) after every re-simulated tick with the
  /// first run's. The simulation goes on from the re-simulated state. Returns false, and keeps
  /// the first mismatch(), when they differ; then further calls only step.
  bool step(const TickInput& input);
  [[nodiscard]] const std::optional<Mismatch>& mismatch() const { return mismatch_; }
  /// Ticks re-simulated so far.
  [[nodiscard]] std::uint64_t resimulated() const { return resimulated_; }

 private:
  struct Slot {
    WorldSnapshot state;  ///< the state after `tick` ticks
    TickInput input;      ///< the input of the tick that starts from it
    std::uint64_t hash = 0;
    double dissipated = 0.0;
    std::any rules;  ///< the rules' state after `tick` ticks (TickRules::save)
  };
  Slot& slot(std::uint64_t tick) { return slots_[tick % slots_.size()]; }
  void remember(std::uint64_t tick);
  bool check(std::uint64_t tick);
  void tick_with_rules(const TickInput& input);

  World& sim_;
  TickRules rules_;
  std::uint64_t rollback_;
  std::uint64_t first_tick_;
  std::vector<Slot> slots_;
  std::optional<Mismatch> mismatch_;
  std::uint64_t resimulated_ = 0;
};

}  // namespace fixstep
