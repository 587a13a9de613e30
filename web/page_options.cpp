// The page's URL parameters (page_options.hpp).
#include "page_options.hpp"

#include <emscripten/emscripten.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace fixstep::web {

namespace {

constexpr std::uint64_t max_count = 1'000'000'000;

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// URL query decoding: '+' is a space, %XX a byte (a malformed escape stays as it is).
std::string decoded(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out.push_back(' ');
    } else if (s[i] == '%' && i + 2 < s.size() && hex_digit(s[i + 1]) >= 0 &&
               hex_digit(s[i + 2]) >= 0) {
      out.push_back(static_cast<char>(hex_digit(s[i + 1]) * 16 + hex_digit(s[i + 2])));
      i += 2;
    } else {
      out.push_back(s[i]);
    }
  }
  return out;
}

std::uint64_t parse_count(const std::string& name, const std::string& value) {
  char* end = nullptr;
  const unsigned long long n = std::strtoull(value.c_str(), &end, 10);
  if (value.empty() || value[0] == '-' || *end != '\0' || n < 1 || n > max_count) {
    throw std::invalid_argument(
        fmt::format("{}={}: must be a whole number in 1..{}", name, value, max_count));
  }
  return n;
}

double parse_fps(const std::string& value) {
  // strtod reads '.' as the decimal point in the "C" locale, the one a wasm program starts in.
  char* end = nullptr;
  const double fps = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(fps) || !(fps > 0.0)) {
    throw std::invalid_argument(fmt::format("fps={}: must be a number > 0", value));
  }
  return fps;
}

void parse_size(const std::string& value, PageOptions& o) {
  const std::size_t x = value.find('x');
  const auto side = [&](const std::string& s) {
    char* end = nullptr;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || v < 16 || v > 8192) {
      throw std::invalid_argument(
          fmt::format("size={}: must be WIDTHxHEIGHT, 16..8192 px each", value));
    }
    return static_cast<int>(v);
  };
  if (x == std::string::npos) side("");
  o.width = side(value.substr(0, x));
  o.height = side(value.substr(x + 1));
  o.size_given = true;
}

bool parse_flag(const std::string& name, const std::string& value) {
  if (value == "1" || value == "true") return true;
  if (value == "0" || value == "false") return false;
  throw std::invalid_argument(fmt::format("{}={}: must be 1 or 0", name, value));
}

void set(PageOptions& o, const std::string& name, const std::string& value) {
  if (name == "scene") {
    // A shipped scene, or one of the cross-platform cause scenes (tests/scenes/cross, preloaded
    // as assets/scenes/cross) the browser checks step: cross/NAME.toml.
    const std::string file = value.starts_with("cross/") ? value.substr(6) : value;
    if (file.find('/') != std::string::npos || !file.ends_with(".toml")) {
      throw std::invalid_argument(fmt::format(
          "scene={}: must name a shipped scene (a file of assets/scenes, e.g. default.toml) or "
          "cross/NAME.toml (tests/scenes/cross)",
          value));
    }
    o.scene = value;
  } else if (name == "frames") {
    o.frames = parse_count(name, value);
  } else if (name == "ticks") {
    o.ticks = parse_count(name, value);
  } else if (name == "replay") {
    o.replay = value;
  } else if (name == "input") {
    o.input = value;
  } else if (name == "fps") {
    o.fps = parse_fps(value);
  } else if (name == "record") {
    o.record = parse_flag(name, value);
  } else if (name == "hash_every") {
    o.hash_every = parse_count(name, value);
  } else if (name == "size") {
    parse_size(value, o);
  } else if (name == "headless") {
    o.headless = parse_flag(name, value);
  } else if (name == "game") {
    if (std::find(page_game_names.begin(), page_game_names.end(), value) == page_game_names.end()) {
      // "a, b or c"
      const auto all_but_last = std::span(page_game_names).first(page_game_names.size() - 1);
      throw std::invalid_argument(fmt::format("game={}: must be {} or {}", value,
                                              fmt::join(all_but_last, ", "),
                                              page_game_names.back()));
    }
    o.game = value;
  } else if (name == "overlay") {
    if (value != "card") {
      throw std::invalid_argument(
          fmt::format("overlay={}: must be card (the overlay test card)", value));
    }
    o.overlay_card = true;
  } else {
    throw std::invalid_argument(fmt::format(
        "unknown parameter '{}' (known: scene, frames, ticks, replay, input, fps, record, "
        "hash_every, size, headless, overlay, game)",
        name));
  }
}

/// game=: what a game takes besides itself (its level is its own, its clock 60 Hz).
bool applies_to_game(const std::string& name) {
  return name == "game" || name == "frames" || name == "replay" || name == "input" ||
         name == "size" || name == "headless";
}

}  // namespace

PageOptions parse_page_options(std::string_view query) {
  if (query.starts_with('?')) query.remove_prefix(1);
  PageOptions o;
  std::vector<std::string> given;  // the parameters' names, in order
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    if (pair.empty()) continue;
    const std::size_t eq = pair.find('=');
    const std::string name = decoded(pair.substr(0, eq));
    const std::string value = eq == std::string_view::npos ? "" : decoded(pair.substr(eq + 1));
    set(o, name, value);
    given.push_back(name);
  }
  if (o.game) {
    for (const std::string& name : given) {
      if (!applies_to_game(name)) {
        throw std::invalid_argument(
            fmt::format("{}= does not apply to game={}: a game takes frames=, replay=, input=, "
                        "size= and headless= only",
                        name, *o.game));
      }
    }
  }
  if (int(o.frames.has_value()) + int(o.ticks.has_value()) + int(o.replay.has_value()) > 1) {
    throw std::invalid_argument("give at most one of frames=, ticks= and replay=");
  }
  if (o.input && !(o.game && o.frames)) {
    throw std::invalid_argument("input= needs game= and frames= (a game's scripted run)");
  }
  if (o.record && !o.frames && !o.ticks) {
    throw std::invalid_argument("record=1 needs frames= or ticks=");
  }
  return o;
}

std::string page_query() {
  char* query = emscripten_run_script_string("location.search");
  return query ? std::string(query) : std::string();
}

}  // namespace fixstep::web
