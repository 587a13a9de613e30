// A world being played: simulation + fixed-step loop + renderer, the one frame pipeline shared
// by headless capture (`fixstep render`), the window (`fixstep view`) and programs that build
// their world in code (examples/, demos/hello_fixstep.cpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fixstep/loop.hpp"
#include "fixstep/render.hpp"
#include "fixstep/simulation.hpp"

namespace fixstep {

/// A camera that shows a world's whole motion: a fit of every body's position, their anchors,
/// each spring's reach (|x0 - anchor| + |v0|/ω) and, for bodies held at a single anchor through
/// links (a rope pinned at one end), the circle round that anchor through the farthest of them,
/// with a 15 % margin. `width` and `height` are the frame size in pixels (for the aspect ratio).
[[nodiscard]] Camera fit_camera(const WorldDef& def, int width, int height);

/// How a Session shows its world.
struct SessionSettings {
  int width = 1280, height = 720;      ///< frame size, pixels (see Renderer)
  std::string title{};                 ///< named in the HUD's first line (e.g. the scene file)
  std::optional<Vec2> view_center{};   ///< m; default: fit_camera's
  std::optional<double> view_width{};  ///< visible width, m; default: fit_camera's
  float hud_text_scale = 2.0f;         ///< see Renderer::set_hud_text_scale (in [1, 4])
};

class Session {
 public:
  /// Builds the world (make_simulation(def): the stability guard applies; with
  /// WorldSettings::track_dissipation turned on, since the HUD shows the energy balance), the
  /// loop (ticks of def.settings.dt) and the renderer. Throws std::invalid_argument for an invalid
  /// or unstable def (see make_simulation), RenderError when rendering cannot start.
  explicit Session(WorldDef def, const SessionSettings& settings = {});

  /// One frame: runs the loop for frame_seconds (s) of real or virtual time; every tick gets
  /// `input` (see TickInput).
  FrameResult advance(double frame_seconds, const TickInput& input = {});
  /// One frame whose ticks the caller runs: tick(tick index, Simulation&) is called once per
  /// tick the loop runs and must step the simulation once (sim.step(input) with that tick's
  /// input: from an InputSampler, a recording, a script); it may also change the world between
  /// ticks (a game's rules). No tick runs once the runtime guard has fired.
  template <class TickFn>
  FrameResult advance_with(double frame_seconds, TickFn&& tick);
  /// One frame whose ticks take their inputs from `sampler` (each press or release reaches
  /// exactly one tick; see InputSampler).
  FrameResult advance(double frame_seconds, InputSampler& sampler);

  /// A restorable state of the session: the world's complete state and the loop's (tick,
  /// accumulator). Pause, time scale, camera and HUD are not part of it.
  struct Snapshot {
    WorldSnapshot world;
    FixedStepLoop::State loop;
  };
  /// Saves into `out`, reusing its storage (no allocation once it holds a state of this world).
  void save(Snapshot& out) const;
  /// Restores a state saved from this session; trails are cleared. Throws
  /// std::invalid_argument for an empty snapshot.
  void restore(const Snapshot& snapshot);
  /// Restores only the world (e.g. from a RewindBuffer): the loop continues from the
  /// snapshot's tick with an empty accumulator; trails are cleared. Throws
  /// std::invalid_argument for an empty snapshot.
  void restore(const WorldSnapshot& world);
  /// Renders the state interpolated by the loop's alpha, with the HUD, into renderer().pixels().
  void draw();
  /// Back to the initial state (tick 0), trails cleared; pause and time scale are kept.
  void restart();
  /// Draws the pointer's drag spring (from `pointer`, m, to body `body`) in the next draw()s,
  /// as the springs are drawn; no_body hides it.
  void show_drag(Vec2 pointer, Entity body) { drag_pointer_ = pointer, drag_body_ = body; }
  /// Shows the window's key help in the HUD.
  void set_show_controls(bool show) { show_controls_ = show; }
  /// Shows the energy line (E, dissipated, balance) in the HUD: on by default. Programs whose
  /// rules or pointer add energy from outside the world's account (a game) may hide it, as
  /// its balance then measures them, not the integrator.
  void set_show_energy(bool show) { show_energy_ = show; }
  /// Shows the engine's HUD lines (title, tick and time, integrator, energy, controls): on by
  /// default. Off, the HUD holds only the status lines and, once the runtime guard has fired,
  /// its message: for programs that lay out a HUD of their own (`fixstep compare`'s tiles).
  void set_show_engine_hud(bool show) { show_engine_hud_ = show; }
  /// Extra HUD lines drawn below the engine's (a game's score, a hint), until replaced; an
  /// empty list shows none. The bitmap font is ASCII only.
  void set_status_lines(std::vector<std::string> lines) { status_lines_ = std::move(lines); }

  [[nodiscard]] const WorldDef& definition() const { return def_; }
  [[nodiscard]] const Simulation& simulation() const { return *sim_; }
  /// The simulation, for programs that change the world between ticks (a game's rules).
  [[nodiscard]] Simulation& simulation() { return *sim_; }
  [[nodiscard]] FixedStepLoop& loop() { return loop_; }
  /// The loop's interpolation weight: draw() shows lerp(previous tick, current tick, alpha).
  [[nodiscard]] double alpha() const { return loop_.alpha(); }
  [[nodiscard]] const Renderer& renderer() const { return renderer_; }
  [[nodiscard]] double initial_energy() const { return initial_energy_; }

 private:
  /// Pauses the loop once the runtime guard has fired.
  void pause_on_fault();
  /// Appends the engine's HUD lines (title, tick, integrator, energy) to hud_.
  void engine_hud_lines();
  /// Appends the loop's state and the window's key help to hud_.
  void control_hud_lines();

  WorldDef def_;
  std::string title_;
  std::unique_ptr<Simulation> sim_;
  FixedStepLoop loop_;
  Renderer renderer_;
  RenderFrame frame_;
  std::vector<std::string> hud_;
  std::vector<std::string> fault_lines_;  ///< the runtime guard's message for the HUD, once built
  double initial_energy_ = 0.0;
  bool show_controls_ = false;
  bool show_energy_ = true;
  bool show_engine_hud_ = true;
  Vec2 drag_pointer_{};
  Entity drag_body_ = no_body;
  std::vector<std::string> status_lines_;  ///< set_status_lines()
};

template <class TickFn>
FrameResult Session::advance_with(double frame_seconds, TickFn&& tick) {
  const FrameResult r = loop_.advance_with(frame_seconds, [&](std::uint64_t t) {
    if (!sim_->fault()) tick(t, *sim_);
  });
  pause_on_fault();
  return r;
}

}  // namespace fixstep
