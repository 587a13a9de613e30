// fixstep diff A.rec B.rec: where two recordings first differ (fixstep/core/recording_diff.hpp):
// their worlds, inputs and stored hashes, and, for recordings of physics alone, both replayed
// side by side, naming the first tick, body and field where the states differ and which
// recording's own hashes this build reproduces.
#include <fmt/format.h>

#include <cstdio>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/recording_diff.hpp>
#include <fixstep/io/command_limits.hpp>
#include <fixstep/io/state_file.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "command_memory.hpp"
#include "command_phase.hpp"
#include "commands.hpp"
#include "progress.hpp"

namespace fixstep::cli {

namespace {

/// The report on standard output; a difference also on standard error (as an error: what the
/// exit status says), the verdict's text after the file names.
int print_report(const RecordingDiff& diff, const DiffOptions& o) {
  const std::vector<std::string> lines = describe(diff, o.a, o.b);
  for (const std::string& line : lines) fmt::print("{}\n", line);
  if (diff.identical()) return 0;
  // Two peers' desync files: their states of the first differing tick name the body when the
  // recordings replay alike (the divergence happened on a peer, not in its inputs).
  if (const std::optional<StatesBeside> states = compare_states_beside(o.a, o.b)) {
    fmt::print("{}\n", states->text);
    if (!states->read) std::fprintf(stderr, "fixstep: warning: %s\n", states->text.c_str());
  }
  const std::string_view verdict =
      std::string_view(lines.back()).substr(lines.back().find(' ') + 1);
  std::fprintf(stderr, "fixstep: error: %s and %s differ: %.*s\n", o.a.c_str(), o.b.c_str(),
               static_cast<int>(verdict.size()), verdict.data());
  return diff.world_difference.empty() ? exit_recordings_differ : exit_scene_mismatch;
}

/// Recordings made with a game's rules: the bodies need the game's replay.
int compare_only(const Recording& a, const Recording& b, const DiffOptions& o) {
  const RecordingDiff diff = compare_recordings(a, b);
  const std::string& rules = (a.rules_name.empty() ? b : a).rules_name;
  std::fprintf(stderr,
               "note: %s needs the game rules %s, which fixstep does not have: its inputs and "
               "stored hashes are compared, its states are not replayed (run the game with "
               "--diff %s %s for the bodies)\n",
               (a.rules_name.empty() ? o.b : o.a).c_str(), rules.c_str(), o.a.c_str(), o.b.c_str());
  return print_report(diff, o);
}

}  // namespace

int diff_command(const DiffOptions& o) {
  set_phase("reading the recordings");
  const Recording a = read_recording(o.a);
  const Recording b = read_recording(o.b);
  if (!a.rules_name.empty() || !b.rules_name.empty()) return compare_only(a, b, o);
  const RecordingDiff recorded = compare_recordings(a, b);
  if (!recorded.world_difference.empty()) return print_report(recorded, o);
  set_phase("loading the scenes");
  const Scene scene_a = scene_for_recording(a, o.a, std::nullopt, o.quiet);
  const Scene scene_b = scene_for_recording(b, o.b, std::nullopt, o.quiet);
  const std::uint64_t end = replay_end(recorded);
  check_command_work(end, tick_work(scene_a.def) + tick_work(scene_b.def),
                     fmt::format("{} and {}: {} ticks each, side by side", o.a, o.b, end));
  std::vector<MemoryTerm> memory = replay_memory(scene_a, a);
  const std::vector<MemoryTerm> memory_b = replay_memory(scene_b, b);
  memory.insert(memory.end(), memory_b.begin(), memory_b.end());
  check_memory("diff", o.a, memory);  // before the worlds are built
  set_phase("replaying the recordings side by side");
  const StopOnSignal signals;  // SIGINT / SIGTERM: the tick in progress stops (StopRequested)
  RecordingDiff diff;
  {
    const WorkProgressLine shown(!o.quiet);
    diff = diff_recordings(scene_a.def, a, scene_b.def, b);
  }
  return print_report(diff, o);
}

}  // namespace fixstep::cli
