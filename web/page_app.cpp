// The page's program (page_app.hpp): building the session, the interactive loop (as
// cli/view.cpp runs it in a window) and the report.
#include "page_app.hpp"

#include <emscripten/emscripten.h>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fixstep/app/scene_view_settings.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/scene/scene_stability.hpp>
#include <utility>

#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "overlay_card.hpp"
#include "page_dom.hpp"

namespace fixstep::web {

namespace {

/// Rewind keeps this much of the past, s of simulated time, in at most rewind_max_bytes of
/// states (`fixstep view` keeps 10 s in 512 MiB; a page has less memory).
constexpr double rewind_seconds = 10.0;
constexpr std::size_t rewind_max_bytes = std::size_t{128} << 20;

}  // namespace

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(scene_dir)) {
    if (entry.path().extension() == ".toml") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

PageApp::PageApp(PageOptions options)
    : o_(std::move(options)), scene_file_(fmt::format("{}/{}", scene_dir, o_.scene)) {
  list_scenes(shipped_scenes(), o_.game ? std::string() : o_.scene);
  if (o_.game) {
    game_ = std::make_unique<PageGame>(o_);
    return;
  }
  if (o_.replay) return;  // the session waits for the recording (recording_fetched)
  scene_ = load_scene(scene_file_);
  WorldDef def = scene_->def;
  try {
    start_session(std::move(def), o_.scene);  // World(def) checks it, as `fixstep run` does
  } catch (const UnstableDefinition& e) {
    throw located(*scene_, e);
  }
  if (o_.record)
    recorder_.emplace(session_->definition(), scene_file_, o_.hash_every, scene_->text);
  if (o_.frames || o_.ticks) return;
  session_->set_key_help(page_key_help);
  session_->set_show_controls(true);
  input_ = std::make_unique<PageInput>("#canvas", o_.width, o_.height);
  const World& sim = session_->simulation();
  rewind_ = RewindBuffer(rewind_capacity(rewind_seconds, sim.settings().dt,
                                         std::max<std::size_t>(sim.snapshot_bytes(), 1),
                                         rewind_max_bytes));
  rewind_.push(sim);
  const Renderer& r = session_->renderer();
  drag_ = PointerDrag(10.0 * r.camera().width / double(r.width()));  // picks within 10 px
}

PageApp::~PageApp() = default;

void PageApp::start_session(WorldDef def, const std::string& title) {
  SessionSettings settings{.width = o_.width, .height = o_.height, .title = title};
  if (scene_) {
    settings.view_center = scene_->view.center, settings.view_width = scene_->view.width;
    apply_scene_view_style(scene_->view, settings);  // background, grid, axes, scale bar, HUD
  }
  if (o_.overlay_card) overlay_card_style(settings);
  // A virtual clock is not clamped (as `fixstep render`): frames exactly 1/fps apart.
  settings.max_frame_time = std::max(settings.max_frame_time, 1.0 / o_.fps);
  session_ = std::make_unique<Session>(std::move(def), settings);
  show_text("renderer", session_->renderer().gl_renderer());
}

bool PageApp::frame(double now_ms) {
  if (game_) return !replay_stopped_ && game_->frame(now_ms);
  if (o_.frames) return frames_frame();
  if (o_.ticks) return ticks_frame(now_ms);
  if (o_.replay) return replay_frame();
  interactive_frame(now_ms);
  return true;
}

void PageApp::interactive_frame(double now_ms) {
  // The browser's clock: the time since the last animation frame (the loop clamps a stall).
  const double seconds = last_ms_ < 0.0 ? 0.0 : (now_ms - last_ms_) / 1000.0;
  last_ms_ = now_ms;
  Session& session = *session_;
  const Camera camera = session.renderer().camera();
  const PageEvents ev = input_->take();
  apply_loop_keys(ev, session.loop());
  if (ev.restart) session.restart(), rewind_.clear(), rewind_.push(session.simulation());
  feed(ev, sampler_, camera, o_.width, o_.height);
  sampler_.set_push(arrow_push(sampler_.held(), camera.width));
  if (ev.rewind) {
    // One tick back per frame while Backspace is held; ticks resume from there.
    if (const WorldSnapshot* past = rewind_.step_back()) session.restore(*past);
  } else {
    session.advance_with(seconds, [&](std::uint64_t tick, World& sim) {
      TickInput input = sampler_.sample(tick);
      drag_.apply(input, sim);
      sim.step(input);
      rewind_.push(sim);
    });
  }
  session.show_drag(sampler_.pointer(), drag_.body());
  draw();
  // What the input did, for a person and for tests/web/input_check.html.
  show_text("result",
            fmt::format("tick={} state_hash={} paused={} dragging={}", session.simulation().tick(),
                        hex_hash(session.simulation().state_hash()), int(session.loop().paused()),
                        int(drag_.body() != null_entity)));
}

void PageApp::draw() {
  Session& session = *session_;
  if (!o_.overlay_card) {
    session.draw();
    return;
  }
  overlay_card(card_, session.view().center, session.view().width / 6.0);
  session.draw(card_);
}

void PageApp::report() {
  const World& sim = session_->simulation();
  show_text("result", fmt::format("tick={} state_hash={}", sim.tick(), hex_hash(sim.state_hash())));
  show_text("summary", summary_line(sim, session_->initial_energy()));
  if (recorder_) show_text("recording", format_recording(recorder_->finish(sim)));
  set_title("fixstep: done");
}

}  // namespace fixstep::web
