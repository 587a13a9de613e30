// fixstep replay: re-simulate a recording headless and verify every stored state hash; and the
// helpers `render --replay` shares with it (the recording's world, its verification, the flags
// that cannot go with it).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <stdexcept>

#include "command_memory.hpp"
#include "command_phase.hpp"
#include "commands.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
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

std::string replay_flag_conflict(const SceneOptions& o) {
  const char* flag = o.dt              ? "--dt"
                     : o.integrator    ? "--integrator"
                     : o.precision     ? "--precision"
                     : o.substeps      ? "--substeps"
                     : o.damping_split ? "--damping-split"
                                       : nullptr;
  if (!flag) return {};
  return fmt::format(
      "{} cannot be used with --replay: a recording replays the world it was recorded with, at "
      "its recorded dt, integrator, precision, substeps and damping split (another would "
      "diverge from its first stored hash); render the scene without --replay to try other "
      "settings",
      flag);
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

namespace {

/// The scene a recording carries (Recording::scene_text), parsed. Its file name is the
/// recording's label for it, so that the summary names the scene as the recorded run did. A
/// text that does not load makes the recording a bad one (RecordingError corrupt), as does a
/// world that is not the recorded one (checked by scene_for_recording).
Scene embedded_scene(const Recording& rec, const std::string& recording_file) {
  try {
    Scene scene =
        parse_scene(rec.scene_text, fmt::format("{} (embedded in {})", rec.scene, recording_file));
    scene.file = rec.scene;
    return scene;
  } catch (const SceneError& e) {
    throw RecordingError(RecordingError::Kind::corrupt, recording_file, 0, "scene_text",
                         fmt::format("the scene it carries does not load: {}", e.what()));
  }
}

/// The scene file a recording without scene_text names, loaded (found as recorded_scene says).
Scene named_scene(const Recording& rec, const std::string& recording_file) {
  const std::string file = recorded_scene(rec, recording_file);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    throw std::runtime_error(fmt::format(
        "{}: the recording's scene {} is not there (neither relative to the current directory "
        "nor beside the recording), and the recording does not carry it ({}); give it with "
        "--scene FILE",
        recording_file, rec.scene,
        rec.version < 3 ? "a recording made before format version 3"
                        : "the program that made it recorded none"));
  }
  return load_scene(file);
}

}  // namespace

Scene scene_for_recording(const Recording& rec, const std::string& recording_file,
                          const std::optional<std::string>& scene_file, bool quiet) {
  check_physics_only(rec, recording_file);
  const bool embedded = !scene_file && !rec.scene_text.empty();
  if (scene_file && !rec.scene_text.empty() && !quiet) {
    std::fprintf(stderr,
                 "note: %s carries the scene it was recorded with (%s); replaying with %s, "
                 "given on the command line, instead\n",
                 recording_file.c_str(), rec.scene.c_str(), scene_file->c_str());
  }
  Scene scene = scene_file ? load_scene(*scene_file)
                : embedded ? embedded_scene(rec, recording_file)
                           : named_scene(rec, recording_file);
  if (!quiet) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  scene.def.precision = rec.settings.precision;
  scene.def.settings.dt = rec.settings.dt;
  scene.def.settings.integrator = rec.settings.integrator;
  scene.def.settings.substeps = rec.settings.substeps;
  if (rec.settings.damping_split) scene.def.settings.damping_split = *rec.settings.damping_split;
  scene.def.settings.seeding = rec.settings.seeding;  // the recording's version's seeding
  scene.def.allow_unstable = true;  // the recorded run ran: replay it whatever the guard says
  const WorldDef def = scene.def;
  const std::uint64_t actual = definition_hash(def);
  if (actual != rec.definition_hash && embedded) {
    throw RecordingError(
        RecordingError::Kind::corrupt, recording_file, 0, "scene_text",
        fmt::format("the scene it carries builds another world than the one recorded "
                    "(definition hash {}, recorded {}): the recording was edited, or its "
                    "program embedded another scene than it ran",
                    hex_hash(actual), hex_hash(rec.definition_hash)));
  }
  if (actual != rec.definition_hash) {
    throw RecordingError(
        RecordingError::Kind::scene_mismatch, scene.file, 0, "",
        fmt::format("the scene no longer matches the recording (made with {}): its bodies, "
                    "springs or planes changed (definition hash {}, recorded {}); replay with "
                    "the scene as it was recorded{}",
                    rec.scene, hex_hash(actual), hex_hash(rec.definition_hash),
                    rec.scene_text.empty() ? "" : " (without --scene: the recording carries it)"));
  }
  check_recorded_bodies(rec, def.bodies.size(), def.joints.size(), recording_file);
  return scene;
}

ReplayReport verify_recording(const Scene& scene, const Recording& rec, bool quiet) {
  World sim = World(scene.def);
  const WorkProgressLine shown(!quiet);
  return replay(sim, rec);
}

void report_divergence(const ReplayReport::Mismatch& m, const std::string& recording_file,
                       std::string_view written) {
  // Ticks count as in the summary's ticks=N: the state after N ticks (the input of the
  // recording's `tick N-1` line is the last it took).
  const std::string range =
      m.last_match + 1 < m.tick
          ? fmt::format("; the first differing tick is in {} .. {}", m.last_match + 1, m.tick)
          : std::string();
  std::fprintf(stderr,
               "fixstep: error: %s: replay diverged at tick %llu: state_hash %s recorded, %s "
               "replayed (the states matched at tick %llu%s); the recording was edited, or made "
               "by a build that steps differently%s\n",
               recording_file.c_str(), static_cast<unsigned long long>(m.tick),
               hex_hash(m.expected).c_str(), hex_hash(m.actual).c_str(),
               static_cast<unsigned long long>(m.last_match), range.c_str(),
               std::string(written).c_str());
}

int replay_command(const ReplayOptions& o) {
  set_phase("reading the recording");
  const Recording rec = read_recording(o.recording);
  set_phase("loading the scene");
  const Scene scene = scene_for_recording(rec, o.recording, o.scene, o.quiet);
  check_command_work(rec.ticks, tick_work(scene.def),
                     fmt::format("{}: end {}", o.recording, rec.ticks));
  check_memory("replay", o.recording, replay_memory(scene, rec));  // before the world is built
  set_phase("replaying the recording");
  const ReplayReport report = verify_recording(scene, rec, o.quiet);
  fmt::print("{}\n", describe(scene));
  if (const auto& m = report.mismatch) {
    report_divergence(*m, o.recording, "");
    return exit_replay_diverged;
  }
  fmt::print("verified {} hashes, ticks={} state_hash={}\n", report.verified, report.ticks,
             hex_hash(report.final_hash));
  return 0;
}

}  // namespace fixstep::cli
