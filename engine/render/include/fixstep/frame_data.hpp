// What the renderer draws of one moment of a World (RenderFrame), and how it is taken from one.
#pragma once

#include <cstdint>
#include <vector>

#include "fixstep/world.hpp"

namespace fixstep {

/// What the renderer needs of one moment of the world, in float (pixels need no more): the
/// positions interpolated between the last two ticks, appearances and lines. Drawing data only,
/// not a restorable state (a snapshot, in game-physics terms, is one). Structure of arrays, one
/// entry per body in World::bodies() order; `ids` names each body by its handle.
struct RenderFrame {
  struct SpringLine {
    float anchor_x = 0, anchor_y = 0;  ///< m
    std::uint32_t body = 0;            ///< the body's entry in x / y
  };
  std::vector<float> x, y;  ///< body positions, m (interpolated when taken with alpha)
  /// Each body's handle, so what a renderer keeps per body across frames (trails) follows the
  /// body, not its entry, when bodies are created or destroyed.
  std::vector<Entity> ids;
  std::vector<float> radius;  ///< m; 0 = no Appearance (drawn at a default size)
  std::vector<Rgba8> color;   ///< colour; alpha 0 = no Appearance (palette colour)
  std::vector<SpringLine> springs;
  /// Links (springs between bodies): link i joins entries link_a[i] and link_b[i] of x / y.
  std::vector<std::uint32_t> link_a, link_b;
  /// Static half-planes n·x >= offset (normals normalised), drawn as ground and walls.
  std::vector<PlaneDef> planes;
};

/// Fills `out` from `world` at interpolation alpha (in [0, 1]; World::interpolate_positions):
/// positions, handles, appearances, anchored springs, links and planes. Reuses out's storage: no
/// allocation once it has grown to the world's size.
void fill_render_frame(const World& world, double alpha, RenderFrame& out);

}  // namespace fixstep
