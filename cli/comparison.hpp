// The tiles of `fixstep compare`: one world per configuration, all advanced by the same frame
// times, each drawn into its cell of one frame with a HUD of its error, energy balance and cost.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fixstep/app/session.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/scene/scene.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "compare_tiles.hpp"
#include "exact_reference.hpp"

namespace fixstep::cli {

/// One tile: its configuration, its world and view, and what has been measured of it.
struct Tile {
  TileSpec spec;
  Scene scene;        ///< the base scene with the spec's overrides
  std::string label;  ///< the HUD's first line: the tile's number and tile_label()
  std::unique_ptr<Session> session;
  /// Wall s per simulated s of its ticks measured warm and alone (step_cost), before frame 0.
  double cost = 0.0;
  /// Wall time spent in its frames' advance() so far, s: the cost inside the program, which
  /// drawing between the frames' ticks makes larger (cold caches), most for small worlds.
  double wall_seconds = 0.0;
  std::optional<double> error;  ///< largest position error over the bodies at error_time, m
  double error_time = 0.0;      ///< s
  double max_error = 0.0;       ///< largest `error` seen so far, m
  /// The bodies a disc contact has touched (no exact state from then on): fed every tick.
  std::optional<TouchedBodies> touched;
  /// Without an exact solution: the most accurate tile's configuration, stepped (untimed, not
  /// drawn) up to this tile's time to measure it against.
  std::unique_ptr<World> shadow;
};

class Comparison {
 public:
  /// Builds a tile per spec from `base` (which must outlive the Comparison), each a Session of
  /// grid's tile size with the engine's HUD replaced by the tile's. Throws std::invalid_argument
  /// naming the spec when the stability guard refuses a tile (unless the scene allows unstable
  /// runs), RenderError when rendering cannot start. Prints the guard's warnings unless quiet.
  /// `max_frame_time` (s): every tile's SessionSettings::max_frame_time.
  Comparison(const Scene& base, std::span<const TileSpec> specs, const TileGrid& grid, bool quiet,
             double max_frame_time = 0.25);

  /// Runs every tile's loop for `seconds` (s) of the shared clock, timing each, then measures
  /// its error: against the exact solution at its own time when the scene has one (what `fixstep
  /// run` prints as exact_error: over the bodies no disc contact has touched, none once every
  /// one has been), otherwise against the most accurate tile's configuration at the last time
  /// both have a tick.
  void advance(double seconds);
  /// Draws every tile with its HUD into its cell of `frame` (rows of frame_width RGBA8
  /// pixels); the gaps between cells are left as they are.
  void draw(std::span<std::uint8_t> frame, int frame_width);
  /// Every tile back to tick 0, its measurements cleared.
  void restart();

  [[nodiscard]] std::size_t size() const { return tiles_.size(); }
  [[nodiscard]] const Tile& tile(std::size_t i) const { return *tiles_[i]; }
  [[nodiscard]] Tile& tile(std::size_t i) { return *tiles_[i]; }
  [[nodiscard]] bool has_exact() const { return has_exact_; }
  /// The tile the others are measured against when there is no exact solution.
  [[nodiscard]] std::size_t reference() const { return reference_; }
  /// What tile i's error is measured against: "exact", "exact (K of N bodies touched by a
  /// contact)" (those K left out), "tile K" or "" (the reference itself).
  [[nodiscard]] std::string error_against(std::size_t i) const;
  /// Why tile i has no error against the exact solution although the scene has one: "disc
  /// contact at tick N" when a contact has touched every body that had one; else "".
  [[nodiscard]] std::string exact_lost(std::size_t i) const;
  /// Whether a tile's runtime guard has fired.
  [[nodiscard]] bool any_fault() const;

 private:
  /// The measurements cleared and the shadows of the tiles at tick 0 (restart(), the start).
  void start();
  /// Lines of a tile's HUD.
  static constexpr std::size_t hud_lines = 5;

  /// A tile's view: its HUD text at hud_scale_, the scene fitted below the HUD panel.
  [[nodiscard]] SessionSettings tile_settings(const Scene& scene) const;
  void measure(std::size_t i);
  static std::optional<double> against_shadow(const World& sim, World& shadow);
  [[nodiscard]] std::vector<std::string> hud(std::size_t i) const;

  const Scene& base_;
  ExactReference exact_;
  TileGrid grid_;
  bool has_exact_ = false;
  std::size_t reference_ = 0;
  double max_frame_time_;   ///< s, SessionSettings::max_frame_time of every tile
  float hud_scale_ = 2.0f;  ///< every tile's HUD text scale (Renderer::set_hud_text_scale)
  std::vector<std::unique_ptr<Tile>> tiles_;
};

}  // namespace fixstep::cli
