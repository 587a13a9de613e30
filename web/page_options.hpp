// What the page was asked to do, read from its URL's query string (?scene=...&frames=...): the
// page's interface for people (a scene chosen on the page) and for the browser tests
// (tests/web/), which run it headless on a virtual clock. Web platform (wasm only).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace fixstep::web {

/// The games the page plays (game=NAME): demos/airhockey (against the computer; no network),
/// demos/peggle, demos/pinball, demos/slingshot and demos/stacker (page_game.hpp).
inline constexpr std::array<std::string_view, 5> page_game_names{"airhockey", "peggle", "pinball",
                                                                 "slingshot", "stacker"};

/// The page's parameters. Without `frames`, `ticks` or `replay` the page is interactive: the
/// scene runs on the browser's clock, driven by requestAnimationFrame, with keys and pointer.
struct PageOptions {
  /// scene=NAME: a shipped scene, assets/scenes/NAME (the site preloads that folder).
  std::string scene = "default.toml";
  /// frames=F: exactly what `fixstep render SCENE --frames F --fps FPS` draws: frame 0 the
  /// initial state, each later frame 1/fps s of virtual time after the last, every frame drawn
  /// (trails sample once per drawn frame); then the page reports and stops.
  std::optional<std::uint64_t> frames;
  /// ticks=N: exactly N ticks with no input, as `fixstep run SCENE --steps N`, stepped in
  /// chunks of at most ~50 ms per browser frame without drawing; the last state is drawn.
  std::optional<std::uint64_t> ticks;
  /// replay=URL: fetches a recording (fixstep's text format), replays it verifying every
  /// stored hash, reports, then plays it back on the canvas.
  std::optional<std::string> replay;
  /// input=URL (game=, with frames=): fetches an input script (docs/CLI.md) that plays the
  /// game's actions instead of its autopilot, as `NAME --frames N --input SCRIPT` does.
  std::optional<std::string> input;
  double fps = 60.0;    ///< fps=F: the virtual clock's frames per second (frames=), > 0
  bool record = false;  ///< record=1: with frames= or ticks=, also shows the run's recording
  std::uint64_t hash_every = 60;  ///< hash_every=K: ticks between a recording's stored hashes
  /// size=WxH: the canvas, px (as `fixstep render --size`); a game without size= has the
  /// size its program draws (app::Settings: e.g. airhockey 960x600).
  int width = 1280, height = 720;
  bool size_given = false;  ///< size= was given
  /// headless=1: the page's bar and scroll bars are hidden, so that a screenshot of a
  /// width x height window is the canvas alone; frames= and ticks= run on timers (headless
  /// Chromium's virtual time does not run requestAnimationFrame).
  bool headless = false;
  /// overlay=card: draws the overlay test card (overlay_card.hpp: every DrawList shape, a view
  /// style of its own) over the scene, as the native golden frame test does, for the browser
  /// checks to compare.
  bool overlay_card = false;
  /// game=NAME: plays a game of page_game_names as its program's fixstep::app::run does
  /// (the game builds its level; its input, rules, drawing, view and HUD lines). Interactive:
  /// the browser's pointer and keys through the game's input (e.g. aim and click). frames=F:
  /// what `NAME --frames F` does, the autopilot playing on a 60 Hz virtual clock, the last
  /// frame drawn. replay=URL: a recording of that game (its rules name and version; for
  /// airhockey a network match's, as either peer wrote it), verified with its rules as `NAME
  /// --replay` does, then played back. Takes frames=, replay=, size= and headless= only.
  std::optional<std::string> game;
};

/// Parses a query string ("?a=1&b=2", the leading '?' optional; values percent-decoded).
/// Throws std::invalid_argument naming the parameter for an unknown parameter or a bad value:
/// a scene name with a '/' or not ending in .toml, a count that is not a whole number in
/// 1..10^9, an fps that is not finite and > 0, a size outside 16..8192 px per side, more than
/// one of frames, ticks and replay, record without frames or ticks, an overlay other than
/// card, a game not of page_game_names, or game= with a parameter other than frames, replay,
/// size and headless.
[[nodiscard]] PageOptions parse_page_options(std::string_view query);

/// The page's own query string (location.search).
[[nodiscard]] std::string page_query();

}  // namespace fixstep::web
