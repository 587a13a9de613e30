// fixstep render: a scene (or a recording's replay) captured headless, frame by frame.
#include <fmt/format.h>

#include <fixstep/capture.hpp>
#include <fixstep/manifest.hpp>
#include <fixstep/scene_stability.hpp>
#include <fixstep/session.hpp>

#include "capture_sink.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "stop_signal.hpp"

namespace fixstep::cli {

SessionSettings session_settings(const Scene& scene, int width, int height) {
  return SessionSettings{.width = width,
                         .height = height,
                         .title = std::filesystem::path(scene.file).filename().string(),
                         .view_center = scene.view.center,
                         .view_width = scene.view.width};
}

Session open_session(const Scene& scene, int width, int height) {
  return Session(world_def(scene), session_settings(scene, width, height));
}

int render_command(const RenderOptions& o) {
  std::optional<Recording> rec;
  if (o.replay) rec = read_recording(*o.replay);
  const Scene scene =
      rec ? scene_for_recording(
                o.scene.scene.empty() ? recorded_scene(*rec, *o.replay) : o.scene.scene, *rec,
                *o.replay, o.scene.quiet)
          : load_with_overrides(o.scene);
  const auto [width, height] = parse_frame_size(o.size);
  // Frame f is encoded and written on the writers' threads while frame f + 1 renders here.
  CaptureSink sink({.out = o.out, .video = o.video, .png_level = o.png_level}, width, height, o.fps,
                   ManifestLayout::frames);
  Session session = open_session(scene, width, height);
  const VirtualClock clock(o.fps);
  const auto frames = static_cast<std::uint64_t>(o.frames);
  std::uint64_t written = 0;
  const StopOnSignal signals;
  Progress progress("render", "frame", frames, !o.scene.quiet);
  for (std::uint64_t f = 0; f < frames && !StopOnSignal::requested(); ++f) {
    if (f > 0 && rec) {  // the recorded input of each tick; none past the recording's end
      session.advance_with(clock.frame_seconds(),
                           [&](std::uint64_t t, Simulation& sim) { sim.step(rec->input_at(t)); });
    } else if (f > 0) {
      session.advance(clock.frame_seconds());
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
  fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
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
