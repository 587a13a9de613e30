// Where two recordings first differ: their worlds, the first tick whose recorded inputs differ,
// the first tick whose stored state hashes differ, and, replayed here side by side, the first
// tick, body and field where the states differ and whether each recording's own hashes come back
// (a desync between two networked peers, read from the two peers' recordings).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/rules.hpp"
#include "fixstep/core/state_difference.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

// Ticks: an input's tick is its index (the recording's `tick N` lines: the input of the N+1-th
// step); a state's or a stored hash's tick is the number of ticks stepped (World::tick(), the
// recording's `hash N` lines). An input that differs at tick N first changes the state at N + 1.

/// What two recordings hold in common, and where they first part.
struct RecordingDiff {
  /// "" when both are of one world (definition hash, recorded settings) stepped with the same
  /// rules (name and version); else what differs, and nothing else is compared.
  std::string world_difference;
  std::uint64_t ticks_a = 0, ticks_b = 0;            ///< ticks each recorded
  std::uint64_t hash_every_a = 0, hash_every_b = 0;  ///< ticks between each one's stored hashes
  /// The first tick, below min(ticks_a, ticks_b), whose recorded inputs differ bit for bit
  /// (same_input); nullopt when they are equal over the ticks both recorded.
  std::optional<std::uint64_t> input_tick;
  /// Stored state hashes (a recording's final hash counts as one stored at its last tick)
  /// compared at the ticks both recordings stored one.
  struct HashDifference {
    std::uint64_t tick = 0;        ///< the first such tick whose hashes differ
    std::uint64_t last_equal = 0;  ///< the last such tick before it (0: the start)
    /// The states first differ at `tick` exactly (else somewhere in (last_equal, tick]).
    [[nodiscard]] bool exact() const { return tick <= last_equal + 1; }
  };
  std::optional<HashDifference> hashes;
  std::uint64_t hashes_compared = 0;  ///< ticks at which both stored a hash
  /// Whether a recording's own stored hashes came back when it was replayed here.
  struct Reproduced {
    std::uint64_t verified = 0;  ///< stored hashes reproduced, in the ticks replayed
    /// The first stored hash that did not (and stopped this check), with the last that did.
    std::optional<ReplayReport::Mismatch> mismatch;
  };
  /// Both recordings replayed here side by side (diff_recordings only; not when the worlds
  /// differ).
  struct Replay {
    std::uint64_t ticks = 0;  ///< ticks replayed: to the first state difference or replay_end
    /// The first difference of the replayed states (state_fields, first_difference; ours is
    /// A's), and its one-line description with A's body names (describe).
    std::optional<StateDifference> state;
    std::string state_text;
    Reproduced a, b;
  };
  std::optional<Replay> replay;

  /// Equal worlds, lengths, inputs and stored hashes.
  [[nodiscard]] bool identical() const {
    return world_difference.empty() && ticks_a == ticks_b && !input_tick && !hashes;
  }
};

/// Bit-for-bit equality of two ticks' inputs, their tick fields aside: every double by its bits
/// (0.0 and -0.0 differ, unlike TickInput's operator==), the buttons, the drag body and the
/// per-body entries in order.
[[nodiscard]] bool same_input(const TickInput& a, const TickInput& b);

/// What can be compared without replaying: the worlds and rules, the inputs and the stored
/// hashes. For recordings with rules this build does not have. O(input changes + stored
/// hashes). Never throws but std::bad_alloc.
[[nodiscard]] RecordingDiff compare_recordings(const Recording& a, const Recording& b);

/// The tick the side-by-side replay of diff_recordings runs to (when no state difference stops
/// it first): the later of input_tick + 1 and hashes->tick where either is known, else the end
/// of the shorter recording; never past it.
[[nodiscard]] std::uint64_t replay_end(const RecordingDiff& diff);

/// compare_recordings, then (when the worlds are the same) both recordings replayed from tick 0
/// side by side, each on World(def) with its own inputs and its own rules (each a separate
/// instance, in the state it had at tick 0, run after every tick as replay() does), their
/// states compared field by field every tick from tick 0 to replay_end (stopping at the first
/// difference) and each one's stored hashes checked as replay() checks them. def_a and def_b
/// are the recordings' worlds with their recorded settings applied (apply_settings). Work:
/// replay_end × (both worlds' ticks + O(bodies)); the caller bounds it (tick_work); polls stop
/// requests every tick (StopRequested) and reports progress (work_progress.hpp). Throws
/// std::invalid_argument when a definition's hash is not its recording's, and what World(def)
/// and World::step throw.
[[nodiscard]] RecordingDiff diff_recordings(const WorldDef& def_a, const Recording& a,
                                            const WorldDef& def_b, const Recording& b,
                                            const TickRules& rules_a = {},
                                            const TickRules& rules_b = {});

/// The report as lines: the lengths, the inputs, the stored hashes, the replay (when done) and
/// each recording's hashes, then a last line starting "verdict: " saying what the differences
/// mean (for a desync: whose peer's state diverged, and at which tick). `a` and `b` name the
/// recordings (their file names).
[[nodiscard]] std::vector<std::string> describe(const RecordingDiff& diff, std::string_view a,
                                                std::string_view b);

}  // namespace fixstep
