#include "fixstep/window/window.hpp"

#include <SDL.h>
#include <fmt/format.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <utility>

#include "fixstep/core/input.hpp"

namespace fixstep {

namespace {

// Owning handles for SDL's objects: each destructor only releases (noexcept).

/// SDL's video subsystem, initialised (with fixstep's hints) for the handle's lifetime.
class SdlVideo {
 public:
  /// SDL_Init(SDL_INIT_VIDEO). Throws WindowError "SDL could not initialise video (WHY)".
  SdlVideo();
  ~SdlVideo() {
    if (active_) SDL_Quit();
  }
  SdlVideo(SdlVideo&& other) noexcept : active_(std::exchange(other.active_, false)) {}
  SdlVideo& operator=(SdlVideo&&) = delete;

 private:
  bool active_ = false;
};

struct DestroyWindow {
  void operator()(SDL_Window* w) const noexcept { SDL_DestroyWindow(w); }
};
struct DestroyRenderer {
  void operator()(SDL_Renderer* r) const noexcept { SDL_DestroyRenderer(r); }
};
struct DestroyTexture {
  void operator()(SDL_Texture* t) const noexcept { SDL_DestroyTexture(t); }
};
using SdlWindow = std::unique_ptr<SDL_Window, DestroyWindow>;
using SdlRenderer = std::unique_ptr<SDL_Renderer, DestroyRenderer>;
using SdlTexture = std::unique_ptr<SDL_Texture, DestroyTexture>;

SdlVideo::SdlVideo() {
  // SDL's own software renderer: it copies our pixels to the window surface. A GL-based SDL
  // renderer would load libGL next to libOSMesa, and both export the same gl* symbols.
  SDL_SetHint(SDL_HINT_RENDER_DRIVER, "software");
  // ...and its window surface must not be "accelerated" either: by default SDL backs it with an
  // OpenGL texture, which loads libGL/GLX beside libOSMesa and crashes inside Mesa (seen under
  // Xvfb). "0" keeps the plain X11/Wayland framebuffer.
  SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    const std::string why = SDL_GetError();
    SDL_Quit();  // whatever SDL_Init set up before it failed
    throw WindowError(fmt::format("SDL could not initialise video ({})", why));
  }
  active_ = true;
}

bool has_display() {
  auto set = [](const char* name) {
    const char* v = std::getenv(name);
    return v && *v;
  };
  return set("DISPLAY") || set("WAYLAND_DISPLAY") || set("SDL_VIDEODRIVER");
}

// SDL 2.26 falls back to its "offscreen" (or "dummy") driver when it cannot reach the display
// named by DISPLAY / WAYLAND_DISPLAY: the window would exist but never be seen. Only accept
// those drivers when SDL_VIDEODRIVER asks for them by name.
void check_driver_shows_windows() {
  const std::string driver = SDL_GetCurrentVideoDriver() ? SDL_GetCurrentVideoDriver() : "";
  const char* requested = std::getenv("SDL_VIDEODRIVER");
  if ((driver == "offscreen" || driver == "dummy") && !(requested && driver == requested)) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    throw WindowError(fmt::format(
        "no display: could not connect to {} (SDL fell back to its '{}' driver, which shows "
        "nothing)",
        display && *display ? fmt::format("DISPLAY={}", display)
                            : fmt::format("WAYLAND_DISPLAY={}", wayland ? wayland : ""),
        driver));
  }
}

// SDL's video, on a driver that shows windows. Throws WindowError.
SdlVideo open_video() {
  if (!has_display()) {
    throw WindowError("no display: DISPLAY and WAYLAND_DISPLAY are not set, so no window can open");
  }
  SdlVideo video;
  check_driver_shows_windows();  // throws: `video` quits SDL on the way out
  return video;
}

SdlWindow create_window(const std::string& title, int width, int height) {
  SdlWindow window(SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                    width, height, 0));
  if (!window) {
    throw WindowError(
        fmt::format("SDL could not create a {}x{} window: {}", width, height, SDL_GetError()));
  }
  return window;
}

SdlRenderer create_renderer(SDL_Window& window) {
  SdlRenderer renderer(SDL_CreateRenderer(&window, -1, SDL_RENDERER_SOFTWARE));
  if (!renderer) {
    throw WindowError(
        fmt::format("SDL could not create a software renderer for the window: {}", SDL_GetError()));
  }
  return renderer;
}

// ABGR8888 is R,G,B,A byte order in memory on little-endian machines: the renderer's layout.
SdlTexture create_texture(SDL_Renderer& renderer, int width, int height) {
  SdlTexture texture(SDL_CreateTexture(&renderer, SDL_PIXELFORMAT_ABGR8888,
                                       SDL_TEXTUREACCESS_STREAMING, width, height));
  if (!texture) {
    throw WindowError(fmt::format("SDL could not create a {}x{} texture for the window: {}", width,
                                  height, SDL_GetError()));
  }
  return texture;
}

}  // namespace

// Members in acquisition order: if a step throws, the ones built so far are released in
// reverse (the texture before its renderer, the renderer before its window, SDL_Quit last).
struct Window::Impl {
  Impl(const std::string& title, int width, int height)
      : video(open_video()),
        window(create_window(title, width, height)),
        renderer(create_renderer(*window)),
        texture(create_texture(*renderer, width, height)),
        width(width),
        height(height) {}

  SdlVideo video;
  SdlWindow window;
  SdlRenderer renderer;
  SdlTexture texture;
  int width, height;
};

Window::Window(const std::string& title, int width, int height)
    : impl_(std::make_unique<Impl>(title, width, height)) {}

Window::~Window() = default;

std::string Window::driver() const {
  const char* d = SDL_GetCurrentVideoDriver();
  return d ? d : "none";
}

namespace {

/// The InputButton bit of a key, or 0.
std::uint32_t key_button(SDL_Keycode key) {
  switch (key) {
    case SDLK_LEFT:
      return button_left;
    case SDLK_RIGHT:
      return button_right;
    case SDLK_UP:
      return button_up;
    case SDLK_DOWN:
      return button_down;
    case SDLK_RETURN:
    case SDLK_KP_ENTER:
      return button_action;
    default:
      return 0;
  }
}

std::uint32_t mouse_button(Uint8 button) {
  if (button == SDL_BUTTON_LEFT) return button_pointer_primary;
  if (button == SDL_BUTTON_RIGHT) return button_pointer_secondary;
  return 0;
}

/// The window's own keys (pause, step, speed, restart, quit).
void window_key(SDL_Keycode key, WindowEvents& ev) {
  switch (key) {
    case SDLK_ESCAPE:
      ev.quit = true;
      break;
    case SDLK_SPACE:
      ev.toggle_pause = true;
      break;
    case SDLK_PERIOD:
      ev.single_step = true;
      break;
    case SDLK_PLUS:
    case SDLK_EQUALS:
    case SDLK_KP_PLUS:
      ++ev.time_scale_steps;
      break;
    case SDLK_MINUS:
    case SDLK_KP_MINUS:
      --ev.time_scale_steps;
      break;
    case SDLK_r:
      ev.restart = true;
      break;
    default:
      break;
  }
}

void add_edge(WindowEvents& ev, bool press, std::uint32_t buttons) {
  if (buttons != 0) ev.edges.push_back({press, buttons});
}

}  // namespace

WindowEvents Window::poll() {
  WindowEvents ev;
  poll(ev);
  return ev;
}

void Window::poll(WindowEvents& ev) {
  ev.quit = ev.toggle_pause = ev.single_step = ev.restart = false;
  ev.time_scale_steps = 0;
  ev.edges.clear();
  SDL_Event e;
  while (SDL_PollEvent(&e)) {
    switch (e.type) {
      case SDL_QUIT:
        ev.quit = true;
        break;
      case SDL_KEYDOWN:
        if (!e.key.repeat) add_edge(ev, true, key_button(e.key.keysym.sym));
        window_key(e.key.keysym.sym, ev);
        break;
      case SDL_KEYUP:
        add_edge(ev, false, key_button(e.key.keysym.sym));
        break;
      case SDL_MOUSEBUTTONDOWN:
      case SDL_MOUSEBUTTONUP:
        add_edge(ev, e.type == SDL_MOUSEBUTTONDOWN, mouse_button(e.button.button));
        ev.pointer_seen = true;
        ev.pointer_x = e.button.x + 0.5, ev.pointer_y = e.button.y + 0.5;
        break;
      case SDL_MOUSEMOTION:
        ev.pointer_seen = true;
        ev.pointer_x = e.motion.x + 0.5, ev.pointer_y = e.motion.y + 0.5;
        break;
      default:
        break;
    }
  }
  const Uint8* keys = SDL_GetKeyboardState(nullptr);
  ev.rewind = keys[SDL_SCANCODE_BACKSPACE] != 0;
}

void Window::present(std::span<const std::uint8_t> rgba) {
  if (rgba.size() != static_cast<std::size_t>(impl_->width) * impl_->height * 4) {
    throw WindowError("window: frame size does not match the window");
  }
  SDL_UpdateTexture(impl_->texture.get(), nullptr, rgba.data(), impl_->width * 4);
  SDL_RenderClear(impl_->renderer.get());
  SDL_RenderCopy(impl_->renderer.get(), impl_->texture.get(), nullptr, nullptr);
  SDL_RenderPresent(impl_->renderer.get());
}

}  // namespace fixstep
