// The joint benchmark (bench_joints.cpp): three scenes of bodies with shapes held by joints,
// described once, engine-neutral, by one generator (joints_scene.cpp) and built from that
// description by fixstep (joints_fixstep.cpp: BodyDef::shapes, JointDef) and by Box2D v3.1.1 and
// v3.2 (joints_box2d3.cpp, where bench/box2d3.cmake built them); the joints' errors measured on
// every engine's poses the same way (joints_scene.cpp); the report (joints_report.cpp). Internal
// to bench/.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discs.hpp"
#include "fixstep/core/types.hpp"

namespace joints {

using fixstep::Vec2;

inline constexpr double tick = 1.0 / 60.0;  ///< s, every engine's step
inline constexpr double gravity = 10.0;     ///< m/s² along -y: b2DefaultWorldDef's
inline constexpr double friction = 0.6;     ///< μ of every shape but the car's tyres
inline constexpr double density = 1.0;      ///< kg/m², every shape: b2DefaultShapeDef's

// The chain: `chain_links` boxes of 0.5 m × 0.125 m (1 kg/m²) hinged end to end by revolute
// joints, the first to the world at the origin, laid out straight along +x at rest: it swings
// down and folds as it goes. Timed from its first tick for `chain_window` ticks (the swing
// through the bottom), no warm-up.
inline constexpr int chain_links = 100;
inline constexpr double chain_half_length = 0.25, chain_half_width = 0.0625;  ///< m
inline constexpr int chain_window = 300;
// The ragdoll pile: `ragdoll_count` ragdolls after Box2D's human (shared/human.c, scale 1: 11
// capsules, 1.6 m tall, 10 revolute joints with its angle limits; no joint friction, springs or
// feet, and limits that hold the straight start: the elbows' about the straight arm where Box2D
// sets a reference of π/4, the knees' upper 0 where Box2D's is −0.02π),
// each turned by a random angle in [-π, π) about its middle (SplitMix64), on a grid of
// `ragdoll_columns` columns `ragdoll_spacing` apart (the lowest row's middles at 1.6 m), dropped
// into a container (ground y = 0, walls x = 0 and x = width); a ragdoll's own capsules never
// touch (a negative collision group each). Warmed up for `ragdoll_warmup` ticks (the rows fall),
// then `ragdoll_window` ticks timed while they land and pile up.
inline constexpr int ragdoll_count = 100;
inline constexpr int ragdoll_bones = 11;
inline constexpr int ragdoll_columns = 8;
inline constexpr double ragdoll_spacing = 1.6;  ///< m
inline constexpr int ragdoll_warmup = 60, ragdoll_window = 240;
// The car: a 2.6 m × 0.6 m chassis box (1 kg/m²) on two wheels of radius 0.4 m (2 kg/m², μ
// 1.5, as Box2D's sample car) on wheel joints with a vertical suspension (frequency 4 Hz,
// damping ratio 0.7, travel ±0.25 m), the rear wheel driven by the motor (car_motor_speed
// within car_motor_torque), over a polyline terrain: flat to x = 10 m, then rolling bumps to
// x = 260 m, points 1 m apart (fixstep: WorldDef::add_polyline; Box2D: a chain shape). Timed
// from the first tick for `car_window` ticks (10 s); the distance is the chassis's x at the end
// less at the start.
inline constexpr double car_frequency = 4.0, car_damping_ratio = 0.7;  ///< Hz, ζ
inline constexpr double car_travel = 0.25;                             ///< m, each way
inline constexpr double car_motor_speed = -20.0;  ///< rad/s (clockwise: drives to +x)
inline constexpr double car_motor_torque = 5.0;   ///< N·m
inline constexpr double car_tyre_friction = 1.5;  ///< μ
inline constexpr int car_window = 600;

enum class JointSceneKind { chain, ragdoll_pile, car };
inline constexpr JointSceneKind joint_scene_kinds[] = {
    JointSceneKind::chain, JointSceneKind::ragdoll_pile, JointSceneKind::car};
[[nodiscard]] const char* joint_scene_name(JointSceneKind k);

/// A shape in its body's frame: a circle (center, radius), a capsule (a, b, radius) or a box
/// (center, half extents).
enum class ShapeKind { circle, capsule, box };
struct Shape {
  ShapeKind kind = ShapeKind::circle;
  Vec2 center{};  ///< m: circle, box
  Vec2 a{}, b{};  ///< m: capsule
  double radius = 0.0;
  Vec2 half{};  ///< m: box
  double density = joints::density;
  double friction = joints::friction;
};

/// A dynamic body at its start: origin and angle (the frame its shapes are in), its shapes, and
/// a collision group (negative: bodies of the same group never touch; 0: none).
struct BodySpec {
  Vec2 position{};
  double angle = 0.0;
  std::vector<Shape> shapes{};
  int group = 0;
};

enum class JointKind { revolute, wheel };
/// A joint, with its anchor and axis given in world coordinates at the start and in each
/// body's frame (the frame of the world for body -1). Revolute: the relative angle
/// θ_b − θ_a − reference within [lower, upper] (rad). Wheel: b's anchor (its hub) on the line
/// through a's anchor along the axis, the translation along it within [lower, upper] (m), a
/// spring towards 0 (frequency, damping ratio) and a motor turning b.
struct JointSpec {
  JointKind kind = JointKind::revolute;
  int body_a = -1;  ///< index into JointScene::bodies; -1: the world
  int body_b = 0;
  Vec2 anchor{};              ///< m, world, at the start
  Vec2 local_a{}, local_b{};  ///< m, the anchor in a's and b's frames
  double reference = 0.0;     ///< rad, θ_b − θ_a at the start
  Vec2 axis{0.0, 1.0};        ///< wheel: unit, world, at the start
  Vec2 local_axis{0.0, 1.0};  ///< wheel: unit, in a's frame
  std::optional<double> lower{}, upper{};
  double frequency = 0.0, damping_ratio = 0.0;       ///< Hz, ζ: wheel
  double motor_speed = 0.0, max_motor_torque = 0.0;  ///< rad/s, N·m (0: no motor)
};

/// One scene as every engine builds it: dynamic bodies, joints, and static geometry (a ground
/// y = 0 with walls x = 0 and x = width up to wall_height, and/or a terrain polyline).
struct JointScene {
  JointSceneKind kind = JointSceneKind::chain;
  std::vector<BodySpec> bodies{};
  std::vector<JointSpec> joints{};
  bool container = false;
  double width = 0.0, wall_height = 0.0;  ///< m
  std::vector<Vec2> terrain{};            ///< m, left to right; empty: none
  int warmup = 0;                         ///< ticks stepped before timing
  int window = 0;                         ///< ticks timed
  /// Appends `j` with its local anchors, axis and reference filled from the bodies' start.
  void add_joint(JointSpec j);
};

[[nodiscard]] JointScene make_chain(int links = chain_links);
[[nodiscard]] JointScene make_ragdoll_pile(int ragdolls = ragdoll_count, std::uint64_t seed = 7);
[[nodiscard]] JointScene make_car();
[[nodiscard]] JointScene make_joint_scene(JointSceneKind k);

/// A body's origin (m) and angle (rad).
struct Pose {
  Vec2 position{};
  double angle = 0.0;
  friend bool operator==(const Pose&, const Pose&) = default;
};

/// The joints' errors on a set of poses, the same code for every engine.
struct JointErrors {
  /// m: revolute, the distance between the anchor carried by a and by b; wheel, b's hub's
  /// distance from the axis line through a's anchor. The largest over the joints.
  double separation = 0.0;
  /// How far past a limit the deepest joint is: rad (revolute), m (wheel); 0 within.
  double beyond_limit = 0.0;
};
[[nodiscard]] JointErrors joint_errors(const JointScene& s, std::span<const Pose> poses);

/// The deepest overlap of the circles and capsules (boxes are not measured) on a set of poses:
/// between bodies that may touch (not one group, not joined), and into the ground and walls, m.
struct Overlaps {
  double between = 0.0;
  double statics = 0.0;
};
[[nodiscard]] Overlaps deepest_overlaps(const JointScene& s, std::span<const Pose> poses);

/// An engine stepping a joint scene at `tick`.
class JointStepper {
 public:
  virtual ~JointStepper() = default;
  virtual void step() = 0;
  /// The bodies' poses, in scene order.
  virtual void poses(std::vector<Pose>& out) const = 0;
  /// The engine's own deepest overlap over its contact manifolds, m (as boxes.hpp's).
  [[nodiscard]] virtual double own_overlap() const = 0;
  [[nodiscard]] virtual int threads() const = 0;
};

/// fixstep f64: BodyDef::shapes, JointDef, the container's ground and walls as PlaneDefs and the
/// terrain as WorldDef::add_polyline, WorldSettings::contacts, on `threads` threads.
[[nodiscard]] std::unique_ptr<JointStepper> make_fixstep_joints(const JointScene& s, int threads);
/// Box2D v3 (the release r) on `workers` workers, as its box stepper.
[[nodiscard]] std::unique_ptr<JointStepper> make_box2d3_joints(const JointScene& s, int workers,
                                                               discs::Box2d3Release r);

// --- the steppers by key, results and the report (joints_report.cpp) ------------------------

/// fixstep_t1, fixstep_t2; box2d3_w1, box2d3_w2 (v3.1.1); box2d32_w1, box2d32_w2 (v3.2): those
/// this build has.
[[nodiscard]] std::vector<std::string> joint_stepper_keys();
[[nodiscard]] std::string joint_stepper_label(const std::string& key);
[[nodiscard]] std::unique_ptr<JointStepper> make_joint_stepper(const std::string& key,
                                                               const JointScene& s);

/// One case, "<scene>/<stepper>".
struct JointCase {
  double ns_per_body_step =
      0.0;              ///< median over the rounds of the window's time / (bodies × ticks)
  double spread = 0.0;  ///< (slowest − fastest round) / median
  double bodies = 0.0, joints = 0.0;
  double separation = 0.0;      ///< m, the largest JointErrors::separation over the window
  double beyond_limit = 0.0;    ///< rad or m, the largest over the window
  double overlap = 0.0;         ///< m, Overlaps::between after the window
  double static_overlap = 0.0;  ///< m, Overlaps::statics after the window
  double own_overlap = 0.0;     ///< m, the engine's own after the window
  double distance = 0.0;        ///< m, the first body's x at the window's end less at its start
  int threads = 1;
};

struct JointResults {
  std::map<std::string, JointCase> cases{};
  int rounds = 1;
  double load_start = 0.0, load_end = 0.0;  ///< 1-minute load average
  /// A cache line's round trip between the first two CPUs (core_round_trip_ns()), ns; NaN
  /// where not measured.
  double round_trip_start = std::numeric_limits<double>::quiet_NaN(),
         round_trip_end = std::numeric_limits<double>::quiet_NaN();
};

[[nodiscard]] std::string joint_report_markdown(const JointResults& r);

}  // namespace joints
