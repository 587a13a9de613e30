#include "fixstep/window/window.hpp"

#include <SDL.h>
#include <fmt/format.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <utility>

#include "fixstep/core/input.hpp"
#include "sdl_keys.hpp"

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
        height(height) {
    // Gamepads where SDL finds any: without the subsystem (or a device) there is none, which
    // is no error. SDL reports each controller present now as an added device.
    (void)SDL_InitSubSystem(SDL_INIT_GAMECONTROLLER);
  }

  SdlVideo video;
  SdlWindow window;
  SdlRenderer renderer;
  SdlTexture texture;
  int width, height;
  InputMap map = default_input_map();
  SDL_GameController* pad = nullptr;  ///< the first game controller, or none

  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (pad != nullptr) SDL_GameControllerClose(pad);
  }
};

Window::Window(const std::string& title, int width, int height)
    : impl_(std::make_unique<Impl>(title, width, height)) {}

Window::~Window() = default;

std::string Window::driver() const {
  const char* d = SDL_GetCurrentVideoDriver();
  return d ? d : "none";
}

namespace {

void add_key(WindowEvents& ev, bool press, Key key) {
  if (key == Key::none) return;
  ev.keys.push_back({press, key});
  ev.keys_down[static_cast<std::size_t>(key)] = press;
}

}  // namespace

WindowEvents Window::poll() {
  WindowEvents ev;
  poll(ev);
  return ev;
}

void Window::set_input_map(InputMap map) {
  impl_->map = std::move(map);
}

void Window::open_pad(int device) {
  if (impl_->pad != nullptr || !SDL_IsGameController(device)) return;
  impl_->pad = SDL_GameControllerOpen(device);  // the first one only; nullptr: none
}

void Window::poll(WindowEvents& ev) {
  ev.close_requested = false;
  ev.keys.clear();
  SDL_Event e;
  while (SDL_PollEvent(&e)) {
    switch (e.type) {
      case SDL_QUIT:
        ev.close_requested = true;
        break;
      case SDL_KEYDOWN:
      case SDL_KEYUP:
        if (!e.key.repeat) {
          add_key(ev, e.type == SDL_KEYDOWN, detail::sdl_scancode_key(e.key.keysym.scancode));
        }
        break;
      case SDL_MOUSEBUTTONDOWN:
      case SDL_MOUSEBUTTONUP:
        add_key(ev, e.type == SDL_MOUSEBUTTONDOWN, detail::sdl_mouse_key(e.button.button));
        ev.pointer_seen = true;
        ev.pointer_x = e.button.x + 0.5, ev.pointer_y = e.button.y + 0.5;
        break;
      case SDL_MOUSEMOTION:
        ev.pointer_seen = true;
        ev.pointer_x = e.motion.x + 0.5, ev.pointer_y = e.motion.y + 0.5;
        break;
      case SDL_CONTROLLERDEVICEADDED:
        open_pad(e.cdevice.which);
        break;
      case SDL_CONTROLLERBUTTONDOWN:
      case SDL_CONTROLLERBUTTONUP:
        add_key(ev, e.type == SDL_CONTROLLERBUTTONDOWN, detail::sdl_pad_key(e.cbutton.button));
        break;
      case SDL_CONTROLLERAXISMOTION:
        if (e.caxis.axis < pad_axis_count) {
          ev.pad_axes[e.caxis.axis] = pad_axis_value(e.caxis.value);
        }
        break;
      default:
        break;
    }
  }
  impl_->map.apply(ev);
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
