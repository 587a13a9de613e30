// fixstep in a web page: the page's parameters (page_options.hpp) pick what runs, PageApp runs
// it one browser frame at a time under emscripten_set_main_loop. Interactive pages are driven by
// requestAnimationFrame; headless runs (frames=, ticks=, replay= with headless=1) by timers,
// since headless Chromium's virtual time runs timers but not animation frames, and their
// results do not depend on the browser's clock (a virtual one: exactly 1/fps per frame).
#include <emscripten/emscripten.h>

#include <exception>
#include <memory>
#include <string>

#include "page_app.hpp"
#include "page_dom.hpp"
#include "page_options.hpp"

namespace {

std::unique_ptr<fixstep::web::PageApp> app;  // the page's one program, for its lifetime

void stop_with_error(const std::string& message) {
  fixstep::web::show_error(message);
  emscripten_cancel_main_loop();
}

void one_frame() {
  try {
    if (!app->frame(emscripten_get_now())) emscripten_cancel_main_loop();
  } catch (const std::exception& e) {
    stop_with_error(e.what());
  }
}

void fetched(void*, void* data, int size) {
  try {
    app->recording_fetched(std::string(static_cast<const char*>(data), std::size_t(size)));
  } catch (const std::exception& e) {
    stop_with_error(e.what());
  }
}

void fetch_failed(void*) {
  app->recording_failed("not found or not readable");
}

void script_fetched(void*, void* data, int size) {
  try {
    app->script_fetched(std::string(static_cast<const char*>(data), std::size_t(size)));
  } catch (const std::exception& e) {
    stop_with_error(e.what());
  }
}

void script_failed(void*) {
  stop_with_error("could not fetch the input script: not found or not readable");
}

}  // namespace

int main() {
  fixstep::web::PageOptions options;
  try {
    options = fixstep::web::parse_page_options(fixstep::web::page_query());
    app = std::make_unique<fixstep::web::PageApp>(options);
  } catch (const std::exception& e) {
    fixstep::web::show_error(e.what());
    return 0;
  }
  if (options.replay)
    emscripten_async_wget_data(options.replay->c_str(), nullptr, fetched, fetch_failed);
  if (options.input) {
    emscripten_async_wget_data(options.input->c_str(), nullptr, script_fetched, script_failed);
  }
  emscripten_set_main_loop(one_frame, 0, false);  // requestAnimationFrame
  if (options.headless && (options.frames || options.ticks || options.replay)) {
    emscripten_set_main_loop_timing(EM_TIMING_SETTIMEOUT, 0);
  }
  return 0;
}
