// Shapes a body carries: circles, capsules, boxes and convex polygons at a pose in the body's
// frame, the exact mass properties they give, and the checks a definition passes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "fixstep/core/collision_filter.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// Most vertices a convex polygon may have (Box2D's B2_MAX_POLYGON_VERTICES).
inline constexpr int max_polygon_vertices = 8;
/// Largest extent of a shape, m: every vertex, offset and radius within it.
inline constexpr double max_shape_extent = 1e6;
/// Smallest edge and smallest capsule length, m (Box2D's linear slop scaled to fixstep's
/// millimetre tolerance): closer vertices are one.
inline constexpr double min_shape_edge = 1e-6;

/// What a shape is. A box is a polygon of four vertices written as its half-extents.
enum class ShapeKind : std::uint8_t { circle = 0, capsule = 1, box = 2, polygon = 3 };

/// "circle", "capsule", "box" or "polygon" (the scene file's spelling).
[[nodiscard]] const char* shape_kind_name(ShapeKind kind);

/// One shape of a body (Box2D's b2ShapeDef with its geometry): what World(def) and
/// World::create_body take in BodyDef::shapes. Coordinates are in the shape's own frame, which
/// sits at `offset` and `angle` in the body's frame (the frame of Body::position and
/// Body::angle).
///
/// Geometry by kind:
///   circle:  centre (0, 0) of the shape frame, radius `radius` > 0;
///   capsule: the segment vertices[0]..vertices[1] (count = 2, at least min_shape_edge long)
///            swept by a disc of radius `radius` > 0;
///   box:     the rectangle [-half_extents.x, half_extents.x] × [-half_extents.y,
///            half_extents.y] (each >= min_shape_edge / 2), rounded by `radius` >= 0;
///   polygon: vertices[0 .. count) (3 <= count <= max_polygon_vertices), convex,
///            counter-clockwise, no three collinear, every edge at least min_shape_edge long,
///            rounded by `radius` >= 0 (a rounded polygon is its Minkowski sum with a disc).
struct ShapeDef {
  ShapeKind kind = ShapeKind::circle;
  double radius = 0.5;  ///< m: circle and capsule radius; box and polygon rounding
  Vec2 half_extents{};  ///< m, box only
  std::array<Vec2, max_polygon_vertices> vertices{};  ///< m: capsule (2) and polygon only
  int count = 0;                                      ///< vertices used: capsule 2, polygon 3..8
  Vec2 offset{};       ///< m: the shape frame's origin in the body frame
  double angle = 0.0;  ///< rad: the shape frame's angle in the body frame
  /// kg/m²: the body's mass and inertia come from its shapes' densities when any shape sets
  /// one (a shape without one then weighs nothing); unset on every shape: Body::mass spread
  /// evenly over the shapes' area.
  std::optional<double> density = std::nullopt;
  /// Coulomb μ, in [0, 1e100]; unset: ContactSettings::friction. A pair uses √(μ_a μ_b).
  std::optional<double> friction = std::nullopt;
  /// e, in [0, 1]; unset: ContactSettings::restitution. A pair uses the larger.
  std::optional<double> restitution = std::nullopt;
  /// Rolling resistance c, dimensionless, in [0, 1e100], default 0 (none): a contact of this
  /// shape resists its two bodies' relative turning with an angular impulse of at most
  /// c · r · λ_n, r the larger radius of the pair's shapes (a circle's or capsule's radius, a
  /// box's or polygon's rounding) and λ_n the manifold's normal impulse; a pair uses the larger
  /// c (Box2D v3.1's b2SurfaceMaterial::rollingResistance). A uniform disc rolling on flat
  /// ground then slows at (2/3) c g.
  double rolling_resistance = 0.0;
  CollisionFilter filter{};  ///< which shapes and discs this one may touch
  /// A sensor reports what it overlaps (World::sensors_begun) and pushes nothing.
  bool sensor = false;
  /// Drawing only (not in the definition or state hash): the shape's fill colour; alpha 0
  /// (the default): its body's colour.
  Rgba8 color{0, 0, 0, 0};
  /// One-way (a platform of any kind: box, polygon, capsule, circle): the shape blocks only
  /// what comes from its up side, the shape frame's +y axis turned with its body,
  /// up = R(body angle + angle)·(0, 1). A contact with it acts only when (a) its normal, from
  /// this shape towards the other, has n·up > 0.1 (a box platform's top face blocks, its sides
  /// (n·up = 0) and bottom let a body through; a capsule's or polygon's slanted faces block
  /// within about 84° of up), and (b) the pair's manifold separation at the tick's start
  /// poses was at least -0.01 m (twice the 5 mm slop): the other body was not already
  /// crossing. Otherwise the pair has no contact that tick: no impulse, no push-out, no
  /// continuous collision, no contact event. The rule holds against whatever the shape meets,
  /// planes and segments included (a dynamic body's one-way shape passes down through the
  /// ground). Two one-way shapes touch only when each one's rule lets the contact act (each
  /// sees the other on its up side: two with the same up pass through each other).
  /// docs/SHAPES.md, "One-way platforms". Default false.
  bool one_way = false;
  friend bool operator==(const ShapeDef&, const ShapeDef&) = default;
};

/// A circle of `radius` (m) centred at `center` in the body frame.
[[nodiscard]] ShapeDef make_circle(double radius, Vec2 center = {});
/// A capsule: the segment a..b (body frame, m) swept by a disc of `radius` (m).
[[nodiscard]] ShapeDef make_capsule(Vec2 a, Vec2 b, double radius);
/// A box of half-extents hx, hy (m), centred at `center` and turned by `angle` (rad) in the
/// body frame, rounded by `rounding` (m).
[[nodiscard]] ShapeDef make_box(double hx, double hy, Vec2 center = {}, double angle = 0.0,
                                double rounding = 0.0);
/// A convex polygon through `points` (body frame, m, counter-clockwise), rounded by `rounding`.
/// Does not check it (shape_problem does; World(def) refuses a bad one).
[[nodiscard]] ShapeDef make_polygon(std::span<const Vec2> points, double rounding = 0.0);

/// What is wrong with `shape`, in words naming the field ("polygon vertex 3 makes it concave",
/// "radius must be finite and > 0"), or nothing when it is a valid shape: finite values, the
/// geometry rules above, every coordinate within max_shape_extent, density >= 0, friction and
/// restitution in range, a non-zero area.
[[nodiscard]] std::optional<std::string> shape_problem(const ShapeDef& shape);

/// Mass, centre of mass and rotational inertia.
struct MassProperties {
  double mass = 0.0;     ///< kg
  Vec2 center{};         ///< m, the centre of mass in the body frame
  double inertia = 0.0;  ///< kg·m², about the centre of mass
  double area = 0.0;     ///< m²
};

/// The exact mass properties of `shape` of uniform `density` (kg/m²) in the body frame:
/// circle π r²; capsule the rectangle 2r·L plus two half discs (inertia by the parallel-axis
/// theorem about the segment's midpoint); polygon by the triangle fan from its centroid
/// (Eberly, "Polyhedral Mass Properties", 2D case); a rounded polygon adds the rim rectangles
/// and the corner sectors (a full disc in total), exactly. Assumes a valid shape.
[[nodiscard]] MassProperties shape_mass(const ShapeDef& shape, double density);

/// The mass properties of a body of `shapes`: with densities (any shape sets one) their sum;
/// otherwise `mass` (kg) spread evenly over the shapes' area. Inertia about the combined
/// centre of mass (parallel-axis theorem). Throws std::invalid_argument when the result has
/// no mass or no area.
[[nodiscard]] MassProperties body_mass(std::span<const ShapeDef> shapes, double mass);

/// Axis-aligned bounding box, m.
struct Aabb {
  Vec2 lower{}, upper{};
  friend bool operator==(const Aabb&, const Aabb&) = default;
};

/// The box around `shape` placed at body position `position` (m) and angle `angle` (rad),
/// rounding radius included.
[[nodiscard]] Aabb shape_aabb(const ShapeDef& shape, Vec2 position, double angle);

/// The shape's outline in world coordinates for drawing: a polygon's or box's vertices
/// (counter-clockwise), a capsule's two segment ends, a circle's centre; `radius` is the
/// rounding/sweep radius. Placed at body position `position` and angle `angle` (rad).
struct ShapeOutline {
  std::array<Vec2, max_polygon_vertices> points{};
  int count = 0;
  double radius = 0.0;
};
[[nodiscard]] ShapeOutline shape_outline(const ShapeDef& shape, Vec2 position, double angle);

}  // namespace fixstep
