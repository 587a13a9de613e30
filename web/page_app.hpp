// The page's program: `fixstep view`'s loop in a browser (a Session drawn on the WebGL2 canvas,
// the browser's keys and pointer, rewind), and the headless runs the browser tests drive
// (frames=, ticks=, replay=: page_options.hpp). Web platform (wasm only).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/app/session.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/pointer_drag.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/rewind.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/render/draw_list.hpp"
#include "fixstep/scene/scene.hpp"
#include "page_game.hpp"
#include "page_input.hpp"
#include "page_options.hpp"

namespace fixstep::web {

/// Where the page's shipped scenes are (the site preloads assets/scenes there).
inline constexpr const char* scene_dir = "assets/scenes";

/// The shipped scenes' file names, sorted.
[[nodiscard]] std::vector<std::string> shipped_scenes();

class PageApp {
 public:
  /// Loads the scene (or, for replay=, starts fetching the recording) and builds the session
  /// on the page's canvas; with game=, starts the game instead (PageGame). Throws what the
  /// scene loader, the stability guard or Session throw.
  explicit PageApp(PageOptions options);
  ~PageApp();
  PageApp(const PageApp&) = delete;
  PageApp& operator=(const PageApp&) = delete;

  /// One browser frame at time `now_ms` (performance.now(), ms). Returns false once the page
  /// has finished (a headless run reported its result): the main loop stops.
  bool frame(double now_ms);

  /// replay=: the fetched recording's text arrived (emscripten_async_wget_data), or failed.
  void recording_fetched(std::string text);
  /// input=: the fetched input script's text (a game's frames= run waits for it).
  void script_fetched(const std::string& text);
  void recording_failed(const std::string& why);

 private:
  void start_session(WorldDef def, const std::string& title);
  void interactive_frame(double now_ms);
  bool frames_frame();
  bool ticks_frame(double now_ms);
  bool replay_frame();
  /// Writes the run's result: "tick=N state_hash=H" (id result), the summary line `fixstep run`
  /// prints (id summary), the recording's text when recording (id recording); title "done".
  void report();

  /// Draws the frame: with the overlay test card over it when asked (overlay=card).
  void draw();

  PageOptions o_;
  std::unique_ptr<PageGame> game_;  ///< game=: the page plays a game instead of a scene
  DrawList card_;                   ///< overlay=card's shapes, recorded each frame about the view
  std::string scene_file_;          ///< assets/scenes/NAME
  std::optional<Scene> scene_;
  std::unique_ptr<Session> session_;
  std::uint64_t frames_done_ = 0;
  std::optional<Recorder> recorder_;
  // interactive
  std::unique_ptr<PageInput> input_;
  InputSampler sampler_;
  RewindBuffer rewind_{1};
  PointerDrag drag_{0.0};
  double last_ms_ = -1.0;
  // replay
  std::optional<Recording> recording_;
  bool replay_stopped_ = false;  ///< the fetch failed or the recording diverged: nothing to play
};

}  // namespace fixstep::web
