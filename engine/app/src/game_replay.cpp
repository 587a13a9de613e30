// fixstep::app: a recording replayed with a game's rules and verified
// (fixstep/app/game_level.hpp).
#include <fmt/format.h>

#include <stdexcept>

#include "fixstep/app/game_level.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/summary.hpp"

namespace fixstep::app::detail {

GameReplay replay_game(const AnyGame& game, const Settings& settings, const Recording& rec,
                       const std::string& file, const std::optional<std::string>& scene) {
  GameReplay r{.level = replay_level(game, settings, rec, scene)};
  if (definition_hash(r.level.def) != rec.definition_hash) {
    throw std::runtime_error(fmt::format("{} was recorded on another level (hash {}, this one {})",
                                         file, hex_hash(rec.definition_hash),
                                         hex_hash(definition_hash(r.level.def))));
  }
  check_command_work(rec.ticks, tick_work(r.level.def),  // before a tick is stepped
                     fmt::format("{}: end {}", file, rec.ticks));
  r.world = std::make_unique<World>(r.level.def);
  r.initial_energy = r.world->energy().total();
  r.game = r.level.game->clone();
  r.report = replay(*r.world, rec, game_rules(*r.game, settings.rules_before_step));
  return r;
}

}  // namespace fixstep::app::detail
