// What the page shows outside the canvas: text in its elements, its title, the scene selector.
// The browser tests (tests/web/) read the results from here. Web platform (wasm only).
#pragma once

#include <string>
#include <vector>

#include "fixstep/core/recording.hpp"  // ReplayReport

namespace fixstep::web {

/// Sets the text of the page's element with id `id` (nothing if there is none).
void show_text(const char* id, const std::string& text);
/// Sets document.title: how a harness knows the page has finished ("fixstep: done",
/// "fixstep: error").
void set_title(const std::string& title);
/// Fills the page's scene selector (id "scene") with `names`, `current` selected (an empty
/// `current`: an empty entry first, selected); choosing another one reloads the page with
/// ?scene=NAME.
void list_scenes(const std::vector<std::string>& names, const std::string& current);
/// Shows `message` as the page's result (id "result"), "error: " first, and sets the title to
/// "fixstep: error".
void show_error(const std::string& message);
/// Shows a verified replay's verdict as the page's result (id "result"): "verified ticks=N
/// state_hash=H hashes=K", or, for a recording that diverged, the first tick, both hashes and
/// the last tick that matched, with the title "fixstep: diverged". Returns whether it verified
/// (a diverged recording is not played back, as `fixstep render --replay` and `NAME --replay`).
bool show_replay_verdict(const ReplayReport& r);

}  // namespace fixstep::web
