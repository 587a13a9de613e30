// A world being played: simulation + fixed-step loop + renderer, the one frame pipeline shared
// by headless capture (`fixstep render`), the window (`fixstep view`) and programs that build
// their world in code (examples/, demos/hello_fixstep.cpp).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/app/key_bindings.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/render.hpp"

namespace fixstep {

/// A camera that shows a world's whole motion: a fit of every body's position (and the box
/// round its shapes where it starts), their anchors,
/// each spring's reach (|x0 - anchor| + |v0|/ω) and, for bodies held at a single anchor through
/// links (a rope pinned at one end), the circle round that anchor through the farthest of them,
/// with a 15 % margin. `width` and `height` are the frame size in pixels (for the aspect ratio).
[[nodiscard]] Camera fit_camera(const WorldDef& def, int width, int height);

/// The engine's HUD lines, as bits of SessionSettings::hud_lines (Session::set_hud_lines). The
/// values are those of the scene's [view] hud_lines (SceneView::hud_lines).
enum HudLine : unsigned {
  hud_title = 1u << 0,       ///< "fixstep  TITLE  (N bodies)"
  hud_time = 1u << 1,        ///< tick, t and dt
  hud_integrator = 1u << 2,  ///< the integrator and precision
  hud_energy = 1u << 3,      ///< energy, dissipated, balance (when set_show_energy is on)
  hud_controls = 1u << 4,    ///< time scale and the key help (when set_show_controls is on)
};
/// Every engine HUD line.
inline constexpr unsigned all_hud_lines = 0x1f;

/// How a Session shows its world.
///
/// The automatic view (no view_center): the world as fit_camera frames it, in the part of the
/// frame below the HUD's top-left panel, so the HUD never hides a body the view fits. The band
/// reserved is as tall as the most HUD lines shown so far: it grows (and the view with it) when
/// more lines appear (controls, status lines, the runtime guard's message), never shrinks. A
/// program's view (view_center, or Session::set_view, follow, zoom) reserves nothing.
struct SessionSettings {
  int width = 1280, height = 720;      ///< frame size, pixels (see Renderer)
  std::string title{};                 ///< named in the HUD's first line (e.g. the scene file)
  std::optional<Vec2> view_center{};   ///< m; default: the automatic view's
  std::optional<double> view_width{};  ///< visible width, m; default: the automatic view's
  /// The name of a body the view follows (follow()) from the start and after each restart();
  /// empty: none. The constructor throws std::invalid_argument when no body has that name.
  std::string follow{};
  float hud_text_scale = 2.0f;  ///< see Renderer::set_hud_text_scale (in [1, 4])
  /// Background colour, grid, axes, scale bar and joints (Renderer::set_view_style).
  ViewStyle style{};
  /// The corner the HUD panel sits in; with the automatic view, the band reserved for it is at
  /// the top or the bottom of the frame accordingly.
  HudCorner hud_corner = HudCorner::top_left;
  /// false: no HUD at all (neither the engine's lines nor the status lines; the runtime guard's
  /// message still shows when it fires), and no band reserved for it.
  bool show_hud = true;
  /// Which of the engine's lines the HUD may show (HudLine bits; energy and controls also need
  /// their switches).
  unsigned hud_lines = all_hud_lines;
  /// The loop's frame-time clamp, s (LoopSettings::max_frame_time): the real clock's guard
  /// against stalls. A virtual clock passes its frame time (>= 0.25 s when it is longer), so no
  /// frame is clamped: frames are exactly 1/fps apart at any fps.
  double max_frame_time = 0.25;
};

/// Most ticks one frame of a Session may step: its loop's tick cap, ceil(max_frame_time / dt)
/// + 1, must not exceed it (a Session refuses a dt too short for its longest frame).
inline constexpr double max_frame_ticks = 0x1p30;

class Session {
 public:
  /// Builds the world (World(def), with WorldSettings::track_dissipation turned on, since the HUD
  /// shows the energy balance), the loop (ticks of def.settings.dt) and the renderer. Throws as
  /// World(def) does (its checks: UnstableDefinition, LimitError, std::invalid_argument), and
  /// std::invalid_argument for a max_frame_time that is not finite and > 0 or is more than
  /// max_frame_ticks ticks, RenderError when rendering cannot start. restart() builds the world
  /// again, checks included.
  explicit Session(WorldDef def, const SessionSettings& settings = {});
  /// As above, with the world already built: `sim` must be World(def) at tick 0, made
  /// with def.settings.track_dissipation on (so that a large world can be built on another
  /// thread, e.g. while a window keeps showing the previous one; the renderer is made here, on
  /// the calling thread). Throws std::invalid_argument when sim is past tick 0, has another body
  /// count than def, or does not track dissipation; as above otherwise.
  Session(WorldDef def, World sim, const SessionSettings& settings = {});

  /// One frame: runs the loop for frame_seconds (s) of real or virtual time; every tick gets
  /// `input` (see TickInput).
  FrameResult advance(double frame_seconds, const TickInput& input = {});
  /// One frame whose ticks the caller runs: tick(tick index, World&) is called once per
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
  /// The same, with `overlay`'s shapes drawn after the bodies and before the HUD (a game's
  /// drawing: app::Overlay).
  void draw(const DrawList& overlay);
  /// Takes the frame the next draw() draws: the bodies' positions interpolated by alpha, the
  /// followed body centred. draw() takes it itself unless prepare_frame() was called since the
  /// last tick or draw (so that a game can ask drawn_position() first); nothing may change the
  /// world in between.
  void prepare_frame();
  /// Where `body` is drawn in the prepared frame (prepare_frame()), m: its position interpolated
  /// by alpha; nullopt for a handle that names no live body or when no frame is prepared.
  [[nodiscard]] std::optional<Vec2> drawn_position(Entity body) const;
  /// Back to the initial state (tick 0), trails cleared; pause and time scale are kept, and the
  /// view follows SessionSettings::follow's body again.
  void restart();
  /// Draws the pointer's drag spring (from `pointer`, m, to body `body`) in the next draw()s,
  /// as the springs are drawn; null_entity hides it.
  void show_drag(Vec2 pointer, Entity body) { drag_pointer_ = pointer, drag_body_ = body; }
  /// Shows the loop's key help in the HUD (the window's, fixstep::window_key_help, unless
  /// set_key_help() gave another).
  void set_show_controls(bool show);
  /// The key help line set_show_controls() shows: the keys of the program's loop (e.g.
  /// fixstep::page_key_help in a browser, which has no Esc to quit).
  void set_key_help(std::string_view help) { key_help_ = help; }
  /// Shows the energy line (E, dissipated, balance) in the HUD: on by default. Programs whose
  /// rules or pointer add energy from outside the world's account (a game) may hide it, as
  /// its balance then measures them, not the integrator.
  void set_show_energy(bool show);
  /// Shows the engine's HUD lines (title, tick and time, integrator, energy, controls): on by
  /// default. Off, the HUD holds only the status lines and, once the runtime guard has fired,
  /// its message: for programs that lay out a HUD of their own (`fixstep compare`'s tiles).
  void set_show_engine_hud(bool show);
  /// Extra HUD lines drawn below the engine's (a game's score, a hint), until replaced; an
  /// empty list shows none. The bitmap font is ASCII only. The lines are copied into storage
  /// the session keeps: setting lines every frame allocates nothing once warm.
  void set_status_lines(std::span<const std::string> lines);
  /// Background colour, grid, axes, scale bar and joints (SessionSettings::style).
  void set_view_style(const ViewStyle& style) { renderer_.set_view_style(style); }
  /// Who rasterises the overlay and the HUD (Renderer::set_overlay_path; the CPU by default).
  void set_overlay_path(OverlayPath path) { renderer_.set_overlay_path(path); }
  /// The HUD's corner (SessionSettings::hud_corner).
  void set_hud_corner(HudCorner corner);
  /// Shows the HUD or hides it all (SessionSettings::show_hud).
  void set_show_hud(bool show);
  /// Which engine lines the HUD may show (HudLine bits; SessionSettings::hud_lines).
  void set_hud_lines(unsigned lines);
  /// The HUD's text scale, px per font pixel: Renderer::set_hud_text_scale (throws
  /// std::invalid_argument outside [1, 4]).
  void set_hud_text_scale(float scale);

  // --- the camera: what part of the world the frame shows (units: m) ----------------------
  /// Shows the world around `center` (m), `width` m across the frame (the height follows the
  /// frame's aspect ratio, y up); stops following. Throws std::invalid_argument unless center
  /// is finite and width finite and > 0.
  void set_view(Vec2 center, double width);
  /// Keeps `body` at the centre of the frame: each draw() centres the view on the body's
  /// interpolated position (the position drawn), at the current width (zoom() still applies).
  /// null_entity stops following; so does the body's destruction (the view stays where it last
  /// was). Throws std::invalid_argument for a handle that names no body of the simulation.
  void follow(Entity body);
  /// Magnifies the view by `factor` about its centre: the width becomes width / factor (2
  /// shows half as many metres across, 0.5 twice as many). Throws std::invalid_argument unless
  /// factor is finite and > 0 and the new width finite and > 0.
  void zoom(double factor);
  /// The view the next draw() starts from (the last one drawn, or as set since).
  [[nodiscard]] const Camera& view() const { return renderer_.camera(); }
  /// The body the view follows, or null_entity.
  [[nodiscard]] Entity followed() const { return follow_; }
  /// Forgets the trails (a jump, a teleport, a new level): each body starts a new one.
  void clear_trails() { renderer_.clear_trails(); }

  [[nodiscard]] const WorldDef& definition() const { return def_; }
  [[nodiscard]] const World& simulation() const { return *sim_; }
  /// The simulation, for programs that change the world between ticks (a game's rules).
  [[nodiscard]] World& simulation() { return *sim_; }
  [[nodiscard]] FixedStepLoop& loop() { return loop_; }
  /// The loop's interpolation weight: draw() shows lerp(previous tick, current tick, alpha).
  [[nodiscard]] double alpha() const { return loop_.alpha(); }
  [[nodiscard]] const Renderer& renderer() const { return renderer_; }
  /// The frame last prepared or drawn (prepare_frame()).
  [[nodiscard]] const RenderFrame& frame() const { return frame_; }
  [[nodiscard]] double initial_energy() const { return initial_energy_; }

 private:
  /// Pauses the loop once the runtime guard has fired.
  void pause_on_fault();
  /// Appends the engine's HUD lines (title, tick, integrator, energy) to hud_.
  void engine_hud_lines();
  /// Appends the loop's state and the window's key help to hud_.
  void control_hud_lines();
  /// HUD lines draw() shows with the current settings, before the runtime guard's message.
  [[nodiscard]] std::size_t planned_hud_lines() const;
  /// The automatic view: refits the world below a HUD of `lines` lines when more than reserved.
  void reserve_hud(std::size_t lines);
  /// After each tick: samples the trails; the prepared frame is stale.
  void after_tick();
  /// Renders the prepared frame, `overlay` (if any) and the HUD.
  void render(const DrawList* overlay);
  /// The constructors' common part, once sim_ is built.
  void start(const SessionSettings& settings);
  /// The program took the camera: the view is no longer automatic.
  void take_view() { auto_view_ = false; }
  /// Follows the body named follow_name_ (nothing when it is empty). Throws
  /// std::invalid_argument when no body has that name.
  void follow_named();

  WorldDef def_;
  std::string title_;
  std::unique_ptr<World> sim_;
  FixedStepLoop loop_;
  Renderer renderer_;
  RenderFrame frame_;
  std::vector<std::string> hud_;
  std::vector<std::string> fault_lines_;  ///< the runtime guard's message for the HUD, once built
  double initial_energy_ = 0.0;
  bool show_controls_ = false;
  std::string key_help_{window_key_help};
  bool show_energy_ = true;
  bool show_engine_hud_ = true;
  Vec2 drag_pointer_{};
  Entity drag_body_ = null_entity;
  std::vector<std::string> status_lines_;  ///< set_status_lines()
  bool auto_view_ = true;                  ///< the view is fit_camera's below the HUD
  std::optional<double> auto_width_;       ///< SessionSettings::view_width, m
  std::size_t hud_reserved_ = 0;           ///< HUD lines the automatic view leaves room for
  Entity follow_ = null_entity;            ///< follow()
  std::string follow_name_;                ///< SessionSettings::follow
  bool frame_ready_ = false;               ///< prepare_frame() since the last tick or draw
  HudCorner hud_corner_ = HudCorner::top_left;
  bool show_hud_ = true;
  unsigned hud_lines_ = all_hud_lines;
  std::size_t status_count_ = 0;  ///< status_lines_[0, status_count_) are shown
};

template <class TickFn>
FrameResult Session::advance_with(double frame_seconds, TickFn&& tick) {
  const FrameResult r = loop_.advance_with(frame_seconds, [&](std::uint64_t t) {
    if (sim_->fault()) return;
    tick(t, *sim_);
    after_tick();
  });
  pause_on_fault();
  return r;
}

}  // namespace fixstep
