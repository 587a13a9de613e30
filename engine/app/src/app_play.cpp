// fixstep::app: live play, in the window on the real clock or headless on a virtual one.
#include <chrono>
#include <fixstep/app/key_bindings.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/world_settings.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "app_modes.hpp"
#include "fixstep/app/game_play.hpp"
#ifdef FIXSTEP_APP_WINDOW
#include <fixstep/window/window.hpp>
#endif

namespace fixstep::app::detail {

namespace {

constexpr double headless_fps = 60.0;  // frames/s of a headless run's virtual clock
constexpr auto window_frame = std::chrono::microseconds(16667);  // the window's pace, 60 Hz

/// Plays in a window on the real clock until Esc or the close button (or `frames` frames).
void play_window(GamePlay& play, const Settings& settings, std::int64_t frames) {
#ifdef FIXSTEP_APP_WINDOW
  Window window(settings.name, settings.width, settings.height);
  // The game's keys and the window's, a line each: one line of both is wider than a HUD
  // beside a game's field.
  const std::string hint = settings.controls.empty()
                               ? "r: restart   esc: quit"
                               : settings.controls + "\nr: restart   esc: quit";
  RealClock clock;
  UserEvents ev;
  for (std::int64_t frame = 0; frames == 0 || frame < frames; ++frame) {
    const auto frame_start = std::chrono::steady_clock::now();
    window.poll(ev);
    if (ev.quit) break;
    Session& session = play.session();
    apply_loop_keys(ev, session.loop());  // space pause, '.' one tick, +/- speed
    if (ev.restart) play.restart();
    feed(ev, play.sampler(), session.renderer().camera(), settings.width, settings.height);
    play.game().input(ev, session.simulation(), play.sampler());
    play.advance(clock.frame_seconds());
    play.draw(hint);
    window.present(session.renderer().pixels());
    std::this_thread::sleep_until(frame_start + window_frame);
  }
#else
  (void)play, (void)settings, (void)frames;
  throw std::runtime_error("this build of fixstep has no window (FIXSTEP_BUILD_WINDOW=OFF)");
#endif
}

/// Runs `frames` frames headless on a virtual 60 Hz clock (frame 0 is t = 0), the autopilot
/// playing; writes every frame as DIR/frame_NNNNNN.png when `out_dir` is not empty, and draws
/// the last frame when `last_frame` is asked for (trails are sampled every tick, drawn or not).
void play_headless(GamePlay& play, const Settings& settings, std::int64_t frames,
                   const std::string& out_dir, bool last_frame) {
  std::optional<FrameWriter> writer;
  if (!out_dir.empty()) {
    prepare_output_dir(out_dir);
    writer.emplace(out_dir, settings.width, settings.height);
  }
  const VirtualClock clock(headless_fps);
  for (std::int64_t frame = 0; frame < frames; ++frame) {
    if (frame > 0) {
      play.game().autopilot(frame, play.session().simulation(), play.sampler());
      play.advance(clock.frame_seconds());
    }
    if (!writer && !(last_frame && frame + 1 == frames)) continue;
    play.draw("autopilot");
    if (writer) writer->submit(play.session().renderer().pixels());
  }
  if (writer) writer->finish();
}

}  // namespace

int play(const AnyGame& game, const Settings& settings, const Options& o) {
  GamePlay play(load_level(game, settings, o.scene.value_or(settings.scene_file)), settings,
                o.record);
  if (o.window || o.frames == 0) {
    play_window(play, settings, o.frames);
  } else {
    play_headless(play, settings, o.frames, o.out, !o.last_frame.empty());
  }
  if (!o.last_frame.empty()) {
    write_png(o.last_frame, settings.width, settings.height, play.session().renderer().pixels());
  }
  play.finish();
  return 0;
}

}  // namespace fixstep::app::detail
