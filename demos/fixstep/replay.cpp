// fixstep replay: re-simulate a recording headless and verify every stored state hash; and the
// helpers `render --replay` shares with it.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fixstep/limits.hpp>
#include <stdexcept>

#include "commands.hpp"
#include "progress.hpp"

namespace fixstep::cli {

int exit_code(const RecordingError& error) {
  switch (error.kind()) {
    case RecordingError::Kind::scene_mismatch:
      return exit_scene_mismatch;
    case RecordingError::Kind::unsupported_version:
      return exit_unsupported_version;
    default:
      return exit_bad_recording;
  }
}

Scene scene_for_recording(const std::string& scene_file, const Recording& rec,
                          const std::string& recording_file, bool quiet) {
  Scene scene = load_scene(scene_file);
  if (!quiet) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  scene.precision = rec.settings.precision;
  scene.world.dt = rec.settings.dt;
  scene.world.integrator = rec.settings.integrator;
  scene.world.substeps = rec.settings.substeps;
  scene.allow_unstable = true;  // the recorded run ran: replay it whatever the guard says
  const WorldDef def = world_def(scene);
  const std::uint64_t actual = definition_hash(def);
  if (actual != rec.definition_hash) {
    throw RecordingError(
        RecordingError::Kind::scene_mismatch, scene_file, 0, "",
        fmt::format("the scene no longer matches the recording (made with {}): its bodies, "
                    "springs or planes changed (definition hash {}, recorded {}); replay with "
                    "the scene as it was recorded",
                    rec.scene, hex_hash(actual), hex_hash(rec.definition_hash)));
  }
  check_recorded_bodies(rec, def.bodies.size(), recording_file);
  return scene;
}

std::string recorded_scene(const Recording& rec, const std::string& recording_file) {
  const std::filesystem::path scene(rec.scene);
  std::error_code ec;
  if (scene.is_relative() && !std::filesystem::exists(scene, ec)) {
    const std::filesystem::path beside =
        std::filesystem::path(recording_file).parent_path() / scene;
    if (std::filesystem::exists(beside, ec)) return beside.string();
  }
  return rec.scene;
}

int replay_command(const ReplayOptions& o) {
  const Recording rec = read_recording(o.recording);
  const std::string scene_file = o.scene ? *o.scene : recorded_scene(rec, o.recording);
  std::error_code ec;
  if (!o.scene && !std::filesystem::exists(scene_file, ec)) {
    throw std::runtime_error(fmt::format(
        "{}: the recording's scene {} is not there (neither relative to the current directory "
        "nor beside the recording); give it with --scene FILE",
        o.recording, rec.scene));
  }
  const Scene scene = scene_for_recording(scene_file, rec, o.recording, o.quiet);
  check_command_work(rec.ticks, tick_work(scene.bodies, scene.links, scene.world),
                     fmt::format("{}: end {}", o.recording, rec.ticks));
  Simulation sim = make_simulation(checked_world_def(scene));
  const ReplayReport report = [&] {
    const WorkProgressLine shown(!o.quiet);
    return replay(sim, rec);
  }();
  fmt::print("{}\n", describe(scene));
  if (const auto& m = report.mismatch) {
    // Ticks count as in the summary's ticks=N: the state after N ticks (the input of the
    // recording's `tick N-1` line is the last it took).
    const std::string range =
        m->last_match + 1 < m->tick
            ? fmt::format("; the first differing tick is in {} .. {}", m->last_match + 1, m->tick)
            : std::string();
    std::fprintf(stderr,
                 "fixstep: error: replay diverged at tick %llu: state_hash %s recorded, %s "
                 "replayed (the states matched at tick %llu%s); the recording was edited, or "
                 "made by a build that steps differently\n",
                 static_cast<unsigned long long>(m->tick), hex_hash(m->expected).c_str(),
                 hex_hash(m->actual).c_str(), static_cast<unsigned long long>(m->last_match),
                 range.c_str());
    return exit_replay_diverged;
  }
  fmt::print("verified {} hashes, ticks={} state_hash={}\n", report.verified, report.ticks,
             hex_hash(report.final_hash));
  return 0;
}

}  // namespace fixstep::cli
