// The box benchmark (bench_boxes.cpp), for the rotating-shapes work: two scenes of 1 m boxes,
// built once by one generator (boxes_scene.cpp) and stepped by Box2D v3.1.1 and v3.2
// (boxes_box2d3.cpp, where bench/box2d3.cmake built them) and by fixstep with BodyDef::shapes
// (boxes_fixstep.cpp, once World steps shapes); the deepest overlap measured on every engine's
// poses the same way (boxes_scene.cpp), and Box2D's own from its contact manifolds; the report
// (boxes_report.cpp). Internal to bench/.
#pragma once

#include <cstddef>
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

namespace boxes {

using fixstep::Vec2;

inline constexpr double tick = 1.0 / 60.0;  ///< s, every engine's step
inline constexpr double half = 0.5;         ///< m, every box's half-extent: 1 m squares
inline constexpr double density = 1.0;      ///< kg/m²: every box 1 kg
inline constexpr double gravity = 10.0;     ///< m/s² along -y: b2DefaultWorldDef's
inline constexpr double friction = 0.6;     ///< μ, every shape: b2DefaultShapeDef's
inline constexpr double restitution = 0.0;  ///< e, every shape: b2DefaultShapeDef's

// The pyramid: Box2D's benchmark pyramid (box2d shared/benchmarks.c, CreateLargePyramid, at
// its BENCHMARK_DEBUG size of 20 rows; samples/sample_benchmark.cpp "Large Pyramid" shows it):
// rows i = 0..19 of 20 - i boxes of 1 m, centred at x = (i + 1) a + 2 (j - i) a - 20 a,
// y = (2 i + 1) a with a = 0.5 m (touching, no gap), 210 boxes on a static ground box whose top
// is y = 0. Warmed up for `pyramid_warmup` ticks, untimed, then timed.
inline constexpr int pyramid_rows = 20;
inline constexpr int pyramid_warmup = 60;
// The tower: 20 boxes of 1 m stacked one on another, centred at x = 0, y = (2 i + 1) a
// (touching), on the same ground; warmed up and timed as the pyramid (the shapes issue's
// "20-box tower", against Box2D on the same scene).
inline constexpr int tower_boxes = 20;
// The box pile: N boxes dropped into a container (ground y = 0, walls x = 0 and x = width) from
// a grid of columns = ⌈2 √N⌉ and as many rows as N needs, 1.3 m apart (the lowest row's centres
// 1 m up), each turned by a random angle in [-0.25, 0.25] rad (a SplitMix64 stream; at 1.3 m no
// two boxes overlap at tick 0). The lower rows land and pile up while the upper ones still fall:
// timed after `pile_warmup` ticks, while settling (N = 10⁴: rows of 200, 50 rows, 65 m high).
inline constexpr double pile_spacing = 1.3;    ///< m
inline constexpr double pile_max_tilt = 0.25;  ///< rad
inline constexpr int pile_warmup = 120;

enum class BoxSceneKind { pyramid, tower, box_pile };
[[nodiscard]] const char* box_scene_name(BoxSceneKind k);

/// A box's centre (m) and angle (rad, counter-clockwise).
struct Pose {
  Vec2 position{};
  double angle = 0.0;
  friend bool operator==(const Pose&, const Pose&) = default;
};

/// One scene as every engine builds it: dynamic boxes of half-extent `half` at rest, the ground
/// y = 0 (free space above) and, for a container, walls x = 0 and x = width up to wall_height.
struct BoxScene {
  BoxSceneKind kind = BoxSceneKind::pyramid;
  std::vector<Pose> start{};
  double width = 0.0;  ///< m, the container's inside; 0: the ground only (the pyramid)
  double wall_height = 0.0;
  int warmup = 0;  ///< ticks stepped before timing
};

[[nodiscard]] BoxScene make_pyramid(int rows = pyramid_rows);
[[nodiscard]] BoxScene make_tower(int boxes = tower_boxes);
[[nodiscard]] BoxScene make_box_pile(std::size_t n, std::uint64_t seed = 23);
/// The pyramid and the tower ignore n (always 210 and 20 boxes).
[[nodiscard]] BoxScene make_box_scene(BoxSceneKind k, std::size_t n);

/// The overlap of two 1 m boxes by the separating axis theorem: the smallest overlap of their
/// projections on the four face normals (the shortest translation that parts them), m; 0 when
/// an axis separates them.
[[nodiscard]] double box_penetration(const Pose& a, const Pose& b);
/// What the boxes look like, measured the same way for every engine.
struct BoxQuality {
  double box_overlap = 0.0;     ///< deepest box_penetration over all pairs, m (>= 0)
  double static_overlap = 0.0;  ///< deepest vertex below the ground or past a wall, m (>= 0)
  /// The pyramid: its top box's drop from its start, m (how far the pyramid has sagged or
  /// fallen); the pile: the mean height of the boxes' centres, m.
  double height = 0.0;
};
/// Overlaps by a uniform grid of cell 1.5 m (each box against its 3 x 3 cells): O(N).
[[nodiscard]] BoxQuality measure_boxes(const BoxScene& s, std::span<const Pose> poses);
/// The deepest box-box overlap by testing all pairs (the grid's check), m.
[[nodiscard]] double box_overlap_brute_force(std::span<const Pose> poses);

/// An engine stepping a box scene at `tick`.
class BoxStepper {
 public:
  virtual ~BoxStepper() = default;
  virtual void step() = 0;
  /// The boxes' poses, in scene order.
  virtual void poses(std::vector<Pose>& out) const = 0;
  /// The engine's own deepest overlap: Box2D, the largest -separation over the manifold
  /// points of its touching contacts (as of its last collide phase, at the start of the last
  /// step), m; NaN where the engine reports none.
  [[nodiscard]] virtual double own_overlap() const = 0;
  [[nodiscard]] virtual int threads() const = 0;
};

/// Why fixstep cannot step the box scenes yet, or nothing once it can: World(def) refused the
/// shapes (its message), or a 1 m box dropped from 1 m does not come to rest on the ground
/// (World accepted BodyDef::shapes but did not collide them).
[[nodiscard]] std::optional<std::string> fixstep_shapes_problem();
/// fixstep f64 with BodyDef::shapes (a box each), the ground and walls as PlaneDefs,
/// WorldSettings::contacts (the scene's μ and e) on `threads` threads. Throws what World(def)
/// throws.
[[nodiscard]] std::unique_ptr<BoxStepper> make_fixstep_boxes(const BoxScene& s, int threads);
/// Box2D v3 (the release r) on `workers` workers, as its disc stepper (discs::make_box2d3).
[[nodiscard]] std::unique_ptr<BoxStepper> make_box2d3_boxes(const BoxScene& s, int workers,
                                                            discs::Box2d3Release r);

// --- the steppers by key, results and the report (boxes_report.cpp) -----------------------

/// fixstep_t1, fixstep_t2; box2d3_w1, box2d3_w2 (v3.1.1); box2d32_w1, box2d32_w2 (v3.2): those
/// this build has (fixstep's whether or not World steps shapes yet).
[[nodiscard]] std::vector<std::string> box_stepper_keys();
[[nodiscard]] std::string box_stepper_label(const std::string& key);
[[nodiscard]] std::unique_ptr<BoxStepper> make_box_stepper(const std::string& key,
                                                           const BoxScene& s);

/// One timed case: "<scene>/<stepper>/<N>".
struct BoxCase {
  double ns_per_body_step = 0.0;  ///< median real time of a step / dynamic boxes
  double bodies = 0.0;
  double ticks = 0.0;           ///< ticks stepped when the overlap was measured
  double box_overlap = 0.0;     ///< m, measure_boxes after the timed steps
  double static_overlap = 0.0;  ///< m
  double own_overlap = 0.0;     ///< m, the engine's own (NaN: none)
  double height = 0.0;          ///< m, BoxQuality::height
  int threads = 1;
};

struct BoxResults {
  std::map<std::string, BoxCase> cases{};
  std::vector<std::int64_t> pile_sizes{};
  int repetitions = 1;
  double load_start = 0.0, load_end = 0.0;  ///< 1-minute load average
  /// A cache line's round trip between the first two CPUs (core_round_trip_ns()), ns; NaN
  /// where not measured.
  double round_trip_start = std::numeric_limits<double>::quiet_NaN(),
         round_trip_end = std::numeric_limits<double>::quiet_NaN();
  std::optional<std::string> fixstep_problem;  ///< fixstep_shapes_problem() of this run
};

[[nodiscard]] std::string box_report_markdown(const BoxResults& r);

}  // namespace boxes
