// `fixstep view`: the Session's frames presented in an SDL2 window, driven by the real clock;
// the world is rebuilt when its scene file is saved (hot reload, scene_watch.hpp), on a thread
// of its own (scene_load.hpp) while the window keeps showing the world before the save.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fixstep/app/session.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/pointer_drag.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/rewind.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <fixstep/scene/scene_stability.hpp>
#include <fixstep/window/window.hpp>
#include <functional>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "command_memory.hpp"
#include "command_phase.hpp"
#include "commands.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "scene_load.hpp"
#include "scene_watch.hpp"
#include "view_rewind.hpp"

namespace fixstep::cli {

Window open_window(const std::string& title, int width, int height, std::string_view headless) {
  try {
    return Window(title, width, height);
  } catch (const WindowError& e) {
    const std::string_view fault = e.what();
    throw WindowError(fmt::format("{}{} Capture frames headless instead: {}", fault,
                                  fault.ends_with('.') ? "" : ".", headless));
  }
}

namespace {

/// The world a window shows: the scene it was built from, its session and rewind buffer.
struct ShownWorld {
  Scene scene;
  std::unique_ptr<Session> session;
  RewindBuffer rewind{1};
  PointerDrag drag{0.0};  ///< picks within 10 pixels; holds a body of this world only
};

/// Starts showing `session`'s world (from `scene`): the key help in the HUD, rewind from tick 0
/// (as `plan` says). The previous world's rewind states are freed before the new buffer is made.
void show(ShownWorld& shown, Scene scene, std::unique_ptr<Session> session,
          const RewindPlan& plan) {
  session->set_show_controls(true);
  shown.scene = std::move(scene);
  shown.session = std::move(session);
  shown.rewind = RewindBuffer(1);
  shown.rewind = make_rewind(plan);
  shown.rewind.push(shown.session->simulation());
  const Renderer& r = shown.session->renderer();
  shown.drag = PointerDrag(10.0 * r.camera().width / double(r.width()));
}

/// The --fps a frame of settings.max_frame_time s stands for, if longer than the clamp.
std::optional<double> fps_of(const SessionSettings& settings) {
  return settings.max_frame_time > SessionSettings{}.max_frame_time
             ? std::optional(1.0 / settings.max_frame_time)
             : std::nullopt;
}

/// The memory check of a load (view_memory) in a width x height window; on a reload, with the
/// world shown meanwhile (`shown`, kept until the new one is ready).
std::function<void(const Scene&)> memory_check(int width, int height, const Scene* shown) {
  std::vector<MemoryTerm> kept;
  if (shown) {
    kept.push_back({.what = fmt::format("the world shown while the new one loads"),
                    .bytes = total_bytes(view_memory(*shown, width, height)) - program_base_bytes,
                    .way_out = "fewer bodies or links"});
  }
  return [width, height, kept](const Scene& scene) {
    std::vector<MemoryTerm> terms = view_memory(scene, width, height);
    terms.insert(terms.end(), kept.begin(), kept.end());
    check_memory("view", scene.file, terms);
  };
}

/// The load's warnings on standard error, unless --quiet.
void print_warnings(const LoadedWorld& world, const SceneOptions& o) {
  if (o.quiet) return;
  for (const std::string& w : world.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

/// The first world, loaded on a thread of its own while this one shows the load's progress on
/// a terminal ("loading s.toml: stability guard: iteration 310/10000 (3 %), 4.2 s"). SIGINT
/// ends the process at once, as before any window opened.
LoadedWorld load_first(const SceneOptions& o, int width, int height) {
  BackgroundLoad load(o, memory_check(width, height, nullptr));
  StatusLine line(!o.quiet);
  while (!load.ready()) {
    line.show(fmt::format("loading {}: {}", o.scene, describe(load.status())));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  line.finish();
  LoadedWorld world = load.take();
  print_warnings(world, o);
  return world;
}

/// A hot reload in progress: the load of the file as saved, on its own thread. A save seen while
/// a load runs stops that load and starts another once it has ended.
struct Reload {
  std::optional<BackgroundLoad> load;
  bool again = false;  ///< a newer save was seen: load the file again when `load` ends
};

/// Shows `loaded` in place of `shown`'s world. The new world starts at tick 0 with no trails;
/// kept are the camera (unless the edit changed the scene's [view]: then the new [view], or the
/// fit of the new world without one, applies), the time scale and the pause (a world the
/// runtime guard stopped gives way to one that runs). Throws, leaving `shown` untouched, when
/// a frame of the new world would take too many ticks (check_frame_ticks).
void swap_in(ShownWorld& shown, LoadedWorld loaded, const SceneOptions& o) {
  const Session& old = *shown.session;
  const Renderer& r = old.renderer();
  const Scene& scene = loaded.scene;
  SessionSettings settings = session_settings(scene, r.width(), r.height());
  settings.max_frame_time = shown.session->loop().settings().max_frame_time;  // as --fps set it
  check_frame_ticks(settings.max_frame_time, scene.def.settings.dt, fps_of(settings),
                    dt_source(o, scene), dt_fix(o));
  check_frame_ticks(settings.max_frame_time, scene.def.settings.dt, fps_of(settings),
                    dt_source(o, scene), dt_fix(o));
  if (scene.view.center == shown.scene.view.center && scene.view.width == shown.scene.view.width) {
    settings.view_center = r.camera().center;
    settings.view_width = r.camera().width;
  }
  auto next = std::make_unique<Session>(std::move(loaded.def), std::move(loaded.sim), settings);
  FixedStepLoop& loop = shown.session->loop();
  next->loop().set_time_scale(loop.time_scale());
  next->loop().set_paused(loop.paused() && !old.simulation().fault());
  show(shown, std::move(loaded.scene), std::move(next), loaded.plan);
}

/// What the window does when the scene file was saved: starts loading it (or, while a load
/// runs, stops that one to load the newer save after it), or, while recording, keeps the world
/// and says why, in the HUD and once on standard error.
void on_scene_saved(ShownWorld& shown, Reload& reload, const ViewOptions& o, bool recording) {
  Session& s = *shown.session;
  if (recording) {
    const std::string& file = o.scene.scene;
    std::fprintf(stderr,
                 "fixstep: %s changed: not reloaded while recording (--record); the session "
                 "keeps the world the recording started with\n",
                 file.c_str());
    s.set_status_lines(reload_error_lines(
        "NOT RELOADED while recording (--record)",
        fmt::format("{} changed on disk; quit and view it again to see the edit", file),
        s.renderer().width(), s.renderer().hud_text_scale()));
    return;
  }
  if (reload.load) {
    reload.load->cancel();
    reload.again = true;
    return;
  }
  reload.load.emplace(o.scene,
                      memory_check(s.renderer().width(), s.renderer().height(), &shown.scene));
  fmt::print(
      "loading {} (at tick {}): the window shows the world before the save until it is "
      "ready\n",
      o.scene.scene, s.simulation().tick());
  std::fflush(stdout);
}

/// Each frame while a reload runs: its progress in the HUD; once it has ended, the new world
/// shown (said on standard output), or the located error of a bad edit in the HUD and once on
/// standard error while the last good world keeps running.
void follow_reload(ShownWorld& shown, Reload& reload, const ViewOptions& o) {
  Session& s = *shown.session;
  const std::string& file = o.scene.scene;
  const int width = s.renderer().width();
  const float scale = s.renderer().hud_text_scale();
  if (!reload.load->ready()) {
    s.set_status_lines(loading_lines(file, describe(reload.load->status()), width, scale));
    return;
  }
  if (reload.again) {  // a newer save stopped this load (or finds what it made stale)
    std::fprintf(stderr, "fixstep: %s was saved again while it loaded: that load was %s\n",
                 file.c_str(), reload.load->stop() ? "dropped" : "stopped");
    reload.load.reset();
    reload.load.emplace(o.scene, memory_check(width, s.renderer().height(), &shown.scene));
    reload.again = false;
    return;
  }
  const std::uint64_t tick = s.simulation().tick();
  try {
    LoadedWorld loaded = reload.load->take();
    print_warnings(loaded, o.scene);
    s.set_status_lines({});
    swap_in(shown, std::move(loaded), o.scene);
  } catch (const std::exception& e) {
    reload.load.reset();
    // A std::bad_alloc past the memory check (less memory free than the estimate needs).
    const std::string why = dynamic_cast<const std::bad_alloc*>(&e) != nullptr
                                ? "out of memory (std::bad_alloc) while loading it"
                                : std::string(e.what());
    std::fprintf(stderr,
                 "fixstep: reload failed: %s; the last good world keeps running (tick %llu)\n",
                 why.c_str(), static_cast<unsigned long long>(tick));
    s.set_status_lines(
        reload_error_lines("RELOAD FAILED - the last good world runs on", why, width, scale));
    return;
  }
  reload.load.reset();
  const std::size_t n = shown.session->simulation().body_count();
  fmt::print("reloaded {}: {} bod{}, definition hash {}; tick reset to 0 (was {})\n", file, n,
             n == 1 ? "y" : "ies", hex_hash(definition_hash(shown.session->definition())), tick);
  std::fflush(stdout);
}

}  // namespace

int view_command(const ViewOptions& o) {
  check_paths(view_paths(o));  // before any work: --record may not be the scene
  // The watch takes the file's stamp before the file is read: a save during the load is seen.
  std::optional<FileWatch> watch;
  if (!o.no_watch) watch.emplace(o.scene.scene);
  const auto [width, height] = parse_frame_size(o.size);
  LoadedWorld first = load_first(o.scene, width, height);
  // --fps: a virtual clock, not clamped (frames exactly 1/fps apart).
  const double frame_time = std::max(SessionSettings{}.max_frame_time, o.fps ? 1.0 / *o.fps : 0.0);
  check_frame_ticks(frame_time, first.scene.def.settings.dt, o.fps, dt_source(o.scene, first.scene),
                    dt_fix(o.scene));
  // SIGINT and SIGTERM from here on stop the session as run's are (stop_signal.hpp): the tick in
  // progress is abandoned, the recording kept up to the last complete tick. Installed before
  // the window, so SDL keeps its own handler out (it installs one only over the default).
  const StopOnSignal signals;
  // The window first: without a display it fails at once with a pointer to `render`.
  Window window = open_window(fmt::format("fixstep - {}", first.scene.file), width, height,
                              "fixstep render SCENE --out DIR");
  ShownWorld shown;
  SessionSettings settings = session_settings(first.scene, width, height);
  settings.max_frame_time = frame_time;
  show(shown, std::move(first.scene),
       std::make_unique<Session>(std::move(first.def), std::move(first.sim), settings), first.plan);
  Reload reload;
  set_phase("showing the world");

  InputSampler sampler;  // window events -> one input per tick
  // --record: every tick's input and state hash, following the kept timeline through rewinds
  // and restarts.
  std::optional<Recorder> recorder;
  if (o.record) {  // carrying the scene as loaded: saving an edit cannot break the recording
    recorder.emplace(shown.session->definition(), o.scene.scene, o.hash_every, shown.scene.text);
  }
  const std::uint64_t initial_hash = shown.session->simulation().state_hash();
  bool torn = false;       // a stop request abandoned a tick half-way: the state is not a tick's
  std::uint64_t done = 0;  // the tick of the last complete state shown or stepped
  RealClock real_clock;
  // --fps: a virtual clock (validated by VirtualClock), else the real one.
  const double virtual_frame = o.fps ? VirtualClock(*o.fps).frame_seconds() : 0.0;
  constexpr auto frame_budget = std::chrono::microseconds(16667);  // ~60 Hz presentation

  WindowEvents ev;
  for (std::int64_t frame = 0; o.frames == 0 || frame < o.frames; ++frame) {
    const auto frame_start = std::chrono::steady_clock::now();
    if (watch && watch->changed(frame_start)) {
      on_scene_saved(shown, reload, o, recorder.has_value());
    }
    if (reload.load) follow_reload(shown, reload, o);
    Session& session = *shown.session;
    RewindBuffer& rewind = shown.rewind;
    PointerDrag& drag = shown.drag;
    const Camera camera = session.renderer().camera();
    window.poll(ev);
    if (ev.quit || StopOnSignal::requested()) break;
    apply_loop_keys(ev, session.loop());
    if (ev.restart) {
      session.restart(), rewind.clear(), rewind.push(session.simulation());
      if (recorder) recorder->truncate(0);
    }
    feed(ev, sampler, camera, width, height);
    sampler.set_push(arrow_push(sampler.held(), camera.width));

    const double seconds = o.fps ? virtual_frame : real_clock.frame_seconds();
    const bool was_faulted = session.simulation().fault().has_value();
    if (ev.rewind) {
      // One tick back per frame while Backspace is held; ticks resume from there.
      if (const WorldSnapshot* past = rewind.step_back()) {
        session.restore(*past);
        if (recorder) recorder->truncate(past->tick());
      }
    } else if (frame > 0) {
      try {
        session.advance_with(seconds, [&](std::uint64_t tick, World& sim) {
          TickInput input = sampler.sample(tick);
          drag.apply(input, sim);
          sim.step(input);
          rewind.push(sim);
          if (recorder) recorder->record(input, sim);
          done = sim.tick();
        });
      } catch (const StopRequested&) {  // inside a tick: discard it, keep the ticks before
        torn = true;
        break;
      }
    }
    if (const auto& fault = session.simulation().fault(); fault && !was_faulted) {
      // Session paused the loop; the HUD shows the message too ('r' restarts).
      std::fprintf(stderr, "fixstep: error: %s\n", explain_fault(shown.scene, *fault).c_str());
    }
    done = session.simulation().tick();
    session.show_drag(sampler.pointer(), drag.body());
    session.draw();
    window.present(session.renderer().pixels());
    if (!o.fps) std::this_thread::sleep_until(frame_start + frame_budget);
  }
  if (reload.load && !reload.load->stop()) {  // at its next poll: within about a second
    std::fprintf(stderr, "fixstep: quit while %s loaded: the load was stopped\n",
                 o.scene.scene.c_str());
  }
  reload.load.reset();
  const Session& session = *shown.session;
  fmt::print("{} driver={}\n", describe(shown.scene), window.driver());
  if (!torn) fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
  if (recorder) {  // after a torn tick, up to its last stored hash (every tick at --hash-every 1)
    write_recording(*o.record, torn ? recorder->finish_at_last_hash(initial_hash)
                                    : recorder->finish(session.simulation()));
    fmt::print("recording={}\n", *o.record);
  }
  if (const int sig = StopOnSignal::requested()) {
    std::fprintf(stderr, "fixstep: stopped by %s after tick %llu%s%s\n", StopOnSignal::name(),
                 static_cast<unsigned long long>(done),
                 torn ? " (the tick in progress discarded)" : "",
                 recorder ? "; recording written" : "");
    return 128 + sig;
  }
  return session.simulation().fault() ? exit_diverged : 0;
}

}  // namespace fixstep::cli
