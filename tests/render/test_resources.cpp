// Resource safety of Renderer and Window: each failure of their construction, provoked
// after some resources were acquired, throws the right error with the right message and leaves
// nothing behind; destructors never throw.
//
// Under the asan preset LeakSanitizer checks every test process at exit. It sees SDL's
// allocations, but not OSMesa's: tests/lsan.supp suppresses any leak allocated inside
// libOSMesa.so (Mesa's own 480-byte framebuffer leak), and with it a leaked context or GL
// object. The GL tests therefore measure the heap themselves: a leaked OSMesa context keeps
// about 3 MB, a shader object left in a live context about 3 KB, a program about 15 KB.
#include <SDL.h>
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "fixstep/render/render.hpp"
#include "fixstep/window/window.hpp"
#include "gl_pipeline.hpp"  // engine/render/src: internal, not installed
#include "gl_shaders.hpp"
#include "osmesa_library.hpp"

namespace fixstep {
namespace {

static_assert(std::is_nothrow_destructible_v<Renderer>);
static_assert(std::is_nothrow_destructible_v<Window>);
static_assert(std::is_nothrow_destructible_v<gl::Pipeline>);
static_assert(std::is_nothrow_destructible_v<gl::Context>);
static_assert(std::is_nothrow_destructible_v<gl::Program>);

// --- helpers ----------------------------------------------------------------------------------

// Sets (value) or unsets (nullptr) an environment variable for the scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

#if defined(__SANITIZE_ADDRESS__)
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
std::size_t heap_bytes() {
  return __sanitizer_get_current_allocated_bytes();
}
#else
std::size_t heap_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}
#endif

// Heap bytes left allocated per call of `attempt`, averaged over `calls` calls that follow a
// first one (which fills Mesa's and LLVM's process-wide caches).
template <class Attempt>
double heap_growth_per_call(Attempt&& attempt, int calls = 6) {
  attempt();
  const std::size_t before = heap_bytes();
  for (int i = 0; i < calls; ++i) attempt();
  return (double(heap_bytes()) - double(before)) / calls;
}

// Calls `make` and expects it to throw `Error` whose message starts with `prefix`.
template <class Error, class Make>
void expect_error(Make&& make, const std::string& prefix) {
  try {
    make();
    ADD_FAILURE() << "no exception; expected \"" << prefix << "...\"";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).substr(0, prefix.size()), prefix) << e.what();
  }
}

// --- the GL pipeline: failures after the context, shaders or programs were created ----------

constexpr int size = 64;
// Growth allowed per failed or completed pipeline: Mesa keeps a few hundred bytes per context
// (measured: ~200 B); a leaked context is ~3 MB.
constexpr double max_pipeline_growth = 64 * 1024;

constexpr const char* vertex_ok = R"(#version 330 core
layout(location = 0) in vec2 a_pos;
void main() { gl_Position = vec4(a_pos, 0.0, 1.0); }
)";
constexpr const char* fragment_ok = R"(#version 330 core
out vec4 frag;
void main() { frag = vec4(1.0); }
)";
constexpr const char* does_not_compile = R"(#version 330 core
out vec4 frag;
void main() { frag = vec4(1.0) +; }
)";
// Compiles, but a program needs a main().
constexpr const char* does_not_link = R"(#version 330 core
out vec4 frag;
void shade() { frag = vec4(1.0); }
)";

// Builds a Pipeline from `sources` drawing into `pixels`, expects RenderError starting with
// `prefix`, and that neither the context (still current otherwise) nor memory stays behind.
void expect_pipeline_failure(const gl::ShaderSources& sources, std::uint8_t* pixels,
                             const std::string& prefix) {
  ASSERT_EQ(gl::osmesa().OSMesaGetCurrentContext(), nullptr);
  const double growth = heap_growth_per_call([&] {
    expect_error<RenderError>([&] { gl::Pipeline pipeline(size, size, pixels, sources); }, prefix);
    EXPECT_EQ(gl::osmesa().OSMesaGetCurrentContext(), nullptr)
        << "the context outlived the failure";
  });
  EXPECT_LT(growth, max_pipeline_growth) << "bytes left per failed construction";
}

TEST(RenderResources, MakeCurrentFailureReleasesTheContext) {
  // No pixel buffer: OSMesaMakeCurrent refuses it, after the context was created.
  expect_pipeline_failure({vertex_ok, {fragment_ok, fragment_ok, fragment_ok}}, nullptr,
                          "render: OSMesaMakeCurrent failed");
}

TEST(RenderResources, VertexShaderFailureReleasesTheContext) {
  std::vector<std::uint8_t> pixels(size * size * 4);
  expect_pipeline_failure({does_not_compile, {fragment_ok, fragment_ok, fragment_ok}},
                          pixels.data(), "render: shader compilation failed: ");
}

TEST(RenderResources, FragmentShaderFailureReleasesTheFirstProgram) {
  // Held when it fails: the context, the vertex shader, the first program.
  std::vector<std::uint8_t> pixels(size * size * 4);
  expect_pipeline_failure({vertex_ok, {fragment_ok, does_not_compile, fragment_ok}}, pixels.data(),
                          "render: shader compilation failed: ");
}

TEST(RenderResources, LinkFailureReleasesBothPrograms) {
  // Held when it fails: the context, both shaders, the first program and the second one.
  std::vector<std::uint8_t> pixels(size * size * 4);
  expect_pipeline_failure({vertex_ok, {fragment_ok, does_not_link, fragment_ok}}, pixels.data(),
                          "render: shader program failed to link: ");
}

TEST(RenderResources, CompletePipelineReleasesEverything) {
  std::vector<std::uint8_t> pixels(size * size * 4);
  const double growth = heap_growth_per_call([&] {
    gl::Pipeline pipeline(size, size, pixels.data(),
                          {vertex_ok, {fragment_ok, fragment_ok, fragment_ok}});
    EXPECT_NE(pipeline.vbo.get(), 0u);
  });
  EXPECT_LT(growth, max_pipeline_growth);
  EXPECT_EQ(gl::osmesa().OSMesaGetCurrentContext(), nullptr);
}

// The builder on a context that lives on: a failed compile or link must delete its shader or
// program itself (the context would otherwise keep them until it is destroyed).
TEST(RenderResources, ShaderBuilderFailuresLeaveNothingInALiveContext) {
  std::vector<std::uint8_t> pixels(size * size * 4);
  gl::Pipeline live(size, size, pixels.data(),
                    {vertex_ok, {fragment_ok, fragment_ok, fragment_ok}});
  const gl::Shader vertex = gl::compile_shader(GL_VERTEX_SHADER, vertex_ok);
  // A leaked shader is ~3 KB, a program ~15 KB. (glibc's counters include its per-thread cache
  // of freed chunks: over 100 calls what they add is below 100 B a call.)
  constexpr double max_growth = 1024;
  EXPECT_LT(heap_growth_per_call(
                [] {
                  expect_error<RenderError>(
                      [] { (void)gl::compile_shader(GL_FRAGMENT_SHADER, does_not_compile); },
                      "render: shader compilation failed: 0:3(");
                },
                100),
            max_growth);
  EXPECT_LT(heap_growth_per_call(
                [&] {
                  const gl::Shader fragment = gl::compile_shader(GL_FRAGMENT_SHADER, does_not_link);
                  expect_error<RenderError>(
                      [&] { (void)gl::link_program(vertex, fragment); },
                      "render: shader program failed to link: error: fragment shader lacks `main'");
                },
                100),
            max_growth);
}

// A renderer destroyed while another one's context is current must delete its GL objects in its
// own context: the other renderer's objects have the same names.
TEST(RenderResources, DestructionLeavesOtherRenderersIntact) {
  auto picture = [](Renderer& r) {
    r.begin(Rgba8{0, 0, 0, 255});
    r.disc(32, 32, 20, Rgba8{200, 100, 50, 255}, 2.0f, Rgba8{10, 20, 30, 255});
    r.text(4, 4, "fixstep", 1.0f, Rgba8{255, 255, 255, 255});
    r.finish();
    return std::vector<std::uint8_t>(r.pixels().begin(), r.pixels().end());
  };
  std::optional<Renderer> first(std::in_place, size, size);
  Renderer second(size, size);
  const std::vector<std::uint8_t> expected = picture(second);  // second's context is current
  first.reset();
  std::vector<std::uint8_t> after;
  ASSERT_NO_THROW(after = picture(second));
  EXPECT_EQ(after, expected);
}

TEST(RenderResources, UnusableGalliumDriverIsRefusedBeforeOsmesa) {
  const ScopedEnv driver("GALLIUM_DRIVER", "foo");
  expect_error<RenderError>([] { Renderer r(size, size); },
                            "render: GALLIUM_DRIVER=foo is not a driver OSMesa can use");
}

// Mesa reads MESA_GL_VERSION_OVERRIDE once per process, at its first context: the death test
// runs in a fresh process, where no OpenGL 3.3 core context can then be created.
TEST(RenderResources, ContextCreationFailure) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        setenv("MESA_GL_VERSION_OVERRIDE", "3.0", 1);
        try {
          Renderer r(size, size);
        } catch (const RenderError& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::exit(0);  // LeakSanitizer checks this process as it exits
        }
        std::exit(1);
      },
      testing::ExitedWithCode(0), "render: OSMesaCreateContextAttribs failed to create");
}

// --- the window: failures after SDL, its window or its renderer were acquired ---------------

// The environment of one window attempt: DISPLAY, WAYLAND_DISPLAY and SDL_VIDEODRIVER.
struct Display {
  ScopedEnv x11, wayland, driver;
  Display(const char* display, const char* videodriver)
      : x11("DISPLAY", display),
        wayland("WAYLAND_DISPLAY", nullptr),
        driver("SDL_VIDEODRIVER", videodriver) {}
};

// Opens a width x height window and expects WindowError with exactly `message`, and SDL quit.
void expect_window_failure(int width, int height, const std::string& message) {
  try {
    Window window("test_resources", width, height);
    ADD_FAILURE() << "the window opened; expected: " << message;
  } catch (const WindowError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
  EXPECT_EQ(SDL_WasInit(0), 0u) << "SDL was left initialised";
}

TEST(WindowResources, NoDisplayFailsBeforeSdl) {
  const Display env(nullptr, nullptr);
  expect_window_failure(
      size, size, "no display: DISPLAY and WAYLAND_DISPLAY are not set, so no window can open");
}

TEST(WindowResources, SdlInitFailure) {
  const Display env(nullptr, "bogus");
  expect_window_failure(size, size, "SDL could not initialise video (bogus not available)");
}

TEST(WindowResources, UnreachableDisplayQuitsSdl) {
  // SDL initialises video on its offscreen driver (it cannot reach :97), which the window
  // refuses: SDL must be quit again.
  const Display env(":97", nullptr);
  expect_error<WindowError>([] { Window w("test_resources", size, size); },
                            "no display: could not connect to DISPLAY=:97 (SDL fell back to its '");
  EXPECT_EQ(SDL_WasInit(0), 0u);
}

TEST(WindowResources, WindowCreationFailureQuitsSdl) {
  const Display env(nullptr, "dummy");
  expect_window_failure(20000, size,
                        "SDL could not create a 20000x64 window: Window is too large.");
}

TEST(WindowResources, TextureCreationFailureReleasesRendererAndWindow) {
  // SDL_CreateWindow makes a 0-pixel-wide window 1 pixel wide, then the texture is refused.
  const Display env(nullptr, "dummy");
  expect_window_failure(
      0, size, "SDL could not create a 0x64 texture for the window: Texture dimensions can't be 0");
}

TEST(WindowResources, OpensPresentsAndReleasesEverything) {
  const Display env(nullptr, "dummy");
  {
    Window window("test_resources", size, size);
    EXPECT_EQ(window.driver(), "dummy");
    const std::vector<std::uint8_t> frame(size * size * 4, 128);
    window.present(frame);
    (void)window.poll();
    expect_error<WindowError>([&] { window.present(std::span(frame).first(16)); },
                              "window: frame size does not match the window");
  }
  EXPECT_EQ(SDL_WasInit(0), 0u);
}

}  // namespace
}  // namespace fixstep
