// fixstep::app: --diff A.rec B.rec, where two recordings of the game first differ, both replayed
// side by side with the game's rules (fixstep/core/recording_diff.hpp), so the body is named.
#include <fmt/format.h>

#include <cstdio>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/recording_diff.hpp>
#include <fixstep/io/command_limits.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/io/state_file.hpp>
#include <fixstep/io/summary.hpp>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app_modes.hpp"
#include "fixstep/app/game_level.hpp"

namespace fixstep::app::detail {

namespace {

/// Throws std::runtime_error when `rec` names rules other than this game's (a recording from
/// before rules were named is taken: its hashes decide).
void check_rules(const Settings& settings, const Recording& rec, const std::string& file) {
  const std::string rules = rules_name_of(settings.name);
  if (rec.rules_name.empty() ||
      (rec.rules_name == rules && rec.rules_version == settings.rules_version)) {
    return;
  }
  throw std::runtime_error(fmt::format(
      "{} needs the rules {} version {}, and this program has {} version {}: compare it with the "
      "program (and version) that recorded it",
      file, rec.rules_name, rec.rules_version, rules, settings.rules_version));
}

/// The level `rec` was recorded on, checked against its definition hash.
Level level_of(const AnyGame& game, const Settings& settings, const Recording& rec,
               const std::string& file, const Options& o) {
  Level level = replay_level(game, settings, rec, o.scene);
  if (definition_hash(level.def) != rec.definition_hash) {
    throw std::runtime_error(fmt::format("{} was recorded on another level (hash {}, this one {})",
                                         file, hex_hash(rec.definition_hash),
                                         hex_hash(definition_hash(level.def))));
  }
  return level;
}

int report(const Settings& settings, const RecordingDiff& diff, const Options& o) {
  const std::vector<std::string> lines = describe(diff, o.diff[0], o.diff[1]);
  for (const std::string& line : lines) std::printf("%s\n", line.c_str());
  if (diff.identical()) return 0;
  // Two peers' desync files: their states of the first differing tick name the body when the
  // recordings replay alike (the divergence happened on a peer, not in its inputs).
  if (const std::optional<StatesBeside> states = compare_states_beside(o.diff[0], o.diff[1])) {
    std::printf("%s\n", states->text.c_str());
    if (!states->read) {
      std::fprintf(stderr, "%s: warning: %s\n", settings.name.c_str(), states->text.c_str());
    }
  }
  std::fprintf(stderr, "%s: error: %s and %s differ: %s\n", settings.name.c_str(),
               o.diff[0].c_str(), o.diff[1].c_str(),
               lines.back().substr(lines.back().find(' ') + 1).c_str());
  return diff.world_difference.empty() ? exit_diverged : exit_error;
}

}  // namespace

int diff_files(const AnyGame& prototype, const Settings& settings, const Options& o) {
  const std::string &file_a = o.diff[0], &file_b = o.diff[1];
  const Recording a = read_recording(file_a);  // throws RecordingError naming the file
  const Recording b = read_recording(file_b);
  check_rules(settings, a, file_a);
  check_rules(settings, b, file_b);
  const RecordingDiff recorded = compare_recordings(a, b);
  if (!recorded.world_difference.empty()) return report(settings, recorded, o);
  const Level level_a = level_of(prototype, settings, a, file_a, o);
  const Level level_b = level_of(prototype, settings, b, file_b, o);
  const std::uint64_t end = replay_end(recorded);
  check_command_work(end, tick_work(level_a.def) + tick_work(level_b.def),
                     fmt::format("--diff {} {}: {} ticks each, side by side", file_a, file_b, end));
  const std::unique_ptr<AnyGame> game_a = level_a.game->clone(), game_b = level_b.game->clone();
  const RecordingDiff diff = diff_recordings(level_a.def, a, level_b.def, b,
                                             game_rules(*game_a, settings.rules_before_step),
                                             game_rules(*game_b, settings.rules_before_step));
  return report(settings, diff, o);
}

}  // namespace fixstep::app::detail
