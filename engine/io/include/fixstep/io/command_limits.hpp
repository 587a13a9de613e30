// The limits of one command (a run, a render, a replay, a comparison): how many ticks it may
// step and how much work it may do in all, so that a few bytes of command line or recording
// cannot buy days of CPU. Checked before the first tick, refused with a LimitError (limits.hpp)
// naming the claim, the limit and the way out. What a body-substep costs here:
// docs/ROBUSTNESS.md, "Limits on work and memory".
#pragma once

#include <cstdint>
#include <string_view>

#include "fixstep/core/limits.hpp"

namespace fixstep {

/// Most ticks one command steps: `run --steps` / `--duration`, `render` and `compare` (frames ×
/// ticks per frame), a recording's claimed ticks (max_recording_ticks is the same number, so
/// every run can be recorded and replayed).
inline constexpr std::uint64_t max_command_ticks = 1'000'000'000;
/// Most body-substeps in one command (ticks × tick_work): 10^13 (about a day of CPU).
inline constexpr std::uint64_t max_command_work = 10'000'000'000'000;
/// Most memory the sync test's K + 1 snapshots of a world may take (SyncTest keeps one per
/// rolled-back tick): 2 GiB, as for the implicit solve.
inline constexpr std::uint64_t max_sync_test_bytes = std::uint64_t{2} << 30;

/// Throws LimitError when `ticks` ticks of `work_per_tick` body-substeps exceed max_command_ticks
/// or max_command_work. `what` names the claim in the message, e.g. "--steps 2000000000" or
/// "x.rec: end 1000000000".
void check_command_work(std::uint64_t ticks, std::uint64_t work_per_tick, std::string_view what);

}  // namespace fixstep
