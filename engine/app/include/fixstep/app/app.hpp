// A game in one call: fixstep::app::run(game, settings, argc, argv) gives a game type the
// window, headless capture, recording, replay with verification, the sync test and --help.
//
// A game is a copyable type with two members, and up to seven more:
//
//   void setup(WorldDef& level);                           // required
//   void rules(World& world, const TickInput& input);      // required
//   void input(const UserEvents& ev, const World& world, InputSampler& sampler);
//   void autopilot(std::int64_t frame, const World& world, InputSampler& sampler);
//   void prepare(TickInput& input, const World& world);
//   void draw(Overlay& overlay) const;
//   bool pre_solve(const PreSolveContact& contact) const;  // false: the contact does not act
//   std::string summary() const;
//   void seat(int player);                                 // networked play only
//   TickInput merge(std::span<const TickInput> players, const World& world) const;
//
// setup() completes the level: run() hands it the scene file's world (Settings::scene_file, or
// --scene), or an empty WorldDef when the game builds its level in code; level.find_body(NAME)
// and level.find_joint(NAME) give the handles the world will have, to keep in the game's
// members. rules() runs after (Settings::rules_before_step: before) every tick, live, in a replay
// and in the sync test alike, so it may change the world (score, spawn, destroy) and keep state in
// the game's members: run() copies the game as setup() left it to start afresh (restart, replay)
// and to roll back (sync test), so what setup() keeps (the handles WorldDef::add_body returned, the
// bodies it tagged) every copy has. input() turns a window's events into per-body input (the
// sampler carries it into the ticks and the recording); autopilot() does the same for a headless
// frame; prepare() adjusts one live tick's input before it is stepped (e.g. which body the pointer
// may drag); draw() draws shapes over the world (lines, circles, polygons, arrows, labels:
// app::Overlay) and adds lines to the HUD; summary() is the game's state in one line, printed after
// a run and a replay. seat() and merge() are for networked play (fixstep::net::run,
// fixstep/net_app/run.hpp): seat() tells the game which player its input(), autopilot() and draw()
// play (0 = the host; it may be called again at any time, so it must not change what rules() do),
// and merge() makes each tick's one input from every player's (index = player), on every peer,
// before the step (so, like rules(), it must be deterministic; it replaces prepare() in a match).
// pre_solve() is the world's pre-solve hook (fixstep/core/pre_solve.hpp: asked once a tick for
// each contact of a body with shapes, before the solve; false disables it for the tick),
// installed on every world the game is stepped in, live, in a replay, the sync test and
// networked play, with the copy of the game whose rules step that world: it may read that
// game's members (restored with the world on a rollback) and the contact, and must not change
// anything.
#pragma once

#include <concepts>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fixstep/app/game_model.hpp"
#include "fixstep/app/overlay.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/types.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/render/input_map.hpp"

namespace fixstep::app {

/// What run() needs to know of a game besides its type.
struct Settings {
  /// The program's name: messages, the window's title, --help, and the scene name a
  /// recording stores when the level is built in code ("NAME (built in code)").
  std::string name;
  /// What the game is, one line (--help's first line).
  std::string description{};
  /// The version of the game's rules (>= 1), written with the name into every recording the
  /// game makes (Recording::rules_name, rules_version; the name with each character outside
  /// letters, digits, '.', '_' and '-' made '_'). Raise it when a change to the rules would
  /// replay older recordings differently: --replay refuses a recording of other rules, naming
  /// both, and `fixstep replay` refuses any recording that needs rules.
  std::uint32_t rules_version = 1;
  /// The level's scene file (TOML, fixstep/scene/scene.hpp), loaded at start and for each replay
  /// that carries no scene text; --scene FILE replaces it. Empty: no file, setup() builds the
  /// level from an empty WorldDef.
  std::string scene_file{};
  int width = 1280, height = 720;  ///< frame size, pixels
  /// The view: centre (m) and visible width (m); default: the scene's [view], else a view that
  /// fits the world (fit_camera).
  std::optional<Vec2> view_center{};
  std::optional<double> view_width{};
  /// The name of a body the view keeps at the centre of the frame (Session::follow), in every
  /// mode, from the first frame and after a restart; empty: the view stays put. A level
  /// without a body of that name is an error (exit 1).
  std::string follow{};
  /// The game's keys, shown at the bottom of the window's HUD (e.g. "arrows: move  enter: jump").
  std::string controls{};
  /// The game's actions: a name, a bit of TickInput::held / pressed / released, and the keys,
  /// mouse buttons and gamepad buttons bound to it (fixstep/render/input_map.hpp). Empty:
  /// fixstep's default actions (default_actions(): the arrows, Enter, the mouse buttons). A
  /// game that drags with the pointer binds Key::mouse_left to button_pointer_primary itself.
  /// --input scripts press and release actions by these names.
  std::vector<ActionBinding> actions{};
  /// The game's analogue axes (TickInput::axes): gamepad axes, and key pairs reading -1 / +1.
  std::vector<AxisBinding> axes{};
  /// The loop's keys: pause, step, faster, slower, restart, rewind, quit. A key the game's
  /// actions bind is not a loop key (the game's jump on space leaves pause without a key:
  /// rebind it here).
  std::vector<LoopBinding> loop_keys = default_loop_bindings();
  /// Run rules() before each tick's step instead of after it (input → rules → step): what a
  /// key does in rules() then acts in the same tick (a flipper's motor set by a key moves it in
  /// the tick the key went down). The same order live, in replay, the sync test and networked
  /// play; a recording's hashes are taken after the step either way. Changing it changes what
  /// a recording replays to: raise rules_version.
  bool rules_before_step = false;
  /// Shows the HUD's energy line. Off by default: a game's input and rules add energy from
  /// outside the world's account, so its balance would measure them, not the integrator.
  bool show_energy = false;
  // The view's look. Each, when set, replaces what the scene's [view] table says (background,
  // grid, axes, scale_bar and joints together; hud; hud_scale; hud_lines); unset, the scene's
  // keys, else the defaults, apply (SessionSettings).
  /// Background colour, grid, axes, scale bar and how joints are drawn.
  std::optional<ViewStyle> style{};
  /// The HUD's corner; `show_hud` false hides it all (the game's text() lines included).
  std::optional<HudCorner> hud_corner{};
  std::optional<bool> show_hud{};
  /// The HUD's text scale, px per font pixel, in [1, 4] (else run() exits 1).
  std::optional<float> hud_text_scale{};
  /// Which engine lines the HUD may show (HudLine bits of fixstep/app/session.hpp).
  std::optional<unsigned> hud_lines{};
  /// Networked play (fixstep::net::run): the most players the game seats, 2–8; a host's
  /// --players may ask for up to this many (else exit 2). seat() and merge() see players
  /// 0 .. N-1.
  int max_players = 2;
};

/// What a type needs to be run: copyable, with setup() and rules() (see the top of this file).
template <class G>
concept Game = std::copy_constructible<G> && std::is_copy_assignable_v<G> &&
    requires(G g, WorldDef& level, World& world, const TickInput& input) {
  g.setup(level);
  g.rules(world, input);
};

/// Runs `game` as its command line asks, and returns the process's exit status:
///
///   NAME                                play in a window until Esc or the close button
///   NAME --frames N [--out DIR]         N frames headless on a 60 Hz virtual clock, the
///                                       autopilot playing; PNG frames into DIR, with
///                                       DIR/frames.csv (each frame's tick, hash, energy)
///   NAME --frames N --input SCRIPT      ... the script playing instead (an input script,
///                                       docs/CLI.md: its press / release name the game's
///                                       actions, its axes the game's axes); also with
///                                       --window, --record and --sync-test
///   NAME --window --frames N            N frames in the window, then quit
///   NAME --frames N --last-frame PNG    ... and the last frame (headless or in the window)
///   NAME ... --record FILE              record the session (the input, a state hash a tick)
///   NAME --replay FILE [--out DIR [--every K]] [--last-frame PNG]
///                                       re-simulate a recording with the rules, verify every
///                                       stored hash, then draw it: frames 0, K, 2K, ... and
///                                       the last, each named by its frame index
///                                       (DIR/frame_000000.png, frame_00000K.png, ...) and
///                                       listed with its tick in DIR/frames.csv
///   NAME --diff A.rec B.rec             where two recordings first differ: inputs, stored
///                                       hashes, and (both replayed side by side with the
///                                       rules) the first tick, body and field
///   NAME --frames N --sync-test K       N frames headless, each tick rolled back K ticks and
///                                       re-simulated (the game's state with the world's)
///   --overwrite                         with --out: replace the capture DIR already holds
///   --scene FILE                        another level (only when the game has a scene file:
///                                       refused for a level built in code, which setup()
///                                       would put in its place)
///   --help                              the above, and the bounds below
///
/// Every output (--record, --last-frame, --out DIR) gets the fixstep command's checks before
/// anything runs (check_output_paths, fixstep/io/output_paths.hpp): not an input, not another
/// output, not a directory or socket, and a --out DIR holding an earlier capture only with
/// --overwrite. Bounds, checked before the first tick (exit 1, naming the flag): --frames N
/// within max_command_ticks and max_command_work (fixstep/io/command_limits.hpp; under
/// --sync-test K each tick counts 1 + K times, and its K + 1 snapshots within
/// max_sync_test_bytes), a --replay's ticks likewise, --frames N --record within
/// max_recording_bytes of hashes. --record is streamed to its file (RecordingWriter). SIGINT and
/// SIGTERM stop every mode within a second: the recording written up to its last complete
/// tick, the frames drawn whole, exit 128 + the signal.
///
/// Exit status: 0 success; 1 an error (a bad scene, an unreadable or cut recording, an
/// unwritable output, a bound exceeded, no display, standard output closed or failing), its
/// message on standard error naming the file or flag; 2 a bad command line or a refused output
/// path; 4 a replay whose state differs from the recording's (naming the first tick, both hashes
/// and the last tick that matched; nothing is drawn) or a --diff of two recordings that differ;
/// 8 a sync test that found a difference;
/// 130 / 143 stopped by SIGINT / SIGTERM. Never throws.
template <Game G>
int run(G game, const Settings& settings, int argc, char** argv) {
  return detail::run_game(detail::GameModel<G>(std::move(game)), settings, argc, argv);
}

}  // namespace fixstep::app
