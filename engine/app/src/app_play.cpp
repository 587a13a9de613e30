// fixstep::app: live play, in the window on the real clock or headless on a virtual one.
#include <chrono>
#include <fixstep/app/key_bindings.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/world_settings.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "app_modes.hpp"
#include "fixstep/app/game_play.hpp"
#include "game_capture.hpp"
#ifdef FIXSTEP_APP_WINDOW
#include <fixstep/window/window.hpp>
#endif

namespace fixstep::app::detail {

namespace {

constexpr auto window_frame = std::chrono::microseconds(16667);  // the window's pace, 60 Hz

/// Plays in a window on the real clock until Esc, the close button, a stop request or
/// `frames` frames (0: no limit).
void play_window(GamePlay& play, const Settings& settings, std::int64_t frames) {
#ifdef FIXSTEP_APP_WINDOW
  Window window(settings.name, settings.width, settings.height);
  InputMap map = game_input_map(settings);
  // The game's keys and the loop's, a line each: one line of both is wider than a HUD beside a
  // game's field.
  const std::string loop_keys = map.loop_help();
  const std::string hint =
      settings.controls.empty() ? loop_keys : settings.controls + "\n" + loop_keys;
  window.set_input_map(std::move(map));
  RealClock clock;
  UserEvents ev;
  for (std::int64_t frame = 0; (frames == 0 || frame < frames) && stop_requested() == 0; ++frame) {
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
/// playing, until a stop request; writes every frame into `capture` when given, and draws the
/// last frame when `last_frame` is asked for (trails are sampled every tick, drawn or not).
/// Returns whether every frame ran.
bool play_headless(GamePlay& play, std::int64_t frames, GameCapture* capture, bool last_frame,
                   bool scripted) {
  const VirtualClock clock(virtual_fps);
  for (std::int64_t frame = 0; frame < frames; ++frame) {
    if (frame > 0) {
      if (!scripted) play.game().autopilot(frame, play.session().simulation(), play.sampler());
      play.advance(clock.frame_seconds());
    }
    if (stop_requested() != 0) return false;  // the frame's ticks stopped: it is not drawn
    if (capture == nullptr && !(last_frame && frame + 1 == frames)) continue;
    play.draw(scripted ? "input script" : "autopilot");
    if (capture != nullptr) capture->add(static_cast<std::uint64_t>(frame), play.session());
  }
  return true;
}

}  // namespace

int play(const AnyGame& game, const Settings& settings, const Options& o) {
  Level level = load_level(game, settings, o.scene.value_or(settings.scene_file));
  if (o.frames > 0) {
    check_frames_work(level, o.frames, 1, "--frames " + std::to_string(o.frames));
    if (!o.record.empty()) check_recorded_frames(level, o.frames, o.record);
  }
  std::optional<InputScript> script;
  if (!o.input.empty()) script = game_script(settings, level, o.input);
  GamePlay play(std::move(level), settings, o.record);
  if (script) play.play_script(*script);
  std::optional<GameCapture> capture;
  if (!o.out.empty()) capture.emplace(o.out, o.overwrite, settings.width, settings.height);
  bool torn = false;  // a stop request abandoned a tick half-way
  bool whole = true;  // every frame asked for ran
  try {
    if (o.window || o.frames == 0) {
      play_window(play, settings, o.frames);
    } else {
      whole = play_headless(play, o.frames, capture ? &*capture : nullptr, !o.last_frame.empty(),
                            script.has_value());
    }
  } catch (const StopRequested&) {
    torn = true;
  }
  if (capture) capture->finish();  // the frames drawn before a stop are whole, and listed
  const int signal = stop_requested();
  if (signal == 0 && whole && !o.last_frame.empty()) {
    write_png(o.last_frame, settings.width, settings.height, play.session().renderer().pixels());
  }
  play.finish_stopped(torn);
  if (signal == 0) return 0;
  return stopped(settings, play.session().simulation().tick(), torn,
                 o.record.empty() ? "" : "the recording written up to its last complete tick");
}

}  // namespace fixstep::app::detail
