// What the renderer draws of one moment of a World (RenderFrame), and how it is taken from one.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"

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
  /// One shape of a body (BodyDef::shapes) as drawn: the points of its outline (ShapeOutline's:
  /// a circle's centre, a capsule's segment ends, a polygon's or box's vertices
  /// counter-clockwise) and its radius, in the body's frame relative to its centre of mass
  /// (World::local_center), unturned: the body's entry `body` puts them at x / y turned by
  /// angle. Drawn filled in the body's colour, outlined as discs are, with a line from the
  /// shape's centre (the mean of its points) to `mark`, so that its turn shows.
  struct Shape {
    std::uint32_t body = 0;   ///< the body's entry in x / y / angle
    std::uint32_t count = 0;  ///< points used: 1 circle, 2 capsule, 3..max_polygon_vertices
    float radius = 0;         ///< m: circle's and capsule's radius, polygon's rounding (>= 0)
    std::array<float, max_polygon_vertices> px{}, py{};  ///< m, as above
    float mark_x = 0, mark_y = 0;  ///< m, as above: a circle's rim on its x axis, a vertex
  };
  std::vector<float> x, y;  ///< body positions, m (interpolated when taken with alpha)
  /// Each body's handle, so what a renderer keeps per body across frames (trails) follows the
  /// body, not its entry, when bodies are created or destroyed.
  std::vector<Entity> ids;
  std::vector<float> radius;  ///< m; 0 = no Appearance (drawn at a default size)
  std::vector<Rgba8> color;   ///< colour; alpha 0 = no Appearance (palette colour)
  /// Appearance::visible: 0 = neither the body, its trail nor its anchored spring is drawn.
  /// Empty: every body is drawn (a frame filled by hand).
  std::vector<std::uint8_t> visible;
  /// Seconds of trail behind each body (Appearance::trail_time; 0 = Appearance::trail off).
  /// Empty: default_trail_time for every body.
  std::vector<float> trail_time;
  /// Each body's angle θ (rad, counter-clockwise from +x, interpolated like x / y) in a world of
  /// rolling discs (ContactSettings::rolling) or with shapes: each shape turns with its body,
  /// and a body without shapes is drawn with a line from its disc's centre to its rim when
  /// spin_marks is set. Empty: no angles (no line; shapes unturned).
  std::vector<float> angle;
  /// Whether bodies without shapes show their angle (above): fill_render_frame sets it for a
  /// world of rolling discs only.
  bool spin_marks = true;
  /// The bodies' shapes, in body order (entry `body` ascending). A body with shapes is drawn
  /// as them instead of a disc. Empty: every body is a disc. An entry naming no body of the
  /// frame, or with a count outside 1..max_polygon_vertices, is not drawn.
  std::vector<Shape> shapes;
  /// 1 for a body that sleeps (ContactSettings::sleep; World::asleep), drawn in its colour
  /// half greyed, as Box2D's debug draw greys sleeping bodies. Empty: none sleeps.
  std::vector<std::uint8_t> asleep;
  std::vector<SpringLine> springs;
  /// Links (springs between bodies): link i joins entries link_a[i] and link_b[i] of x / y.
  std::vector<std::uint32_t> link_a, link_b;
  /// Static half-planes n·x >= offset (normals normalised), drawn as ground and walls.
  std::vector<PlaneDef> planes;
  /// Segments (level geometry), drawn as lines in the planes' colour; one a kinematic body
  /// carries where its body is at the frame's moment (interpolated like x / y).
  std::vector<SegmentDef> segments;
  /// The world's tick when the frame was taken (World::tick()) and its dt (s; 0: unknown, a
  /// frame filled by hand, taken as 1/60 s), and the interpolation alpha of x / y: the frame
  /// shows the moment tick - (1 - alpha) ticks. Trails (Trails::prepare) sample a frame whose
  /// tick they have not sampled, and fade their samples by their age before this moment.
  std::uint64_t tick = 0;
  double dt = 0.0;
  double alpha = 1.0;
};

/// Fills `out` from `world` at interpolation alpha (in [0, 1]; World::interpolate_positions):
/// positions, handles, appearances (visibility and trails included), angles and shapes (a
/// world with rolling discs or shapes), anchored springs, links, planes, segments, the tick, dt
/// and alpha. Reuses out's storage: no
/// allocation once it has grown to the world's size.
void fill_render_frame(const World& world, double alpha, RenderFrame& out);

}  // namespace fixstep
