// The memory estimates of the fixstep commands (command_memory.hpp).
#include "command_memory.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "view_rewind.hpp"

namespace fixstep::cli {

namespace {

/// Per body, what a command keeps beside the world: `run`'s exact reference and touched
/// bodies, `compare`'s per-tile measures, a CSV row's scratch.
constexpr std::uint64_t command_body_bytes = 128;
/// Frames of width x height x 4 bytes a capture holds beside its renderers' buffers: the frame
/// submitted, the frames queued for the PNG or video writers and their encoders' buffers. PNG:
/// 4 (render --size 8192x8192 --out peaks at 6.3 frames with the renderer's); a video, MP4 or
/// GIF: 11 (at 8192x8192, 12.5 and 13 frames with the renderer's).
constexpr std::uint64_t png_capture_frames = 4, video_capture_frames = 11;

/// Frames of buffers the tiles' renderers of `compare` hold together.
constexpr std::uint64_t compare_renderer_frames = 3;

std::uint64_t capture_frames(bool video) {
  return video ? video_capture_frames : png_capture_frames;
}

/// "1000000 bodies, 1998000 links" of a definition, for the terms' names.
std::string counts(const WorldDef& def) {
  std::string s = fmt::format("{} bodies", def.bodies.size());
  if (!def.links.empty()) s += fmt::format(", {} links", def.links.size());
  if (def.settings.contacts) s += ", [contacts]";
  return s;
}

MemoryTerm program_term() {
  return {.what = "the program", .bytes = program_base_bytes, .way_out = ""};
}

std::string fewer(const Scene& scene) {
  return fmt::format("fewer bodies or links in {}", scene.file);
}

std::string size_text(int width, int height) {
  return fmt::format("{}x{}", width, height);
}

}  // namespace

std::vector<MemoryTerm> run_memory(const Scene& scene, std::optional<int> sync_test) {
  const WorldDef& def = scene.def;
  std::vector<MemoryTerm> terms{program_term()};
  terms.push_back({.what = fmt::format("the world of {} and its definition", counts(def)),
                   .bytes = world_bytes_estimate(def) + world_build_bytes_estimate(def) +
                            definition_bytes_estimate(def) + def.bodies.size() * command_body_bytes,
                   .way_out = fewer(scene)});
  if (sync_test) {
    terms.push_back(
        {.what = fmt::format("--sync-test {}: {} snapshots", *sync_test, *sync_test + 1),
         // check_sync_test_memory bounds them by the world's measured snapshot, after the
         // build and before the first is taken.
         .bytes = std::min((std::uint64_t(*sync_test) + 1) * world_bytes_estimate(def),
                           max_sync_test_bytes),
         .way_out = "a smaller --sync-test K"});
  }
  return terms;
}

std::vector<MemoryTerm> render_memory(const Scene& scene, int width, int height, bool video,
                                      const Recording* replay) {
  const WorldDef& def = scene.def;
  std::vector<MemoryTerm> terms{program_term()};
  terms.push_back(
      {.what = fmt::format("the world of {}, its definitions and renderer", counts(def)),
       .bytes = world_bytes_estimate(def) + world_build_bytes_estimate(def) +
                2 * definition_bytes_estimate(def) + renderer_bytes_estimate(def, 0, 0) +
                def.bodies.size() * command_body_bytes,
       .way_out = fewer(scene)});
  terms.push_back({.what = fmt::format("--size {} frame buffers{}", size_text(width, height),
                                       video ? " and the --video encoder" : ""),
                   .bytes = renderer_bytes_estimate(WorldDef{}, width, height) +
                            capture_frames(video) * frame_bytes(width, height),
                   .way_out = "a smaller --size"});
  if (replay) {
    // The world that verifies it first is gone before the Session's is built.
    terms.push_back(replay_memory(scene, *replay)[1]);
  }
  return terms;
}

std::vector<MemoryTerm> compare_memory(const Scene& base, std::size_t tiles, bool shadows,
                                       int width, int height, bool video) {
  const WorldDef& def = base.def;  // a tile's overrides change no count: each tile's is this
  std::vector<MemoryTerm> terms{program_term()};
  terms.push_back({.what = fmt::format("the scene of {}", counts(def)),
                   .bytes = definition_bytes_estimate(def) + def.bodies.size() * command_body_bytes,
                   .way_out = fewer(base)});
  const std::uint64_t world = world_bytes_estimate(def);
  const std::uint64_t per_tile = 2 * definition_bytes_estimate(def) + (shadows ? 2 : 1) * world +
                                 renderer_bytes_estimate(def, 0, 0) +
                                 def.bodies.size() * command_body_bytes;
  // One tile at a time: its world's build, or the copy step_cost times.
  const std::uint64_t per_tiles =
      tiles * per_tile + std::max(world_build_bytes_estimate(def), world);
  terms.push_back({.what = fmt::format("{} tiles (--with) of {}: each its world, {}its definitions "
                                       "and renderer, and the copy a tile's cost is measured on",
                                       tiles, counts(def), shadows ? "a shadow world, " : ""),
                   .bytes = per_tiles,
                   .way_out = fmt::format("fewer --with tiles, or {}", fewer(base))});
  // The tiles' renderers share the frame (less the gaps): together 3 frames of buffers, fitted
  // to six tiles at 8192x8192 (peaks 2.09 GB with --out, 3.76 GB with --video: 7.3 and 13.5
  // frames in all), then the frame they are copied into and the capture's.
  terms.push_back(
      {.what = fmt::format("--size {} frame buffers{}", size_text(width, height),
                           video ? " and the --video encoder" : ""),
       .bytes = (compare_renderer_frames + 1 + capture_frames(video)) * frame_bytes(width, height),
       .way_out = "a smaller --size"});
  return terms;
}

std::vector<MemoryTerm> view_memory(const Scene& scene, int width, int height) {
  const WorldDef& def = scene.def;
  const std::uint64_t world = world_bytes_estimate(def);
  std::vector<MemoryTerm> terms{program_term()};
  terms.push_back(
      {.what = fmt::format("the world of {}, its definitions and renderer", counts(def)),
       .bytes = world + 2 * definition_bytes_estimate(def) + renderer_bytes_estimate(def, 0, 0),
       .way_out = fewer(scene)});
  // Rewind keeps states within rewind_max_bytes, and always one; before it, the world's build
  // and the copy plan_rewind steps come and go.
  terms.push_back(
      {.what = "the rewind buffer",
       .bytes = std::max({std::uint64_t{rewind_max_bytes}, world, world_build_bytes_estimate(def)}),
       .way_out = fewer(scene)});
  terms.push_back(
      {.what = fmt::format("--size {} frame buffers", size_text(width, height)),
       .bytes = renderer_bytes_estimate(WorldDef{}, width, height) + frame_bytes(width, height),
       .way_out = "a smaller --size"});
  return terms;
}

std::vector<MemoryTerm> replay_memory(const Scene& scene, const Recording& rec) {
  const WorldDef& def = scene.def;
  std::uint64_t recording = rec.scene_text.size() + rec.hashes.size() * 16;
  for (const TickInput& in : rec.inputs) {
    recording += sizeof(TickInput) + in.bodies.size() * 64;
  }
  std::vector<MemoryTerm> terms{program_term()};
  terms.push_back({.what = fmt::format("the recording ({} input changes, {} hashes)",
                                       rec.inputs.size(), rec.hashes.size()),
                   .bytes = recording,
                   .way_out = "a recording with fewer stored hashes (--hash-every)"});
  terms.push_back({.what = fmt::format("the world of {} and its definition", counts(def)),
                   .bytes = world_bytes_estimate(def) + world_build_bytes_estimate(def) +
                            definition_bytes_estimate(def),
                   .way_out = fewer(scene)});
  return terms;
}

void check_memory(std::string_view command, const std::string& file,
                  std::span<const MemoryTerm> terms) {
  check_command_memory(fmt::format("{} {}", command, file), terms);
}

}  // namespace fixstep::cli
