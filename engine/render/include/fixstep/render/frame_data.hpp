// What the renderer draws of one moment of a World (RenderFrame), and how it is taken from one.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/joint.hpp"
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
    Rgba8 color{0, 0, 0, 0};       ///< ShapeDef::color: its fill (alpha 0: the body's colour)
  };
  /// A body drawn as an image (Appearance::sprite) instead of its disc or shapes: a `width` x
  /// `height` m rectangle centred on (cx, cy) in the body's frame relative to its centre of
  /// mass (turned by its angle with it), the image stretched over it, top row up.
  struct Sprite {
    std::uint32_t body = 0;       ///< the body's entry in x / y / angle
    float cx = 0, cy = 0;         ///< m, as above
    float width = 0, height = 0;  ///< m, > 0
    std::string path;             ///< the PNG file (Appearance::sprite)
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
  /// The bodies drawn as images, in body order (entry `body` ascending). Empty: none.
  std::vector<Sprite> sprites;
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
  /// A joint as drawn (World::joints(), JointState): its anchors and axis at the frame's moment,
  /// moved with their bodies as x / y and angle are; its type and limits as created.
  struct JointMark {
    /// An end on the world (a null body): no entry of x / y.
    static constexpr std::uint32_t world = 0xffffffffu;
    Joint joint{};          ///< its handle (fill_render_frame keeps type and limits per handle)
    Entity id_a{}, id_b{};  ///< its bodies' handles (null: the world)
    std::uint32_t body_a = world, body_b = world;  ///< their entries in x / y, or `world`
    JointType type = JointType::revolute;
    bool broken = false;  ///< JointState::broken: not drawn
    /// A distance joint with a range (lower or upper: a rope), drawn dashed; a rigid or sprung
    /// one is drawn solid.
    bool rope = false;
    bool has_lower = false, has_upper = false;  ///< which limits it has (JointDef::lower, upper)
    float lower = 0, upper = 0;    ///< rad (revolute) or m (prismatic, wheel, distance)
    float ax = 0, ay = 0;          ///< m: the anchor as body A carries it (JointState::anchor_a)
    float bx = 0, by = 0;          ///< m: the anchor as body B carries it (a distance joint's end)
    float axis_x = 1, axis_y = 0;  ///< unit: the axis as A carries it (prismatic, wheel)
    /// Revolute: the direction (rad, counter-clockwise from +x) from the anchor in which the
    /// relative angle is 0, and the sense in which it grows (+1 or -1): the direction from the
    /// anchor to the centre of B (of A when B is the world) is zero_angle + sense · value, so
    /// the limits' arc spans zero_angle + sense · [lower, upper].
    float zero_angle = 0, sense = 1;
    float value = 0;  ///< JointState::value at the frame's moment (revolute: rad)
  };
  /// The joints in World::joints() order (empty: none, and nothing is drawn for them).
  std::vector<JointMark> joints;
  /// fill_render_frame's scratch: each body slot's entry in x / y, built when a joint's body
  /// has moved in World::bodies() (created or destroyed bodies).
  std::vector<std::uint32_t> entry_of_slot;
  /// The world's tick when the frame was taken (World::tick()) and its dt (s; 0: unknown, a
  /// frame filled by hand, taken as 1/60 s), and the interpolation alpha of x / y: the frame
  /// shows the moment tick - (1 - alpha) ticks. Trails (Trails::prepare) sample a frame whose
  /// tick they have not sampled, and fade their samples by their age before this moment.
  std::uint64_t tick = 0;
  double dt = 0.0;
  double alpha = 1.0;
};

/// Fills `out` from `world` at interpolation alpha (in [0, 1]; World::interpolate_positions):
/// positions, handles, appearances (visibility, trails and sprites included), angles and shapes
/// (a world with rolling discs or shapes), anchored springs, links, planes, segments, joints, the
/// tick, dt and alpha. Reuses out's storage: no allocation once it has grown to the world's
/// size, but for a body with a sprite, whose Appearance (its path) World::get copies each frame. A
/// joint's type and limits never change: they are read (World::joint) for a handle the frame did
/// not hold at its place before, and for every joint when the world's tick is before the frame's (a
/// restart, a snapshot restored, another world); a frame filled from two worlds in turn should be
/// one frame each.
void fill_render_frame(const World& world, double alpha, RenderFrame& out);

}  // namespace fixstep
