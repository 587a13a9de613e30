// The parts of `fixstep compare` that are not the command itself: a tile's configuration as
// given to --with, the grid the tiles are laid out in, and the choice of the tile the others are
// measured against when the scene has no exact solution.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fixstep/core/integrators.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/scene/scene.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fixstep::cli {

/// Most and fewest tiles of one compare frame.
inline constexpr std::size_t min_tiles = 2, max_tiles = 6;

/// One configuration of `fixstep compare --with`:
///   INTEGRATOR[@DT][:substeps=N][:precision=f32|f64]
/// e.g. "rk4@1/30", "implicit_euler@0.0625:substeps=2". DT is a step length in s, written as a
/// decimal or a fraction A/B, 0 < DT <= 1 (as [world] dt); without it the scene's dt applies,
/// and so do its substeps and precision when those are not given.
struct TileSpec {
  std::string text;  ///< as given
  Integrator integrator = Integrator::semi_implicit_euler;
  std::optional<double> dt;  ///< s
  std::optional<int> substeps;
  std::optional<Precision> precision;
  std::optional<DampingSplit> damping_split;  ///< ":split=per_step" (velocity Verlet, Forest–Ruth)
};

/// Parses a --with value. Throws std::invalid_argument naming the part that is wrong, the value
/// and the form expected (unknown integrator: the valid names, or the closest one).
[[nodiscard]] TileSpec parse_tile_spec(std::string_view text);
/// CLI11 validator text: "" when parse_tile_spec accepts value, else its message.
std::string tile_spec_validator(const std::string& value);

/// `base` with a tile's integrator, dt, substeps and precision (the stability guard not run).
[[nodiscard]] Scene tile_scene(const Scene& base, const TileSpec& spec);

/// The short name of a tile's configuration for HUDs and tables: "rk4 @ 1/30 s" (dt as given
/// in the spec, else the scene's, %g), then " x2" for 2 substeps and " f32" for single precision.
[[nodiscard]] std::string tile_label(const TileSpec& spec, const Scene& scene);

/// Index of the tile expected to be the most accurate: the smallest h^p, h = dt / substeps its
/// integration step (s) and p its integrator's order (integrator_order), a single-precision
/// tile's estimate raised to at least 1e-7 (its round-off); ties go to the first such tile. An
/// estimate from the order alone (the constant of the error term is unknown), so named "most
/// accurate" in the HUD only in that sense. `tiles` is not empty.
[[nodiscard]] std::size_t most_accurate(std::span<const Scene> tiles);

/// How n tiles share a width x height frame: 2 and 3 side by side, 4 in a 2x2 grid, 5 and 6 in
/// 3 columns of 2 rows; tiles are separated by `gap` pixels (the frame's remainder goes to the
/// right and bottom edges).
struct TileGrid {
  int columns = 1, rows = 1;
  int tile_width = 0, tile_height = 0;  ///< pixels
  static constexpr int gap = 2;         ///< pixels between tiles
  /// Top-left pixel of tile i (row-major).
  [[nodiscard]] int x(std::size_t i) const;
  [[nodiscard]] int y(std::size_t i) const;
};
/// The grid of `tiles` (min_tiles..max_tiles) tiles in a width x height frame. Throws
/// std::invalid_argument when a tile would be smaller than the renderer's minimum frame size.
[[nodiscard]] TileGrid tile_grid(int tiles, int width, int height);

/// Copies tile i's pixels (grid.tile_height rows of grid.tile_width RGBA8 pixels, top row first)
/// into its cell of `frame` (rows of frame_width RGBA8 pixels).
void blit_tile(std::span<const std::uint8_t> tile, const TileGrid& grid, std::size_t i,
               std::span<std::uint8_t> frame, int frame_width);

/// A cost in s of wall time per simulated s as "41.2 us" (ns, us, ms or s; ASCII for the HUD
/// font).
[[nodiscard]] std::string format_cost(double seconds_per_second);

}  // namespace fixstep::cli
