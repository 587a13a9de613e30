// Components: plain data, SI units. A World stores and steps only the components a scene
// declares; see world.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/collision_filter.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/mover.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// How a body moves (Box2D's b2BodyType).
///   dynamic:   moved by its forces, links, contacts and input; has a finite mass.
///   static_body: never moves (velocity zero); no mass (one given is ignored).
///   kinematic: moves at its velocity, set by a program or per tick by input
///              (TickInput::velocities), and is moved by no force, link or contact; it pushes
///              dynamic bodies as an infinite mass would. No mass (one given is ignored).
/// Links and planes treat static and kinematic bodies as immovable ends; the energy account
/// leaves them out and counts the work a kinematic body does on others as external.
enum class BodyType : std::uint8_t { dynamic = 0, static_body = 1, kinematic = 2 };

/// "dynamic", "static" or "kinematic" (the scene file's spelling).
[[nodiscard]] const char* body_type_name(BodyType type);

/// The rigid point body every other component acts on.
struct Body {
  /// kg, in [min_coefficient, max_coefficient] = [1e-100, 1e100] (value_ranges.hpp)
  double mass = 1.0;
  /// m, each component within max_state_magnitude (1e12): the body's origin, the frame its
  /// shapes are given in (the centre of mass of a body without shapes)
  Vec2 position{};
  Vec2 velocity{};  ///< m/s of the centre of mass, each component within 1e12
  /// Orientation θ, rad, |θ| <= 1e12, counter-clockwise positive: stepped for a body with
  /// shapes (BodyDef::shapes) and, in a world with rolling discs (ContactSettings::rolling),
  /// for every dynamic body (kept in [-π, π] there); ignored elsewhere.
  double angle = 0.0;
  /// Angular velocity ω, rad/s, |ω| <= max_state_magnitude (1e12; counter-clockwise positive):
  /// as angle. The runtime guard checks it after every tick.
  double angular_velocity = 0.0;
};

/// A spring-damper from the body to a fixed anchor point.
///
/// Force on the body, with d = position - anchor:
///   F = -k (|d| - L) d/|d| - b v          (Hooke's law plus a linear dashpot to the fixed frame)
/// With rest length L = 0 this is F = -k (x - anchor) - b v, the damped harmonic oscillator of
/// "Integration Basics" in each axis independently. The damping acts on the full velocity
/// (not only along the spring), which keeps it linear in v.
struct SpringDamper {
  Vec2 anchor{};             ///< m, each component within 1e12
  double stiffness = 0.0;    ///< k, N/m, in [0, 1e100]
  double damping = 0.0;      ///< b, N*s/m, in [0, 1e100]
  double rest_length = 0.0;  ///< L, m, in [0, 1e12]
};

/// A constant force, e.g. the 10 N push of the article's first example.
struct ConstantForce {
  Vec2 force{};  ///< N, each component within max_coefficient (1e100)
};

/// A constant acceleration independent of mass: gravity on a projectile.
struct Gravity {
  Vec2 acceleration{0.0, -9.81};  ///< m/s^2, each component within 1e100
};

/// Linear drag F = -c v (Stokes drag, valid at low Reynolds number).
struct LinearDrag {
  double coefficient = 0.0;  ///< c, N*s/m, in [0, 1e100]
};

/// Seconds of past motion a trail shows by default (Appearance::trail_time).
inline constexpr double default_trail_time = 0.75;
/// Longest Appearance::trail_time, s.
inline constexpr double max_trail_time = 10.0;

/// How a body is drawn. Bodies without one are drawn with a default size and palette colour
/// and the default trail. Drawing only: no field enters the physics, the state hash or the
/// definition hash, and changing one between ticks costs no rebuild of the force terms.
struct Appearance {
  double radius = 0.5;  ///< m, > 0 and <= max_state_magnitude (10^12 m)
  Rgba8 color{230, 87, 46, 255};
  /// false: neither the body nor its trail is drawn (it is still simulated, collides and is
  /// found by queries); shown again, its trail starts afresh where it is.
  bool visible = true;
  /// false: no trail behind this body.
  bool trail = true;
  /// Seconds of past motion the trail shows (sampled every tick), finite, in (0,
  /// max_trail_time].
  double trail_time = default_trail_time;
  /// A PNG image drawn for the body instead of its disc or shapes (empty: none): a path the
  /// renderer opens (relative to the working directory; a scene's `sprite` key is resolved
  /// against the scene file's folder), at most max_image_side px a side. Drawn textured
  /// (nearest texel, the image's own alpha), centred on the body (a body with shapes: on the
  /// middle of its shapes' bounds) and turned with its angle, interpolated like the body.
  std::string sprite{};
  /// The sprite's width and height, m, each finite and >= 0; 0 (either): the body's drawn
  /// size, its shapes' bounds (unturned, in the body frame) or its disc's diameter.
  Vec2 sprite_size{};
};

/// Largest width and height of an image a sprite, a background tile or an overlay's image
/// may have, px.
inline constexpr int max_image_side = 4096;
/// Most distinct images (by path) a renderer or a scene loads.
inline constexpr std::size_t max_images = 256;
/// Most bytes of decoded pixels (4 a pixel) the images of a renderer or a scene take together.
inline constexpr std::size_t max_image_bytes = std::size_t{256} << 20;
/// Largest image file read, bytes (a max_image_side square PNG stored without compression is
/// about 64 MiB).
inline constexpr std::size_t max_image_file_bytes = std::size_t{80} << 20;

/// A disc the body occupies: for contacts with static half-planes (PlaneDef) and, in a world
/// with body contacts on (WorldSettings::contacts), with the other discs. Bodies without one
/// pass through planes and discs; colliders cost nothing in a world without planes or contacts.
struct Collider {
  double radius = 0.5;  ///< m, in [min_coefficient, max_state_magnitude] = [1e-100, 1e12]
  /// e of this body in disc-disc contacts, in [0, 1]; unset: ContactSettings::restitution.
  /// A pair uses the larger of its two (Box2D's rule: a bouncy ball bounces off anything).
  std::optional<double> restitution = std::nullopt;
  /// Coulomb μ of this body in disc-disc contacts, in [0, 1e100]; unset:
  /// ContactSettings::friction.
  /// A pair uses √(μ_a μ_b) (Box2D's b2MixFriction: either surface frictionless, no friction).
  std::optional<double> friction = std::nullopt;
  /// false: the disc takes part in no disc-disc contact and no sensor sees it (it still
  /// meets planes).
  bool collide = true;
  /// true: a sensor (Box2D's isSensor, Godot's Area2D): the disc pushes nothing and is pushed
  /// by nothing (no disc contact, no plane contact) but reports the discs and the bodies with
  /// shapes it overlaps (World::sensors_begun, sensors_ended). Needs WorldSettings::contacts.
  bool sensor = false;
  /// Which discs this one may touch and sense (CollisionFilter).
  CollisionFilter filter{};
  /// Moment of inertia about the centre, kg·m², in [1e-100, 1e100], used only with rolling discs
  /// (ContactSettings::rolling); unset: a uniform disc's ½ m r².
  std::optional<double> inertia = std::nullopt;
};

/// Body-vs-body contacts of discs (Collider), on when WorldSettings::contacts is set. Bodies
/// joined by a link never collide with each other (Box2D's collideConnected = false).
///
/// The resting solver (disc_contacts.hpp) runs warm-started sequential impulses (Catto, GDC
/// 2005) over the touching pairs in a fixed number of iterations a tick, as Box2D 2.4
/// (velocityIterations, positionIterations) and Chipmunk2D (iterations) do: the iteration
/// counts are part of the method, like dt, not caps. What one tick's iterations leave (an
/// impulse not yet at its limit, an overlap deeper than the slop) is carried into the next
/// tick by warm starting and the next tick's push-out; ContactStats reports both. More
/// iterations cost proportionally more and settle a deep pile in fewer ticks.
struct ContactSettings {
  double restitution = 0.0;  ///< e in [0, 1], every pair's default
  double friction = 0.0;     ///< Coulomb μ in [0, 1e100], every pair's default
  /// m/s, finite and >= 0: a shape contact point bounces (Newton's law, e above) only when it
  /// approaches faster than this, else it stops without a bounce, so that a body resting with
  /// e > 0 does not hop on gravity's speed each tick (Box2D's b2WorldDef::restitutionThreshold,
  /// 1 m/s). 0: every approach bounces (an elastic gas). Disc-disc and disc-plane contacts meet
  /// at their time of impact and bounce at any speed; this applies to shapes' manifolds only.
  double restitution_threshold = default_restitution_threshold;
  /// Velocity iterations a tick (normal and friction impulses), in [1, max_iterations]. The
  /// shapes' sweeps in a tick in which no joint is solved take a conjugate step after each but
  /// the last (from 3 iterations; a nonsmooth nonlinear conjugate gradient, Silcowitz, Niebe
  /// and Erleben 2010: docs/SHAPES.md), so a settled stack converges and its sweeps end before
  /// the count.
  int velocity_iterations = default_velocity_iterations;
  /// Position iterations a tick (push-out of overlap beyond the slop), in [0, max_iterations].
  /// The joints' own projection of the tick's error runs up to 10 steps however few these are
  /// (it ends as soon as it converges, a step that grows the error made shorter): fewer let a
  /// whipping chain of joints come apart.
  int position_iterations = default_position_iterations;
  /// Rolling discs: every dynamic body keeps an angle and an angular velocity (Body::angle,
  /// Body::angular_velocity), friction acts at the contact point (the relative tangential
  /// velocity there includes ω r of each disc) and its impulse P turns each disc by r × P / I
  /// (I: Collider::inertia, else ½ m r²), with plane contacts, disc impacts and resting
  /// contacts alike. Off (the default): no angle is stored or stepped, friction acts on the
  /// centres' velocities, and nothing is paid for it.
  bool rolling = false;
  /// Sleeping islands: bodies joined by resting contacts (discs' and shapes') and links form an
  /// island; one whose every body is a dynamic disc or body with shapes that has stayed slower
  /// than sleep_speed (its centre, and its rim when it turns) for sleep_time, without input,
  /// falls asleep: its velocities become 0 and it is neither stepped nor solved (it acts as a
  /// static body) until an awake body's motion over a tick comes near it, a resting contact or
  /// link joins it to an awake body, or input or an edit touches one of its bodies (Box2D's
  /// b2_timeToSleep rule, Catto 2006). Off (the default): every body is stepped every tick,
  /// as in a world from before sleeping; on, a sleeping island ignores the forces too small
  /// to wake it (a pile on a slowly tilting plane stays put).
  bool sleep = false;
  double sleep_speed = default_sleep_speed;  ///< m/s, finite and > 0
  double sleep_time = default_sleep_time;    ///< s, finite and >= 0 (rounded up to ticks)
  static constexpr double default_sleep_speed = 0.05, default_sleep_time = 0.5;
  static constexpr double default_restitution_threshold = 1.0;
  static constexpr int default_velocity_iterations = 20, default_position_iterations = 10;
  static constexpr int max_iterations = 1000;
};

/// A static half-plane n·x >= offset of free space (ground, wall), which bodies with a
/// Collider of radius r stay in: their centres keep n·x >= offset + r.
///
/// A contact is resolved at its time of impact inside the tick (world_contacts.cpp): the
/// normal velocity v_n (< 0, approaching) becomes -e v_n (Newton's restitution law), and the
/// tangential velocity v_t loses min(|v_t|, μ (1 + e) |v_n|) (Coulomb friction applied as an
/// impulse: the normal impulse is m (1 + e) |v_n|). A body that would bounce back by less than
/// one tick of its normal acceleration comes to rest on the plane and slides along it, with
/// Coulomb friction μ |a_n| (sliding friction force μ N).
struct PlaneDef {
  Vec2 normal{0.0, 1.0};     ///< n, points into free space; finite, != 0 (normalised by World)
  double offset = 0.0;       ///< m, within 1e12: the plane is n·x = offset (n normalised)
  double restitution = 0.0;  ///< e, finite, in [0, 1]
  double friction = 0.0;     ///< μ, in [0, 1e100]
};

/// A spring-damper between two bodies (a link): a rope segment, a cloth edge, a suspension.
///
/// Force on body a (body b gets the opposite), with d = x_a - x_b and u = v_a - v_b:
///   L = 0:  F = -k d - b u                                  (linear, each axis independent)
///   L > 0:  F = -k (|d| - L) d/|d| - b (u·d̂) d̂,  d̂ = d/|d|    (damping along the spring only)
/// The parameters of a link (LinkDef::spring).
struct LinkSpring {
  double stiffness = 0.0;    ///< k, N/m, finite and >= 0
  double damping = 0.0;      ///< b, N*s/m, finite and >= 0, on the relative velocity
  double rest_length = 0.0;  ///< L, m, finite and >= 0
};

/// A link between two bodies, in the spirit of Box2D's b2DistanceJointDef: what
/// World::create_link takes, and what WorldDef::links holds. Its bodies are handles: of live
/// bodies for create_link; for a WorldDef, the handles WorldDef::add_body returned (those
/// World(def) gives the definition's bodies).
struct LinkDef {
  Entity body_a;  ///< one end
  Entity body_b;  ///< the other end, != body_a
  LinkSpring spring{};
};

/// Spring stiffness (N/m) and damping (N*s/m) from the parameterization game programmers use:
/// natural frequency f (Hz) and damping ratio ζ of the spring acting on `mass` (kg):
///   ω = 2π f,  k = m ω²,  b = 2 m ζ ω.
/// For an anchored spring `mass` is the body's mass; for a link it is the pair's reduced mass
/// (reduced_mass()). Box2D v3 (b2DistanceJointDef hertz / dampingRatio) and Avian parameterize
/// springs the same way. Throws std::invalid_argument naming the parameter when frequency or
/// mass is not finite and > 0, or damping_ratio is not finite and >= 0.
[[nodiscard]] LinkSpring spring_from_frequency(double frequency_hz, double damping_ratio,
                                               double mass);
/// Reduced mass μ = m_a m_b / (m_a + m_b), kg, of two bodies (each finite and > 0 kg, else
/// std::invalid_argument): the mass a link between them oscillates with.
[[nodiscard]] double reduced_mass(double mass_a, double mass_b);

/// Everything needed to create one body entity, in the spirit of Box2D's b2BodyDef: fill in
/// what the body has; components left empty are not stored and cost nothing when stepping.
struct BodyDef {
  std::string name;                   ///< shown in CSV output and messages; may be empty
  BodyType type = BodyType::dynamic;  ///< static and kinematic bodies ignore body.mass
  Body body{};
  std::optional<SpringDamper> spring;
  std::optional<ConstantForce> constant_force;
  std::optional<Gravity> gravity;
  std::optional<LinearDrag> drag;
  std::optional<Appearance> appearance;
  std::optional<Collider> collider;  ///< contacts with the world's planes (World::add_plane)
  /// The shapes the body carries (shape.hpp), each at its pose in the body frame: a body with
  /// shapes turns (Body::angle, Body::angular_velocity) and meets planes, segments, discs and
  /// other shapes with contact manifolds. Empty: a point body or a disc (collider). A body has
  /// shapes or a collider, not both.
  std::vector<ShapeDef> shapes;
  /// Moment of inertia about the centre of mass, kg·m², in [1e-100, 1e100], of a dynamic body
  /// with shapes; unset: from the shapes (body_mass, shape.hpp).
  std::optional<double> inertia = std::nullopt;
  /// Makes the body a character mover (mover.hpp): a kinematic body with one capsule shape that
  /// each tick moves by collide-and-slide at the velocity the game wants. Unset: an ordinary
  /// body, and a world without movers pays nothing for them.
  std::optional<MoverDef> mover = std::nullopt;
  /// The program's own 64-bit value for this body (an index into its tables, a tag, a
  /// pointer's bits): kept with the body, copied by snapshots, never read by the physics nor
  /// part of the state or definition hash.
  std::uint64_t user_data = 0;
};

}  // namespace fixstep
