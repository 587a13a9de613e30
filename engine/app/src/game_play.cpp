// fixstep::app: a game being played live (fixstep/app/game_play.hpp).
#include "fixstep/app/game_play.hpp"

#include <cstdio>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/io/summary.hpp>
#include <string_view>
#include <utility>

#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep::app::detail {

namespace {
/// A recording stores the state hash after every tick, so a replay names the exact first tick
/// that differs (about 25 bytes a tick).
constexpr std::uint64_t hash_every = 1;
}  // namespace

GamePlay::GamePlay(Level level, const Settings& settings, std::string record_file)
    : level_(std::move(level)),
      name_(settings.name),
      record_file_(std::move(record_file)),
      rules_version_(settings.rules_version),
      session_(level_.def, level_.view),
      game_(level_.game->clone()) {
  session_.set_show_energy(settings.show_energy);
  for (const StabilityFinding& w : session_.simulation().warnings()) {  // the guard's (World)
    std::fprintf(stderr, "warning: %s\n", w.message.c_str());
  }
  if (!record_file_.empty()) start_recording();
}

void GamePlay::start_recording() {
  recorder_.emplace(session_.definition(), level_.scene_name, hash_every, level_.scene_text);
  recorder_->set_rules(rules_name_of(name_), rules_version_);
}

void GamePlay::advance(double seconds) {
  session_.advance_with(seconds, [&](std::uint64_t tick, World& world) {
    TickInput input = sampler_.sample(tick);
    game_->prepare(input, world);
    world.step(input);
    game_->rules(world, input);
    if (recorder_) recorder_->record(input, world);
    last_ = input;
  });
}

void GamePlay::draw(std::string_view hint) {
  session_.show_drag(last_.pointer, last_.drag_body);  // the pointer's spring, if it drags
  draw_game(session_, *game_, overlay_, hint);
}

void draw_game(Session& session, const AnyGame& game, Overlay& overlay, std::string_view hint) {
  session.prepare_frame();
  overlay.clear();
  overlay.bind(&session);
  try {
    game.draw(overlay);
  } catch (...) {
    overlay.bind(nullptr);
    throw;
  }
  overlay.bind(nullptr);
  while (!hint.empty()) {  // a line per '\n'
    const std::size_t end = hint.find('\n');
    overlay.text(hint.substr(0, end));
    hint.remove_prefix(end == std::string_view::npos ? hint.size() : end + 1);
  }
  session.set_status_lines(overlay.lines());
  session.draw(overlay);
}

void GamePlay::restart() {
  session_.restart();
  game_ = level_.game->clone();
  sampler_ = {};
  last_ = {};
  if (recorder_) start_recording();
}

void GamePlay::finish() {
  const World& world = session_.simulation();
  std::printf("%s\n", summary_line(world, session_.initial_energy()).c_str());
  if (const std::string s = game_->summary(); !s.empty()) std::printf("%s\n", s.c_str());
  if (!recorder_) return;
  write_recording(record_file_, recorder_->finish(world));
  std::printf("recorded %llu ticks to %s (check it: %s --replay %s)\n",
              static_cast<unsigned long long>(world.tick()), record_file_.c_str(), name_.c_str(),
              record_file_.c_str());
}

}  // namespace fixstep::app::detail
