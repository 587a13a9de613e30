// fixstep render: a scene (or a recording's replay) captured headless, frame by frame.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fixstep/app/scene_view_settings.hpp>
#include <fixstep/app/session.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/capture/manifest.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <fixstep/scene/scene_stability.hpp>

#include "capture_sink.hpp"
#include "command_memory.hpp"
#include "command_phase.hpp"
#include "commands.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "output_paths.hpp"
#include "progress.hpp"

namespace fixstep::cli {

SessionSettings session_settings(const Scene& scene, int width, int height) {
  SessionSettings s{.width = width,
                    .height = height,
                    .title = std::filesystem::path(scene.file).filename().string(),
                    .view_center = scene.view.center,
                    .view_width = scene.view.width};
  apply_scene_view_style(scene.view, s);  // background, grid, axes, scale bar, HUD
  return s;
}

namespace {

/// --replay: the whole recording replayed headless and verified before anything is written, so
/// that a diverging recording leaves no frame, video or manifest behind. True when it verified;
/// false after the located error (report_divergence).
bool verified_before_capture(const Scene& scene, const Recording& rec, const RenderOptions& o) {
  const ReplayReport report = verify_recording(scene, rec, o.scene.quiet);
  if (!report.mismatch) return true;
  report_divergence(*report.mismatch, *o.replay,
                    "; nothing was written (render --replay verifies the whole recording before "
                    "its first frame)");
  return false;
}

}  // namespace

int render_command(const RenderOptions& o) {
  std::optional<Recording> rec;
  set_phase("reading the recording");
  if (o.replay) rec = read_recording(*o.replay);
  const std::optional<std::string> given =
      o.scene.scene.empty() ? std::nullopt : std::optional(o.scene.scene);
  // The scene file a recording names is kept safe from the outputs too, read or not.
  const std::string scene_file = given ? *given : recorded_scene(*rec, *o.replay);
  check_paths(render_paths(o, scene_file));  // before any work: no output may be an input
  Scene scene = rec ? scene_for_recording(*rec, *o.replay, given, o.scene.quiet)
                    : load_with_overrides(o.scene);
  apply_joint_view(o.scene.joints, scene);  // a recording's scene too
  const auto [width, height] = parse_frame_size(o.size);
  // Before the world and the frame buffers are allocated.
  check_memory("render", scene.file,
               render_memory(scene, width, height, o.video.has_value(), rec ? &*rec : nullptr));
  // A scene's world is checked here, before any output, its guard's findings located in the
  // file; a recording's is replayed whatever the guard says (scene_for_recording).
  std::optional<World> checked;
  if (!rec) checked.emplace(build_world(scene, o.scene.quiet));
  const VirtualClock clock(o.fps);
  // A virtual clock is not clamped (the clamp guards a real clock against stalls): every frame
  // is exactly 1/fps after the last, at any --fps.
  const double frame_time = std::max(SessionSettings{}.max_frame_time, clock.frame_seconds());
  // What set dt, named when a frame or the command would take too many ticks of it.
  const std::string dt_from =
      rec ? fmt::format("the dt of --replay {} ({:g} s)", *o.replay, scene.def.settings.dt)
          : dt_source(o.scene, scene);
  check_frame_ticks(frame_time, scene.def.settings.dt, o.fps, dt_from,
                    rec ? "record it again with --dt" : dt_fix(o.scene));
  const double ticks = std::ceil(double(o.frames - 1) / o.fps / scene.def.settings.dt);
  // With --replay the recording's ticks are stepped once more, to verify it first.
  const double verified = rec ? double(rec->ticks) : 0.0;
  check_command_work(
      static_cast<std::uint64_t>(std::min(ticks + verified, 1e18)), tick_work(scene.def),
      rec ? fmt::format("--frames {} at --fps {:g} with --replay {} (end {})", o.frames, o.fps,
                        *o.replay, rec->ticks)
          : fmt::format("--frames {} at --fps {:g} with {}", o.frames, o.fps, dt_from));
  if (rec && !verified_before_capture(scene, *rec, o)) return exit_replay_diverged;
  set_phase("rendering the frames");
  // Frame f is encoded and written on the writers' threads while frame f + 1 renders here.
  CaptureSink sink(
      {.out = o.out, .video = o.video, .png_level = o.png_level, .overwrite = o.overwrite}, width,
      height, o.fps, ManifestLayout::frames);
  SessionSettings settings = session_settings(scene, width, height);
  settings.max_frame_time = frame_time;
  Session session =
      checked ? Session(scene.def, std::move(*checked), settings) : Session(scene.def, settings);
  const auto frames = static_cast<std::uint64_t>(o.frames);
  std::uint64_t written = 0;
  const StopOnSignal signals;
  Progress progress("render", "frame", frames, !o.scene.quiet);
  bool torn = false;  // a stop request inside a tick: that frame is not drawn
  for (std::uint64_t f = 0; f < frames && !StopOnSignal::requested(); ++f) {
    try {
      if (f > 0 && rec) {  // the recorded input of each tick; none past the recording's end
        session.advance_with(clock.frame_seconds(),
                             [&](std::uint64_t t, World& sim) { sim.step(rec->input_at(t)); });
      } else if (f > 0) {
        session.advance(clock.frame_seconds());
      }
    } catch (const StopRequested&) {
      torn = true;
      break;
    }
    session.draw();  // after a divergence: the last state, with the guard's message in the HUD
    sink.submit(session.renderer().pixels());
    sink.add_row(f, session);  // frames.csv: a row per frame written
    progress.update(++written);
    if (session.simulation().fault()) break;
  }
  sink.finish();  // every frame written, or the first failure's CaptureError
  progress.finish();
  const int sig = StopOnSignal::requested();
  const auto& fault = session.simulation().fault();
  if (!sig && !fault) {
    fmt::print("{} renderer=\"{}\"\n", describe(scene), session.renderer().gl_renderer());
  }
  // A torn state (a tick abandoned half-way) has no summary.
  if (!torn) fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
  sink.print_paths(written, sig ? " (stopped)" : fault ? " (stopped early)" : "");
  if (sig) {
    std::fprintf(stderr,
                 "fixstep: stopped by %s after %llu frames; every frame written is complete\n",
                 StopOnSignal::name(), static_cast<unsigned long long>(written));
    return 128 + sig;
  }
  if (fault) {
    std::fprintf(stderr, "fixstep: error: %s\n", explain_fault(scene, *fault).c_str());
    return exit_diverged;
  }
  return 0;
}

}  // namespace fixstep::cli
