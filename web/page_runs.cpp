// The page's headless runs (page_app.hpp): frames= and ticks= on a virtual clock, replay= of a
// fetched recording. Each reports what `fixstep render`, `fixstep run` or `fixstep replay`
// print, so that the browser tests compare the page with the native build.
#include <emscripten/emscripten.h>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fixstep/core/input.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <stdexcept>
#include <utility>

#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "page_app.hpp"
#include "page_dom.hpp"

namespace fixstep::web {

namespace {

/// ticks=: the ticks stepped per browser frame stop after this much time, ms, so that the page
/// stays responsive (the state does not depend on how the ticks are split into frames).
constexpr double ticks_budget_ms = 50.0;

}  // namespace

bool PageApp::frames_frame() {
  // `fixstep render --frames F --fps FPS`: frame 0 shows the initial state, frame f > 0 follows
  // 1/fps s of virtual time; every frame is drawn (trails sample once per drawn frame).
  Session& session = *session_;
  if (frames_done_ > 0) {
    session.advance_with(1.0 / o_.fps, [&](std::uint64_t tick, World& sim) {
      const TickInput input{.tick = tick};
      sim.step(input);
      if (recorder_) recorder_->record(input, sim);
    });
  }
  draw();
  ++frames_done_;
  if (frames_done_ < *o_.frames && !session.simulation().fault()) return true;
  report();
  return false;
}

bool PageApp::ticks_frame(double now_ms) {
  // `fixstep run --steps N`: N ticks with no input, in chunks of at most ticks_budget_ms.
  World& sim = session_->simulation();
  while (sim.tick() < *o_.ticks && !sim.fault()) {
    const TickInput input{.tick = sim.tick()};
    sim.step(input);
    if (recorder_) recorder_->record(input, sim);
    if (sim.tick() % 256 == 0 && emscripten_get_now() - now_ms > ticks_budget_ms) break;
  }
  if (sim.tick() < *o_.ticks && !sim.fault()) {
    show_text("result", fmt::format("running: tick {} of {}", sim.tick(), *o_.ticks));
    return true;
  }
  draw();
  report();
  return false;
}

void PageApp::script_fetched(const std::string& text) {
  if (game_) game_->script_fetched(text);
}

void PageApp::recording_fetched(std::string text) {
  if (game_) {
    game_->recording_fetched(text);
    return;
  }
  Recording rec = parse_recording(text, *o_.replay);
  if (std::find(page_game_names.begin(), page_game_names.end(), rec.rules_name) !=
      page_game_names.end()) {
    throw std::invalid_argument(fmt::format(
        "{}: recorded by the game {} (rules version {}): open it with game={}&replay={}",
        *o_.replay, rec.rules_name, rec.rules_version, rec.rules_name, *o_.replay));
  }
  check_physics_only(rec, *o_.replay);  // the scenes have no game's rules
  // A recording carries its scene (format version 3): the page loads that. An older one names
  // its scene as given to `fixstep run` (assets/scenes/NAME.toml); the page has the shipped
  // scenes under the same folder.
  scene_file_ =
      fmt::format("{}/{}", scene_dir, std::filesystem::path(rec.scene).filename().string());
  scene_ =
      rec.scene_text.empty()
          ? load_scene(scene_file_)
          : parse_scene(rec.scene_text, fmt::format("{} (embedded in {})", rec.scene, *o_.replay));
  WorldDef def = scene_->def;
  apply_settings(def, rec.settings);
  check_recorded_bodies(rec, def.bodies.size(), def.joints.size(), *o_.replay);
  check_command_work(rec.ticks, tick_work(def), fmt::format("{}: end {}", *o_.replay, rec.ticks));
  const ReplayReport r = replay(def, rec);  // throws scene_mismatch
  if (!show_replay_verdict(r)) {            // a recording that diverges is not played back
    replay_stopped_ = true;
    return;
  }
  o_.scene = std::filesystem::path(scene_file_).filename().string();
  start_session(std::move(def), o_.scene);
  recording_ = std::move(rec);
  set_title("fixstep: done");
}

void PageApp::recording_failed(const std::string& why) {
  replay_stopped_ = true;
  show_error(fmt::format("could not fetch the recording {}: {}", *o_.replay, why));
}

bool PageApp::replay_frame() {
  if (replay_stopped_) return false;
  if (!recording_) return true;  // still fetching
  // After the verdict: the recording played back on the canvas at its own pace (headless: its
  // last state at once), ending at its last tick.
  Session& session = *session_;
  const Recording& rec = *recording_;
  const double seconds = o_.headless ? double(rec.ticks) * rec.settings.dt : 1.0 / o_.fps;
  session.advance_with(seconds, [&](std::uint64_t tick, World& sim) {
    if (sim.tick() < rec.ticks) sim.step(rec.input_at(tick));
  });
  draw();
  return session.simulation().tick() < rec.ticks && !session.simulation().fault();
}

}  // namespace fixstep::web
