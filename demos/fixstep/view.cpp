// `fixstep view`: the Session's frames presented in an SDL2 window, driven by the real clock.
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <fixstep/scene_stability.hpp>
#include <fixstep/session.hpp>
#include <fixstep/window.hpp>
#include <string>
#include <string_view>
#include <thread>

#include "commands.hpp"

namespace fixstep::cli {

namespace {

// The window, or a WindowError whose message (the library's: the fault only) ends with the
// advice of this program: frames can be captured without a display.
Window open_window(const std::string& title, int width, int height) {
  try {
    return Window(title, width, height);
  } catch (const WindowError& e) {
    const std::string_view fault = e.what();
    throw WindowError(
        fmt::format("{}{} Capture frames headless instead: fixstep render SCENE --out DIR", fault,
                    fault.ends_with('.') ? "" : "."));
  }
}

}  // namespace

int view_command(const ViewOptions& o) {
  const Scene scene = load_with_overrides(o.scene);
  const auto [width, height] = parse_frame_size(o.size);
  // The window first: without a display it fails at once with a pointer to `render`.
  Window window = open_window(fmt::format("fixstep - {}", scene.file), width, height);
  Session session = open_session(scene, width, height);
  session.set_show_controls(true);

  // Arrow keys push every body at half a view-width per s² (visible at any scene scale).
  const double push = 0.5 * session.renderer().camera().width;
  RealClock real_clock;
  const std::optional<VirtualClock> virtual_clock =
      o.fps ? std::optional<VirtualClock>(VirtualClock(*o.fps)) : std::nullopt;
  constexpr auto frame_budget = std::chrono::microseconds(16667);  // ~60 Hz presentation

  for (std::int64_t frame = 0; o.frames == 0 || frame < o.frames; ++frame) {
    const auto frame_start = std::chrono::steady_clock::now();
    const WindowEvents ev = window.poll();
    if (ev.quit) break;
    apply_loop_keys(ev, session.loop());
    if (ev.restart) session.restart();

    const double seconds =
        virtual_clock ? virtual_clock->frame_seconds() : real_clock.frame_seconds();
    TickInput input;
    input.push = {ev.push_direction.x * push, ev.push_direction.y * push};
    const bool was_faulted = session.simulation().fault().has_value();
    if (frame > 0) session.advance(seconds, input);
    if (const auto& fault = session.simulation().fault(); fault && !was_faulted) {
      // Session paused the loop; the HUD shows the message too ('r' restarts).
      std::fprintf(stderr, "fixstep: error: %s\n", explain_fault(scene, *fault).c_str());
    }
    session.draw();
    window.present(session.renderer().pixels());
    if (!virtual_clock) std::this_thread::sleep_until(frame_start + frame_budget);
  }
  fmt::print("{} driver={}\n", describe(scene), window.driver());
  fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
  return session.simulation().fault() ? exit_diverged : 0;
}

}  // namespace fixstep::cli
