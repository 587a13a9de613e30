#include "fixstep/window.hpp"

#include <SDL.h>
#include <fmt/format.h>

#include <cstdlib>
#include <string>

namespace fixstep {

struct Window::Impl {
  SDL_Window* window = nullptr;
  SDL_Renderer* renderer = nullptr;
  SDL_Texture* texture = nullptr;
  int width = 0, height = 0;
};

namespace {
void release(Window::Impl*& impl) {
  if (!impl) return;
  if (impl->texture) SDL_DestroyTexture(impl->texture);
  if (impl->renderer) SDL_DestroyRenderer(impl->renderer);
  if (impl->window) SDL_DestroyWindow(impl->window);
  SDL_Quit();
  delete impl;
  impl = nullptr;
}

bool has_display() {
  auto set = [](const char* name) {
    const char* v = std::getenv(name);
    return v && *v;
  };
  return set("DISPLAY") || set("WAYLAND_DISPLAY") || set("SDL_VIDEODRIVER");
}
}  // namespace

Window::Window(const std::string& title, int width, int height) : impl_(new Impl) {
  if (!has_display()) {
    delete impl_;
    throw WindowError(
        "no display: DISPLAY and WAYLAND_DISPLAY are not set, so no window can open. "
        "Capture frames headless instead: fixstep render SCENE --out DIR");
  }
  // SDL's own software renderer: it copies our pixels to the window surface. A GL-based SDL
  // renderer would load libGL next to libOSMesa, and both export the same gl* symbols.
  SDL_SetHint(SDL_HINT_RENDER_DRIVER, "software");
  // ...and its window surface must not be "accelerated" either: by default SDL backs it with an
  // OpenGL texture, which loads libGL/GLX beside libOSMesa and crashes inside Mesa (seen under
  // Xvfb). "0" keeps the plain X11/Wayland framebuffer.
  SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    const std::string why = SDL_GetError();
    SDL_Quit();
    delete impl_;
    throw WindowError(
        fmt::format("SDL could not initialise video ({}). Without a display, use: fixstep render "
                    "SCENE --out DIR",
                    why));
  }
  // SDL 2.26 falls back to its "offscreen" (or "dummy") driver when it cannot reach the
  // display named by DISPLAY / WAYLAND_DISPLAY: the window would exist but never be seen. Only
  // accept those drivers when SDL_VIDEODRIVER asks for them by name.
  const std::string driver = SDL_GetCurrentVideoDriver() ? SDL_GetCurrentVideoDriver() : "";
  const char* requested = std::getenv("SDL_VIDEODRIVER");
  if ((driver == "offscreen" || driver == "dummy") && !(requested && driver == requested)) {
    SDL_Quit();
    delete impl_;
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    throw WindowError(fmt::format(
        "no display: could not connect to {} (SDL fell back to its '{}' driver, which shows "
        "nothing). Start an X server or use: fixstep render SCENE --out DIR",
        display && *display ? fmt::format("DISPLAY={}", display)
                            : fmt::format("WAYLAND_DISPLAY={}", wayland ? wayland : ""),
        driver));
  }
  impl_->width = width;
  impl_->height = height;
  impl_->window = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                   width, height, 0);
  if (impl_->window) {
    impl_->renderer = SDL_CreateRenderer(impl_->window, -1, SDL_RENDERER_SOFTWARE);
  }
  if (impl_->renderer) {
    impl_->texture = SDL_CreateTexture(impl_->renderer, SDL_PIXELFORMAT_ABGR8888,
                                       SDL_TEXTUREACCESS_STREAMING, width, height);
  }
  if (!impl_->texture) {
    const std::string why = SDL_GetError();
    release(impl_);
    throw WindowError(fmt::format("SDL could not create a {}x{} window: {}", width, height, why));
  }
}

Window::~Window() {
  release(impl_);
}

std::string Window::driver() const {
  const char* d = SDL_GetCurrentVideoDriver();
  return d ? d : "none";
}

WindowEvents Window::poll() {
  WindowEvents ev;
  SDL_Event e;
  while (SDL_PollEvent(&e)) {
    if (e.type == SDL_QUIT) ev.quit = true;
    if (e.type != SDL_KEYDOWN) continue;
    switch (e.key.keysym.sym) {
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
  const Uint8* keys = SDL_GetKeyboardState(nullptr);
  ev.push_direction.x = double(keys[SDL_SCANCODE_RIGHT]) - double(keys[SDL_SCANCODE_LEFT]);
  ev.push_direction.y = double(keys[SDL_SCANCODE_UP]) - double(keys[SDL_SCANCODE_DOWN]);
  return ev;
}

void Window::present(std::span<const std::uint8_t> rgba) {
  if (rgba.size() != static_cast<std::size_t>(impl_->width) * impl_->height * 4) {
    throw WindowError("window: frame size does not match the window");
  }
  // ABGR8888 is R,G,B,A byte order in memory on little-endian machines: the renderer's layout.
  SDL_UpdateTexture(impl_->texture, nullptr, rgba.data(), impl_->width * 4);
  SDL_RenderClear(impl_->renderer);
  SDL_RenderCopy(impl_->renderer, impl_->texture, nullptr, nullptr);
  SDL_RenderPresent(impl_->renderer);
}

}  // namespace fixstep
