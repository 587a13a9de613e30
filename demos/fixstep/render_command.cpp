// fixstep render: a scene (or a recording's replay) captured headless, frame by frame.
#include <fmt/format.h>

#include <fixstep/capture.hpp>
#include <fixstep/manifest.hpp>
#include <fixstep/scene_stability.hpp>
#include <fixstep/session.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "stop_signal.hpp"

namespace fixstep::cli {

Session open_session(const Scene& scene, int width, int height) {
  return Session(world_def(scene),
                 SessionSettings{.width = width,
                                 .height = height,
                                 .title = std::filesystem::path(scene.file).filename().string(),
                                 .view_center = scene.view.center,
                                 .view_width = scene.view.width});
}

int render_command(const RenderOptions& o) {
  std::optional<Recording> rec;
  if (o.replay) rec = read_recording(*o.replay);
  const Scene scene =
      rec ? scene_for_recording(
                o.scene.scene.empty() ? recorded_scene(*rec, *o.replay) : o.scene.scene, *rec,
                o.scene.quiet)
          : load_with_overrides(o.scene);
  const auto [width, height] = parse_frame_size(o.size);
  prepare_output_dir(o.out);
  Session session = open_session(scene, width, height);
  const VirtualClock clock(o.fps);
  const auto frames = static_cast<std::uint64_t>(o.frames);
  // Frame f is encoded and written on the writer's thread while frame f + 1 renders here.
  FrameWriter writer(o.out, width, height, PngSettings{.level = o.png_level});
  FrameManifest manifest(o.out);  // frames.csv: a row per frame written
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
    writer.submit(session.renderer().pixels());
    manifest.add(f, session);
    ++written;
    progress.update(written);
    if (session.simulation().fault()) break;
  }
  writer.finish();  // every frame on disk, or the first failure's CaptureError
  manifest.commit();
  progress.finish();
  if (const int sig = StopOnSignal::requested()) {
    fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
    if (written > 0) {
      fmt::print("frames={} (stopped) size={}x{}: {} ... {}\n", written, width, height,
                 frame_path(o.out, 0).string(), frame_path(o.out, written - 1).string());
    }
    fmt::print("manifest={}\n", manifest.file().string());
    std::fprintf(stderr,
                 "fixstep: stopped by %s after %llu frames; every frame written is complete\n",
                 StopOnSignal::name(), static_cast<unsigned long long>(written));
    return 128 + sig;
  }
  if (const auto& fault = session.simulation().fault()) {
    fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
    fmt::print("frames={} (stopped early) size={}x{}: {} ... {}\n", written, width, height,
               frame_path(o.out, 0).string(), frame_path(o.out, written - 1).string());
    fmt::print("manifest={}\n", manifest.file().string());
    std::fprintf(stderr, "fixstep: error: %s\n", explain_fault(scene, *fault).c_str());
    return exit_diverged;
  }
  fmt::print("{} renderer=\"{}\"\n", describe(scene), session.renderer().gl_renderer());
  fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
  fmt::print("frames={} fps={} size={}x{}: {} ... {}\n", frames, o.fps, width, height,
             frame_path(o.out, 0).string(), frame_path(o.out, frames - 1).string());
  fmt::print("manifest={}\n", manifest.file().string());
  return 0;
}

}  // namespace fixstep::cli
