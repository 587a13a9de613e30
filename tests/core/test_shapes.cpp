// Bodies with shapes in a world: the exact checks against closed forms and bounds (their worlds
// in tests/cross/shape_exact.cpp), contact and sensor events, the energy account, the broadphase
// caps, and the same bits after a snapshot, on two threads and in f32.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "plain_sweeps.hpp"
#include "shape_exact.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

constexpr double g = 9.81;

WorldSettings shape_world(double mu, double e = 0.0) {
  return shape_exact::shape_settings(mu, e);
}
using shape_exact::box_body;

// --- the exact checks (tests/cross/shape_exact.cpp, which the cross builds run too) ---------

class ShapeExact : public ::testing::TestWithParam<shape_exact::Check> {};

TEST_P(ShapeExact, MeasuresWithinTheClosedFormOrBound) {
  for (const shape_exact::Measure& m : GetParam().run()) {
    EXPECT_TRUE(m.holds()) << m.what << ": " << m.value << " not in [" << m.low << ", " << m.high
                           << "]";
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, ShapeExact, ::testing::ValuesIn(shape_exact::checks()),
                         [](const auto& info) { return info.param.name; });

// --- events and sensors --------------------------------------------------------------------

TEST(ShapeEvents, ABoxLandingOnABoxBeginsAContactAndASensorSeesItPass) {
  World w(WorldDef::empty(Precision::f64, shape_world(0.5)));
  BodyDef base;
  base.type = BodyType::static_body;
  base.shapes = {make_box(2.0, 0.5)};
  const Entity floor = w.create_body(base);
  BodyDef gate;  // a sensor box the falling box passes through on its way down
  gate.type = BodyType::static_body;
  gate.body.position = {0.0, 3.0};
  gate.shapes = {make_box(1.0, 0.1)};
  gate.shapes[0].sensor = true;
  const Entity sensor = w.create_body(gate);
  const Entity box = w.create_body(box_body(0.5, 0.5, {0.0, 5.0}));
  int begun = 0, sensed_in = 0, sensed_out = 0;
  double speed = 0.0;
  for (int i = 0; i < 180; ++i) {
    w.step();
    for (const ContactEvent& e : w.contacts_begun()) {
      EXPECT_TRUE((e.a == floor && e.b == box) || (e.a == box && e.b == floor));
      ++begun, speed = e.normal_speed;
    }
    for (const SensorEvent& e : w.sensors_begun()) {
      EXPECT_EQ(e.sensor, sensor);
      EXPECT_EQ(e.visitor, box);
      ++sensed_in;
    }
    sensed_out += static_cast<int>(w.sensors_ended().size());
  }
  EXPECT_EQ(begun, 1);
  // It falls 4 m (from a centre at 5 m to its face on the floor at 0.5 m... 4 m) from rest:
  // v = √(2 g h) within a tick's gain.
  EXPECT_NEAR(speed, std::sqrt(2.0 * g * 4.0), g / 60.0 + 0.1);
  EXPECT_EQ(sensed_in, 1);
  EXPECT_EQ(sensed_out, 1);
  EXPECT_TRUE(w.contacts_ended().empty());
}

// A begun contact's closing speed is its fastest point's. A level box turning as it comes down
// 1 cm above the floor meets it at the first tick with both bottom corners, one closing faster
// by 2 ω h: each point's closing speed is −(v_y − g dt ± ω h), at the free velocities and the
// corners' arms ±h. Turned either way, so that the faster point is the manifold's first in one
// and its second in the other.
TEST(ShapeEvents, ABegunContactsSpeedIsItsFastestPointsForATurningBoxEitherWay) {
  for (const double omega : {1.0, -1.0}) {
    const WorldSettings settings = shape_world(0.5);
    World w(WorldDef::empty(Precision::f64, settings));
    BodyDef base;
    base.type = BodyType::static_body;
    base.shapes = {make_box(2.0, 0.5)};
    w.create_body(base);
    const double h = 0.5, vy = -3.0;
    BodyDef falling = box_body(h, h, {0.0, 0.5 + h + 0.01});
    falling.body.velocity = {0.0, vy};
    falling.body.angular_velocity = omega;
    const Entity box = w.create_body(falling);
    w.step();
    ASSERT_EQ(w.contacts_begun().size(), 1u) << "ω " << omega;
    EXPECT_TRUE(w.contacts_begun()[0].a == box || w.contacts_begun()[0].b == box);
    const double free = vy - g * settings.dt;
    const double right = -(free + omega * h), left = -(free - omega * h);
    EXPECT_NEAR(w.contacts_begun()[0].normal_speed, std::max(right, left), 1e-9)
        << "ω " << omega << ": the corners close at " << left << " and " << right << " m/s";
  }
}

// A disc sensor sees bodies with shapes as a sensor shape sees discs: a box falling through a
// static sensor disc begins and ends one overlap, at the ticks its faces cross the disc's
// circle (it falls from rest at 5 m: its bottom face reaches the top of the disc, y = 3.25 m,
// at t = √(2 · 1.25 m / g), its top face leaves the bottom, y = 2.75 m, at √(2 · 2.75 m / g)).
TEST(ShapeEvents, ADiscSensorSeesABoxFallThroughIt) {
  World w(WorldDef::empty(Precision::f64, shape_world(0.5)));
  BodyDef ring;
  ring.type = BodyType::static_body;
  ring.body.position = {0.0, 3.0};
  ring.collider = Collider{.radius = 0.25, .sensor = true};
  const Entity sensor = w.create_body(ring);
  BodyDef falling = box_body(0.5, 0.5, {0.0, 5.0});
  const Entity box = w.create_body(falling);
  std::vector<int> in, out;
  for (int i = 1; i <= 120; ++i) {
    w.step();
    for (const SensorEvent& e : w.sensors_begun()) {
      EXPECT_EQ(e.sensor, sensor);
      EXPECT_EQ(e.visitor, box);
      in.push_back(i);
    }
    for (const SensorEvent& e : w.sensors_ended()) {
      EXPECT_EQ(e.visitor, box);
      out.push_back(i);
    }
  }
  ASSERT_EQ(in.size(), 1u);
  ASSERT_EQ(out.size(), 1u);
  // The first tick that ends with the faces past the circle: semi-implicit Euler's fall by
  // tick n is g dt² n (n + 1) / 2.
  auto first_tick_past = [](double drop) {
    const double dt = 1.0 / 60.0;
    int n = 0;
    while (g * dt * dt * n * (n + 1) / 2.0 < drop) ++n;
    return n;
  };
  EXPECT_EQ(in[0], first_tick_past(1.25));
  EXPECT_EQ(out[0], first_tick_past(2.75));
}

// --- the energy account ------------------------------------------------------------------

TEST(ShapeEnergy, TheAccountBalancesForATumblingPileAndAKinematicPaddle) {
  WorldSettings settings = shape_world(0.4, 0.3);
  settings.track_dissipation = true;
  settings.integrator = Integrator::velocity_verlet;  // exact in free fall: no drift to count
  World w(WorldDef::empty(Precision::f64, settings));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.3, .friction = 0.4});
  for (int i = 0; i < 12; ++i) {
    BodyDef b = box_body(0.3, 0.2, {0.5 * (i % 4) - 0.75, 0.5 + 0.6 * (i / 4)}, 0.3 * i);
    if (i % 3 == 1) b.shapes = {make_capsule({-0.25, 0.0}, {0.25, 0.0}, 0.15)};
    w.create_body(b);
  }
  BodyDef paddle;  // a kinematic paddle turning through the pile: its work is external
  paddle.type = BodyType::kinematic;
  paddle.body.position = {0.0, 0.6};
  paddle.body.angular_velocity = 3.0;
  paddle.shapes = {make_box(1.5, 0.05)};
  w.create_body(paddle);
  const double e0 = w.energy().total();
  for (int i = 0; i < 240; ++i) {
    w.step();
    const double balance = w.energy().total() + w.dissipated_energy() - w.external_work() - e0;
    ASSERT_NEAR(balance, 0.0, 1e-9 * (std::abs(e0) + w.external_work())) << "tick " << i;
  }
  EXPECT_GT(w.dissipated_energy(), 0.0);
  EXPECT_GT(std::abs(w.external_work()), 0.0);
}

// --- no silent caps -----------------------------------------------------------------------

TEST(ShapeCaps, ACrowdOfOverlappingBoxesStopsWithALocatedFault) {
  World w(WorldDef::empty(Precision::f64, shape_world(0.5)));
  for (int i = 0; i < 2000; ++i) w.create_body(box_body(0.5, 0.5, {0.001 * i, 0.0}));
  w.step();
  ASSERT_TRUE(w.fault().has_value());
  EXPECT_EQ(w.fault()->cap, "max_candidate_pairs");
  EXPECT_EQ(w.fault()->field, "contacts");
  EXPECT_NE(w.fault()->with.find("2000 shapes"), std::string::npos) << w.fault()->with;
}

TEST(ShapeCaps, AColumnOfBoxesPairsWithoutReachingAWorkLimit) {
  // 6000 boxes 1 m wide, one above another 2 m apart, all falling alike (no pair forms), so
  // that every box lies in every other's x-interval: a sweep and prune on x tests n(n - 1)/2 =
  // 1.8·10^7 pairs of them, past max_vetoed_pairs (1.6·10^7), where the grid looks at each
  // box's neighbours.
  detail::WorldKernel<double> w(shape_world(0.5));
  std::vector<Entity> boxes;
  for (int i = 0; i < 6000; ++i) boxes.push_back(w.create_body(box_body(0.5, 0.5, {0.0, 2.0 * i})));
  w.step();
  ASSERT_FALSE(w.fault().has_value()) << w.fault()->cap;
  EXPECT_TRUE(w.shape_world()->candidates().empty());
  const double top = w.body(boxes.back()).position.y - 2.0 * 5999;
  EXPECT_LT(top, 0.0);  // it fell
  EXPECT_NEAR(top, w.body(boxes.front()).position.y,
              1e-9);  // as the lowest did (rounding at 12 km)
}

// --- the velocity sweeps end once converged ----------------------------------------------

/// A box of 1 m × 1 m resting on the ground, and beside it (6 m off) a pyramid of boxes
/// `rows` high, each row one box shorter, dropped from 1 cm above their rests.
WorldDef resting_boxes(int rows) {
  WorldDef def = WorldDef::empty(Precision::f64, shape_world(0.6));
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  def.add_body(box_body(0.5, 0.5, {0.0, 0.5}));
  for (int r = 0; r < rows; ++r) {
    for (int k = 0; k < rows - r; ++k) {
      def.add_body(box_body(0.5, 0.5, {6.0 + k + 0.5 * r, 0.51 + 1.01 * r}));
    }
  }
  return def;
}

TEST(ShapeSweeps, EndOnceASweepChangesNoVelocityAndNotBefore) {
  // One box at rest: warm started with last tick's impulses, which hold it, its first sweep
  // changes nothing.
  World lone(resting_boxes(0));
  for (int i = 0; i < 60; ++i) lone.step();
  EXPECT_EQ(lone.contact_stats().shape_velocity_sweeps, 1);
  const Body box = lone.body(lone.bodies()[0]);
  EXPECT_NEAR(box.position.y, 0.5, 1e-9);
  EXPECT_LT(std::hypot(box.velocity.x, box.velocity.y), 1e-9);
  // A pyramid's plain sweeps keep changing its impulses (Gauss-Seidel on a stack): all of them
  // run. (Its conjugate steps settle it, and then its sweeps end: ShapeConjugate.)
  const test::PlainSweeps plain;
  World pyramid(resting_boxes(5));
  for (int i = 0; i < 60; ++i) pyramid.step();
  EXPECT_EQ(pyramid.contact_stats().shape_velocity_sweeps,
            ContactSettings::default_velocity_iterations);
}

// Without joints too every sweep polls (Joints.EveryJointSweepPollsAStopRequest has joints): a
// large box world's tick (up to ContactSettings' largest iteration counts) stops within a sweep
// of a stop request, not at the tick's end.
TEST(ShapeSweeps, EverySweepOfAWorldWithoutJointsPollsAStopRequest) {
  const test::PlainSweeps plain;  // (so that a pyramid runs every sweep)
  detail::WorldKernel<double> w(shape_exact::shape_settings(0.6));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  for (int row = 0; row < 5; ++row) {  // a pyramid: every velocity sweep runs (a stack)
    for (int k = 0; k < 5 - row; ++k) {
      w.create_body(shape_exact::box_body(0.5, 0.5, {k + 0.5 * row, 0.51 + 1.01 * row}));
    }
  }
  for (int i = 0; i < 60; ++i) w.step();
  const std::uint64_t before = w.shape_world()->stop_polls();
  w.step();
  const auto sweeps = static_cast<std::uint64_t>(w.contact_stats().shape_velocity_sweeps);
  EXPECT_EQ(sweeps, std::uint64_t{ContactSettings::default_velocity_iterations});
  const std::uint64_t polls = w.shape_world()->stop_polls() - before;
  EXPECT_GE(polls, sweeps + 1) << "every velocity sweep and at least one push-out sweep";
  EXPECT_LE(polls, sweeps + ContactSettings::default_position_iterations);
  request_stop(2);
  EXPECT_THROW(w.step(), StopRequested);
  clear_stop_request();
}

TEST(ShapeSweeps, AFreelySwingingChainNeedsTwoSweepsOfItsForest) {
  // Revolute joints alone, no contact: the forest's direct solve makes every anchor's velocity
  // error zero in the first sweep; the second finds nothing left and ends the sweeps.
  World w(WorldDef::empty(Precision::f64, shape_world(0.6)));
  Entity last{};
  for (int k = 0; k < 10; ++k) {
    const Entity link = w.create_body(box_body(0.25, 0.0625, {0.25 + 0.5 * k, 0.0}));
    JointDef j;
    j.type = JointType::revolute;
    j.body_a = last, j.body_b = link;
    j.anchor = {0.5 * k, 0.0};
    w.create_joint(j);
    last = link;
  }
  for (int i = 0; i < 30; ++i) {
    w.step();
    EXPECT_EQ(w.contact_stats().shape_velocity_sweeps, 2) << "tick " << i + 1;
  }
}

// --- the same bits -------------------------------------------------------------------------

WorldDef box_rain() {
  WorldDef def = WorldDef::empty(Precision::f64, shape_world(0.5, 0.2));
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.5});
  for (int i = 0; i < 40; ++i) {
    BodyDef b =
        box_body(0.3 + 0.01 * (i % 5), 0.2, {0.7 * (i % 8) - 2.5, 1.0 + 0.6 * (i / 8)}, 0.1 * i);
    if (i % 3 == 0) b.shapes = {make_capsule({-0.3, 0.0}, {0.3, 0.0}, 0.15)};
    def.add_body(b);
  }
  return def;
}

TEST(ShapeDeterminism, ASnapshotStepsOnToTheSameBitsAndTwoThreadsMatchOne) {
  World a(box_rain());
  for (int i = 0; i < 60; ++i) a.step();
  WorldSnapshot snap;
  a.save(snap);
  for (int i = 0; i < 60; ++i) a.step();
  const std::uint64_t h = a.state_hash();
  a.restore(snap);
  for (int i = 0; i < 60; ++i) a.step();
  EXPECT_EQ(a.state_hash(), h);
  WorldDef two = box_rain();
  two.settings.threads = 2;
  World b(two);
  for (int i = 0; i < 120; ++i) b.step();
  EXPECT_EQ(b.state_hash(), h);
}

// --- continuous collision against what does not move ---------------------------------------

// A box at rest 5.5 cm from a one-centimetre static wall is knocked by another at 300 m/s: the
// contact sends it at the wall within the tick, further than its speculative margin (from
// rest) reached, so its continuous check against the static bodies stops it. `far_tiles` more
// static boxes lie 20 m below, out of the way, added last.
WorldDef knocked_box(int far_tiles) {
  WorldDef def = WorldDef::empty(Precision::f64, shape_world(0.3));
  auto add_static = [&](Vec2 at, double hx, double hy) {
    BodyDef b;
    b.type = BodyType::static_body;
    b.body.position = at;
    b.shapes = {make_box(hx, hy)};
    def.add_body(b);
  };
  add_static({0.805, 0.0}, 0.005, 5.0);
  BodyDef box = box_body(0.25, 0.25, {0.0, 0.0});
  box.gravity.reset();
  def.add_body(box);
  BodyDef bat = box_body(0.5, 0.5, {-1.0, 0.0});
  bat.gravity.reset();
  bat.body.velocity = {300.0, 0.0};
  def.add_body(bat);
  for (int i = 0; i < far_tiles; ++i) add_static({i - 0.5 * far_tiles, -20.0}, 0.5, 0.5);
  return def;
}

// With the far boxes the world has min_grid_shapes shapes or more, and the static shapes a fast
// body may meet come from the broadphase's grid, not from a scan of every static body: the box
// must stop at the wall the same way, to the same bits.
TEST(ShapeContinuous, AKnockedBoxStopsAtAThinWallWithFarStaticBodiesToTheSameBits) {
  static_assert(1 + 2 + 200 >= detail::ShapeWorld::min_grid_shapes);
  World few(knocked_box(0)), many(knocked_box(200));
  const Entity box_few = few.bodies()[1], box_many = many.bodies()[1];
  double furthest = 0.0;
  for (int i = 0; i < 10; ++i) {
    few.step(), many.step();
    const Body a = few.body(box_few), b = many.body(box_many);
    EXPECT_EQ(a.position.x, b.position.x) << "tick " << i + 1;
    EXPECT_EQ(a.position.y, b.position.y) << "tick " << i + 1;
    EXPECT_EQ(a.angle, b.angle) << "tick " << i + 1;
    furthest = std::max(furthest, b.position.x);
  }
  EXPECT_GT(furthest, 0.3) << "it was knocked";
  EXPECT_LT(furthest, 0.805) << "its centre stays short of the wall's middle";
}

// The same knock down at a plane, in a world with no static body and no segment: the plane
// alone must still stop the box (a world with nothing that does not move skips the pass).
TEST(ShapeContinuous, AKnockedBoxStopsAtAPlaneInAWorldWithoutStaticBodies) {
  WorldDef def = WorldDef::empty(Precision::f64, shape_world(0.3));
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = -0.8});
  BodyDef box = box_body(0.25, 0.25, {0.0, 0.0});
  box.gravity.reset();
  def.add_body(box);
  BodyDef bat = box_body(0.5, 0.5, {0.0, 1.0});
  bat.gravity.reset();
  bat.body.velocity = {0.0, -300.0};
  def.add_body(bat);
  World w(def);
  const Entity knocked = w.bodies()[0];
  double lowest = 0.0;
  for (int i = 0; i < 10; ++i) {
    w.step();
    lowest = std::min(lowest, w.body(knocked).position.y);
  }
  EXPECT_LT(lowest, -0.3) << "it was knocked";
  EXPECT_GT(lowest, -0.8) << "its centre stays short of the plane (without the pass: -1.05)";
}

// In f32 a body's angle and angular velocity are floats after every tick, as its position and
// velocity are. GCC 12 on x86-64 merged the write-back's two double(static_cast<float>(x))
// stores into one vector store without the rounding (world_kernel.hpp, rounded_to), and f32
// worlds with shapes stepped to other bits than on aarch64 from their second tick.
TEST(ShapeDeterminism, AnF32WorldKeepsItsAnglesAndSpinsInFloat) {
  detail::WorldKernel<float> w(shape_world(0.5));
  BodyDef paddle = box_body(1.0, 0.1, {0.0, 3.0}, 0.3);
  paddle.type = BodyType::kinematic;
  paddle.body.angular_velocity = 2.0;
  const Entity turning = w.create_body(paddle);
  BodyDef thrown = box_body(0.3, 0.3, {-3.0, 1.0}, 0.4);
  thrown.body.angular_velocity = -6.0;
  const Entity spinning = w.create_body(thrown);
  const auto is_float = [](double v) { return double(static_cast<float>(v)) == v; };
  for (int t = 0; t < 30; ++t) {
    w.step();
    for (const Entity e : {turning, spinning}) {
      const Body b = w.body(e);
      EXPECT_TRUE(is_float(b.angle)) << "tick " << t + 1 << ": angle " << b.angle;
      EXPECT_TRUE(is_float(b.angular_velocity)) << "tick " << t + 1 << ": " << b.angular_velocity;
    }
  }
}

}  // namespace
}  // namespace fixstep
