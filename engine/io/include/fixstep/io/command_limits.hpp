// The limits of one command (a run, a render, a replay, a comparison, a view): how many ticks it
// may step, how much work it may do in all and how much memory it may plan to allocate, so that a
// few bytes of command line, scene or recording cannot buy days of CPU or a std::bad_alloc.
// Checked before the first tick (the memory before the worlds and frame buffers are allocated),
// refused with a LimitError (limits.hpp) naming the claim, the limit and the way out. What a
// body-substep costs and what the memory estimates were fitted to: docs/ROBUSTNESS.md, "Limits on
// work and memory".
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "fixstep/core/limits.hpp"
#include "fixstep/core/world_def.hpp"

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

/// Throws LimitError when the sync test's `rollback` + 1 snapshots of `world` (each
/// World::snapshot_bytes() plus a World) exceed max_sync_test_bytes; the message names
/// --sync-test K, the estimate in GiB and the bound.
void check_sync_test_memory(const World& world, int rollback);

/// Most memory one command may plan to allocate, by its estimate (a sum of MemoryTerm): 4 GiB.
/// The estimates are upper bounds of the measured peak resident memory (docs/ROBUSTNESS.md has
/// the table), so a command refused here would have needed more, and one accepted needs less.
inline constexpr std::uint64_t max_command_bytes = std::uint64_t{4} << 30;

/// Bytes of the program before any input is read (its libraries: Mesa, FFmpeg, SDL), included in
/// every command's estimate: 128 MiB, above the resident size measured (docs/ROBUSTNESS.md).
inline constexpr std::uint64_t program_base_bytes = std::uint64_t{128} << 20;

/// An upper estimate of the bytes one World of `def` holds once it has stepped (its state
/// arrays, the force terms and scratch a tick builds, its disc contacts' broadphase and contact
/// lists, its names), and so of each copy of it (a snapshot, a shadow world): per body, link,
/// plane, segment and disc, fitted to peak resident memory (docs/ROBUSTNESS.md).
[[nodiscard]] std::uint64_t world_bytes_estimate(const WorldDef& def);
/// An upper estimate of the bytes building a World of `def` takes beside the world itself, while
/// World(def) runs (the stability guard's vectors, the links' colouring): freed once it is built.
[[nodiscard]] std::uint64_t world_build_bytes_estimate(const WorldDef& def);
/// An upper estimate of the bytes `def` itself holds (its BodyDef, LinkDef, PlaneDef and
/// SegmentDef vectors by their capacity, and names): a Scene, a Session and each compare tile
/// hold a copy.
[[nodiscard]] std::uint64_t definition_bytes_estimate(const WorldDef& def);
/// An upper estimate of the bytes a Renderer drawing `def`'s world into width x height pixels
/// holds: per body its frame data and trail (48 samples), per link its ends, and the frame's
/// buffers (OSMesa's colour and depth buffers, the pixels read back, the HUD's): 4 bytes a pixel
/// each, 4 buffers.
[[nodiscard]] std::uint64_t renderer_bytes_estimate(const WorldDef& def, int width, int height);
/// Bytes of one width x height RGBA8 frame (4 bytes a pixel).
[[nodiscard]] std::uint64_t frame_bytes(int width, int height);

/// One part of a command's memory estimate.
struct MemoryTerm {
  std::string what;     ///< what takes it and where it comes from, e.g. "6 tiles' worlds of ..."
  std::uint64_t bytes;  ///< the estimate, bytes
  std::string way_out;  ///< how to ask for less, e.g. "fewer --with tiles or a smaller world"
};

/// Throws LimitError when the terms sum to more than max_command_bytes: "COMMAND: would need
/// about X GiB of memory (TERM Y GiB + ...; terms under 1 MiB left out); a command may use at
/// most 4 GiB (max_command_bytes): WHAT dominates: WAY OUT", WHAT and WAY OUT those of the
/// largest term. `command` names the command and its input, e.g. "compare scene.toml". The sum
/// saturates at UINT64_MAX instead of overflowing.
void check_command_memory(std::string_view command, std::span<const MemoryTerm> terms);
/// The sum of the terms' bytes, saturating at UINT64_MAX.
[[nodiscard]] std::uint64_t total_bytes(std::span<const MemoryTerm> terms);

}  // namespace fixstep
