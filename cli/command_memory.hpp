// What each fixstep command will allocate, estimated from its input before it allocates it (its
// worlds and their copies, definitions, renderers and frame buffers, recordings), and checked
// against max_command_bytes (fixstep/io/command_limits.hpp): a LimitError naming the command,
// the estimate, the bound, the term that dominates and the way out, instead of a
// std::bad_alloc half-way. The per-item sizes and what they were fitted to: docs/ROBUSTNESS.md,
// "Memory of a command".
#pragma once

#include <cstdint>
#include <fixstep/core/recording.hpp>
#include <fixstep/scene/scene.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fixstep/io/command_limits.hpp"

namespace fixstep::cli {

/// `run`: the scene's definition and world, the exact reference's per-body states;
/// `sync_test` K: K + 1 snapshots of the world (also bounded by max_sync_test_bytes).
[[nodiscard]] std::vector<MemoryTerm> run_memory(const Scene& scene, std::optional<int> sync_test);
/// `render` at width x height pixels: the definition (the scene's and the Session's), the world,
/// the renderer (per body, its trail) and the frame buffers (the renderer's and the capture's
/// frames in flight: 8 frames of width x height x 4 bytes, 15 with `video`, an MP4 or GIF
/// encoder), and with --replay the recording (the
/// world that verifies it first is freed before the Session's is built).
[[nodiscard]] std::vector<MemoryTerm> render_memory(const Scene& scene, int width, int height,
                                                    bool video, const Recording* replay);
/// `compare` of `tiles` tiles of `base` (a tile's overrides change no count) in a width x height
/// frame: per tile two definitions,
/// its world, a shadow world when `shadows` (the scene has no exact solution) and a renderer of
/// its cell; one world's build or the copy step_cost times (a tile at a time); the frame, and the
/// capture's frames in flight (more with `video`).
[[nodiscard]] std::vector<MemoryTerm> compare_memory(const Scene& base, std::size_t tiles,
                                                     bool shadows, int width, int height,
                                                     bool video);
/// `view` at width x height: the definition (the scene's and the Session's), the world, the
/// rewind buffer (at most rewind_max_bytes, and at least one state: more than the world's build
/// and the copy the rewind plan steps, which come before it), the renderer and the window's frame.
[[nodiscard]] std::vector<MemoryTerm> view_memory(const Scene& scene, int width, int height);
/// `replay`: the recording as read, the definition and the world.
[[nodiscard]] std::vector<MemoryTerm> replay_memory(const Scene& scene, const Recording& rec);

/// Throws LimitError (check_command_memory) naming "COMMAND FILE", e.g. "compare scene.toml".
void check_memory(std::string_view command, const std::string& file,
                  std::span<const MemoryTerm> terms);

}  // namespace fixstep::cli
