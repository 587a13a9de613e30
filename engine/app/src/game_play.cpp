// fixstep::app: a game being played live (fixstep/app/game_play.hpp).
#include "fixstep/app/game_play.hpp"

#include <cstdio>
#include <fixstep/core/stop_request.hpp>
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
/// Bytes short of max_recording_bytes at which a recording is finished: more than one tick's
/// lines (a tick's input with every body's input is far less).
constexpr std::size_t recording_margin = std::size_t{1} << 20;
}  // namespace

GamePlay::GamePlay(Level level, const Settings& settings, std::string record_file)
    : level_(std::move(level)),
      name_(settings.name),
      record_file_(std::move(record_file)),
      rules_version_(settings.rules_version),
      rules_before_step_(settings.rules_before_step),
      session_(level_.def, level_.view),
      game_(level_.game->clone()) {
  session_.set_show_energy(settings.show_energy);
  for (const StabilityFinding& w : session_.simulation().warnings()) {  // the guard's (World)
    std::fprintf(stderr, "warning: %s\n", w.message.c_str());
  }
  if (!record_file_.empty()) start_recording();
  game_->attach(session_.simulation());  // its pre_solve(), if any
}

void GamePlay::start_recording() {
  recorder_.reset();  // a restart's: its temporary file is removed
  recorded_ticks_ = 0;
  recorder_.emplace(session_.definition(), level_.scene_name, hash_every, record_file_,
                    level_.scene_text);
  recorder_->set_rules(rules_name_of(name_), rules_version_);
  initial_hash_ = session_.simulation().state_hash();
}

void GamePlay::advance(double seconds) {
  session_.advance_with(seconds, [&](std::uint64_t tick, World& world) {
    if (stop_requested() != 0) return;  // the run ends after this frame (the caller checks)
    if (script_) script_->feed(tick, sampler_);  // --input: the script plays
    TickInput input = sampler_.sample(tick);
    game_->prepare(input, world);
    if (rules_before_step_) game_->rules(world, input);
    world.step(input);
    if (!rules_before_step_) game_->rules(world, input);
    if (recorder_) record(input, world);
    last_ = input;
  });
}

void GamePlay::record(const TickInput& input, const World& world) {
  recorder_->record(input, world);
  // Near the most a recording may hold (max_recording_bytes, what --replay reads): the file is
  // finished here, whole, rather than refused at the end; the session plays on unrecorded.
  if (recorder_->bytes() + recording_margin > max_recording_bytes) {
    const std::uint64_t ticks = recorder_->ticks();
    recorder_->finish(world);
    recorder_.reset();
    std::fprintf(stderr,
                 "%s: warning: the recording reached %zu MiB, the most a recording may hold, at "
                 "tick %llu: %s is written up to there, the rest of the session is not recorded\n",
                 name_.c_str(), max_recording_bytes >> 20, static_cast<unsigned long long>(ticks),
                 record_file_.c_str());
    recorded_ticks_ = ticks;
  }
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
  game_->attach(session_.simulation());
  sampler_ = {};
  last_ = {};
  if (script_) script_->restart();
  if (!record_file_.empty()) start_recording();
}

void GamePlay::finish() {
  finish_stopped(false);
}

void GamePlay::finish_stopped(bool torn) {
  const World& world = session_.simulation();
  if (!torn) {  // a torn state is no tick's: it has no summary
    std::printf("%s\n", summary_line(world, session_.initial_energy()).c_str());
    if (const std::string s = game_->summary(); !s.empty()) std::printf("%s\n", s.c_str());
  }
  if (record_file_.empty()) return;
  std::uint64_t ticks = recorded_ticks_;  // a recording finished at its limit
  if (recorder_) {
    ticks = recorder_->ticks();
    if (torn) {
      recorder_->finish_at_last_hash(initial_hash_);  // every tick completed is hashed
    } else {
      recorder_->finish(world);
    }
    recorder_.reset();
  }
  std::printf("recorded %llu ticks to %s (check it: %s --replay %s)\n",
              static_cast<unsigned long long>(ticks), record_file_.c_str(), name_.c_str(),
              record_file_.c_str());
}

}  // namespace fixstep::app::detail
