// The page's game mode (page_game.hpp): the games, their live play (interactive and frames=)
// as app::run's play_window and play_headless run them, and their recordings verified and
// played back as app::run's --replay does.
#include "page_game.hpp"

#include <emscripten/emscripten.h>
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "airhockey_app.hpp"
#include "fixstep/app/key_bindings.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "page_dom.hpp"
#include "peggle_app.hpp"
#include "pinball_app.hpp"
#include "slingshot_app.hpp"
#include "stacker_app.hpp"

namespace fixstep::web {

namespace {

/// frames= and a headless replay: the frames run per browser frame stop after this much time,
/// ms, so that the page stays responsive (the state does not depend on the split).
constexpr double game_budget_ms = 50.0;
/// app::run's virtual clock (headless frames, a drawn replay), frames/s.
constexpr double game_fps = 60.0;

/// The game of page_game_names named `name`, before its setup(), and its app::Settings.
std::pair<std::unique_ptr<const app::detail::AnyGame>, app::Settings> make_game(
    const std::string& name) {
  using app::detail::GameModel;
  if (name == "airhockey") {  // single-player: the computer plays the right mallet (prepare())
    return {std::make_unique<GameModel<airhockey::AirHockey>>(airhockey::AirHockey{}),
            airhockey::app_settings()};
  }
  if (name == "peggle") {
    return {std::make_unique<GameModel<peggle::Peggle>>(peggle::Peggle{}), peggle::app_settings()};
  }
  if (name == "pinball") {
    return {std::make_unique<GameModel<pinball::Pinball>>(pinball::Pinball{}),
            pinball::app_settings()};
  }
  if (name == "slingshot") {
    return {std::make_unique<GameModel<slingshot::Slingshot>>(slingshot::Slingshot{}),
            slingshot::app_settings()};
  }
  if (name == "stacker") {
    return {std::make_unique<GameModel<stacker::Stacker>>(stacker::Stacker{}),
            stacker::app_settings()};
  }
  throw std::invalid_argument(fmt::format("game={}: not a game of the page", name));
}

bool is_page_game(const std::string& name) {
  return std::find(page_game_names.begin(), page_game_names.end(), name) != page_game_names.end();
}

}  // namespace

PageGame::PageGame(PageOptions o) : o_(std::move(o)) {
  std::tie(prototype_, settings_) = make_game(*o_.game);
  if (o_.size_given) {
    settings_.width = o_.width, settings_.height = o_.height;
  } else {  // the program's size (app::Settings), as `NAME --frames` draws
    o_.width = settings_.width, o_.height = settings_.height;
  }
  if (o_.replay) return;  // the level waits for the recording (recording_fetched)
  play_ = std::make_unique<app::detail::GamePlay>(
      app::detail::load_level(*prototype_, settings_, settings_.scene_file), settings_, "");
  show_text("renderer", play_->session().renderer().gl_renderer());
  set_title(fmt::format("fixstep: {}", settings_.name));
  if (o_.frames) return;
  // As app::run's window, but for quit (a page does not quit).
  InputMap map = app::detail::game_input_map(settings_);
  const std::string loop_keys = map.loop_help(false);
  hint_ = settings_.controls.empty() ? loop_keys : settings_.controls + "\n" + loop_keys;
  show_text("help", hint_);
  input_ = std::make_unique<PageInput>("#canvas", o_.width, o_.height);
  input_->set_input_map(std::move(map));
}

PageGame::~PageGame() = default;

bool PageGame::frame(double now_ms) {
  if (o_.frames) return frames_frame(now_ms);
  if (o_.replay) return replay_frame(now_ms);
  interactive_frame(now_ms);
  return true;
}

void PageGame::interactive_frame(double now_ms) {
  // app::run's play_window on the browser's clock: the loop's keys, restart, the pointer and
  // buttons fed to the sampler, the game's input(), the frame's ticks, the drawing.
  const double seconds = last_ms_ < 0.0 ? 0.0 : (now_ms - last_ms_) / 1000.0;
  last_ms_ = now_ms;
  const PageEvents ev = input_->take();
  Session& session = play_->session();
  apply_loop_keys(ev, session.loop());  // space pause, '.' one tick, +/- speed
  if (ev.restart) play_->restart();
  feed(ev, play_->sampler(), session.renderer().camera(), o_.width, o_.height);
  play_->game().input(ev, session.simulation(), play_->sampler());
  play_->advance(seconds);
  play_->draw(hint_);
  const World& sim = session.simulation();
  show_text("result", fmt::format("tick={} state_hash={}", sim.tick(), hex_hash(sim.state_hash())));
  show_text("summary", play_->game().summary());
}

bool PageGame::frames_frame(double now_ms) {
  // app::run's play_headless: frame 0 the level as set up, each later frame the autopilot's
  // input and 1/60 s of virtual time; only the last frame is drawn (trails sample every tick).
  const VirtualClock clock(game_fps);
  const auto frames = static_cast<std::int64_t>(*o_.frames);
  if (o_.input && !script_) {
    show_text("result", "fetching the input script");
    return true;
  }
  while (frames_done_ < frames) {
    if (frames_done_ > 0) {
      if (!script_) {
        play_->game().autopilot(frames_done_, play_->session().simulation(), play_->sampler());
      }
      play_->advance(clock.frame_seconds());
    }
    ++frames_done_;
    if (emscripten_get_now() - now_ms > game_budget_ms) break;
  }
  if (frames_done_ < frames) {
    show_text("result", fmt::format("running: frame {} of {}", frames_done_, frames));
    return true;
  }
  play_->draw(script_ ? "input script" : "autopilot");
  report();
  return false;
}

void PageGame::script_fetched(const std::string& text) {
  const app::detail::Level level =
      app::detail::load_level(*prototype_, settings_, settings_.scene_file);
  script_ = parse_input_script(text, *o_.input, level.def.bodies,
                               app::detail::script_names(app::detail::game_input_map(settings_)));
  play_->play_script(*script_);
}

void PageGame::show_summary(const World& world, double initial_energy,
                            const app::detail::AnyGame& game) {
  const std::string line = summary_line(world, initial_energy), s = game.summary();
  show_text("summary", s.empty() ? line : line + "\n" + s);
}

void PageGame::report() {
  const World& sim = play_->session().simulation();
  show_text("result", fmt::format("tick={} state_hash={}", sim.tick(), hex_hash(sim.state_hash())));
  show_summary(sim, play_->session().initial_energy(), play_->game());
  set_title("fixstep: done");
}

void PageGame::recording_fetched(const std::string& text) {
  const std::string& file = *o_.replay;
  Recording rec = parse_recording(text, file);
  // As `NAME --replay`: a recording of other rules is refused, naming both. The page refuses a
  // recording without rules too (a scene's, or a game's from before rules were named).
  const std::string rules = app::detail::rules_name_of(settings_.name);
  if (rec.rules_name.empty()) {
    throw std::invalid_argument(
        fmt::format("{} is a recording of the scene {} without a game's rules: open it without "
                    "game= (replay={})",
                    file, rec.scene, file));
  }
  if (rec.rules_name != rules || rec.rules_version != settings_.rules_version) {
    throw std::invalid_argument(fmt::format(
        "{} needs the rules {} version {}, and game={} has {} version {}: {}", file, rec.rules_name,
        rec.rules_version, *o_.game, rules, settings_.rules_version,
        rec.rules_name != rules && is_page_game(rec.rules_name)
            ? fmt::format("open it with game={}&replay={}", rec.rules_name, file)
            : std::string("replay it with the program (and version) that recorded it")));
  }
  app::detail::GameReplay r = app::detail::replay_game(*prototype_, settings_, rec, file, {});
  if (!show_replay_verdict(r.report)) {  // a recording that diverges is not played back
    replay_stopped_ = true;
    return;
  }
  show_summary(*r.world, r.initial_energy, *r.game);
  session_ = std::make_unique<Session>(r.level.def, r.level.view);
  session_->set_show_energy(settings_.show_energy);
  show_text("renderer", session_->renderer().gl_renderer());
  game_ = r.level.game->clone();
  replay_rules_ = app::detail::game_rules(*game_, settings_.rules_before_step);
  recording_ = std::move(rec);
  set_title("fixstep: done");
}

bool PageGame::replay_frame(double now_ms) {
  if (replay_stopped_) return false;
  if (!recording_) return true;  // still fetching
  // After the verdict: the recording played back as app::run's --replay draws it, at 60 frames
  // of virtual time a second (headless: every frame at once, the last one drawn), ending at its
  // last tick.
  Session& session = *session_;
  const Recording& rec = *recording_;
  const VirtualClock clock(game_fps);
  const auto done = [&] { return session.simulation().tick() >= rec.ticks; };
  do {
    session.advance_with(clock.frame_seconds(), [&](std::uint64_t t, World& world) {
      if (t >= rec.ticks) return;
      last_ = rec.input_at(t);
      replay_rules_.tick(world, last_);
    });
  } while (o_.headless && !done() && emscripten_get_now() - now_ms < game_budget_ms);
  if (!o_.headless || done()) {
    session.show_drag(last_.pointer, last_.drag_body);
    app::detail::draw_game(session, *game_, overlay_, {});
  }
  return !done();
}

}  // namespace fixstep::web
