// The page's elements (page_dom.hpp), through small JavaScript functions (emscripten EM_JS).
#include "page_dom.hpp"

#include <emscripten/emscripten.h>
#include <fmt/format.h>

#include "fixstep/io/summary.hpp"  // hex_hash

namespace {

// clang-format off
EM_JS(void, js_show_text, (const char* id, const char* text), {
  const e = document.getElementById(UTF8ToString(id));
  if (e) e.textContent = UTF8ToString(text);
});
EM_JS(void, js_set_title, (const char* title), {
  document.title = UTF8ToString(title);
});
EM_JS(void, js_add_scene, (const char* name, int selected), {
  const s = document.getElementById("scene");
  if (!s) return;
  const o = document.createElement("option");
  o.value = o.textContent = UTF8ToString(name);
  o.selected = selected != 0;
  s.appendChild(o);
});
// clang-format on

}  // namespace

namespace fixstep::web {

void show_text(const char* id, const std::string& text) {
  js_show_text(id, text.c_str());
}

void set_title(const std::string& title) {
  js_set_title(title.c_str());
}

void list_scenes(const std::vector<std::string>& names, const std::string& current) {
  show_text("scene", "");
  if (current.empty()) js_add_scene("", 1);  // a game is playing: no scene chosen
  for (const std::string& name : names) js_add_scene(name.c_str(), name == current ? 1 : 0);
}

void show_error(const std::string& message) {
  show_text("result", "error: " + message);
  set_title("fixstep: error");
}

bool show_replay_verdict(const ReplayReport& r) {
  if (const auto& m = r.mismatch) {
    show_text("result",
              fmt::format("diverged at tick {}: state_hash {} recorded, {} replayed "
                          "(the states matched at tick {}); not played back",
                          m->tick, hex_hash(m->expected), hex_hash(m->actual), m->last_match));
    set_title("fixstep: diverged");
    return false;
  }
  show_text("result", fmt::format("verified ticks={} state_hash={} hashes={}", r.ticks,
                                  hex_hash(r.final_hash), r.verified));
  return true;
}

}  // namespace fixstep::web
