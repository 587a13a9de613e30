// The fixstep subcommands, separated from argument parsing.
#pragma once

#include <cstdint>
#include <fixstep/capture.hpp>
#include <fixstep/scene.hpp>
#include <fixstep/session.hpp>
#include <optional>
#include <string>

namespace fixstep::cli {

/// Exit status when the runtime guard stopped the simulation (a body's state left the finite
/// range; World::fault). 1 is any other error, 2 a command-line error.
inline constexpr int exit_diverged = 3;

struct SceneOptions {
  std::string scene;
  std::optional<std::string> integrator;
  std::optional<double> dt;  ///< s
  std::optional<std::string> precision;
  std::optional<int> substeps;
  bool allow_unstable = false;
  bool quiet = false;  ///< --quiet: errors only (no summary, warnings or progress)
};

struct RunOptions {
  SceneOptions scene;
  std::optional<std::int64_t> steps;
  std::optional<double> duration;  ///< s
  std::optional<std::string> csv;
  std::int64_t every = 1;
};

struct RenderOptions {
  SceneOptions scene;
  std::string out;
  std::int64_t frames = 120;
  double fps = 60.0;
  std::string size = "1280x720";
  int png_level = default_png_level;  ///< see PngSettings::level
};

struct ViewOptions {
  SceneOptions scene;
  std::string size = "1280x720";
  std::int64_t frames = 0;
  std::optional<double> fps;
};

/// Largest --steps, --every and view --frames: 10^12 ticks (over 500 years at 60 Hz).
inline constexpr std::int64_t max_ticks = 1'000'000'000'000;

/// CLI11 validator text: "" when value is a step length dt in (0, 1] s, the scene rule.
std::string dt_validator(const std::string& value);
/// CLI11 validator text: "" when value is a finite number > 0.
std::string positive_finite(const std::string& value);
/// CLI11 validator text: "" when value is WxH within the renderer's limits.
std::string frame_size_validator(const std::string& value);
/// CLI11 validator text: "" when value is an integer PNG level in [min_png_level, max_png_level].
std::string png_level_validator(const std::string& value);
/// Parses "WxH" (validated by frame_size_validator).
std::pair<int, int> parse_frame_size(const std::string& value);

/// "scene=FILE integrator=NAME precision=f32|f64 dt=S [substeps=N]": the first line every
/// subcommand prints.
std::string describe(const Scene& scene);

/// Loads the scene, applies the overrides, runs the stability guard (throws SceneError for an
/// unstable body) and prints the warnings of both to stderr.
Scene load_with_overrides(const SceneOptions& options);

/// The frame pipeline for a scene: its world, its [view] and its file name in the HUD.
[[nodiscard]] Session open_session(const Scene& scene, int width, int height);

int run_command(const RunOptions& options);
int render_command(const RenderOptions& options);
int view_command(const ViewOptions& options);

}  // namespace fixstep::cli
