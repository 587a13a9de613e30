// fixstep stepping a joint scene: World (f64, semi-implicit Euler, the default) built from a
// WorldDef with one dynamic body per scene body carrying its shapes (BodyDef::shapes: circles,
// capsules and boxes with the scene's densities, μ and collision group), Gravity -10 m/s², one
// JointDef per scene joint (revolute: the anchor and the limits; wheel: the hub as anchor, the
// axis, the suspension's frequency and damping ratio, its travel as lower/upper, the motor;
// collide_connected false), the container's ground and walls as static half-planes (PlaneDef)
// and the terrain as a polyline (WorldDef::add_polyline), WorldSettings::contacts on (μ 0.6,
// e 0, the default iterations) and WorldSettings::threads 1 or 2.
//
// The poses are World::body()'s position (the body's origin, the frame its shapes are in) and
// angle, measured by joints_scene.cpp as for Box2D; fixstep's own deepest overlap is
// ContactStats::deepest_shape_overlap (the manifold points of the last tick).
#include <memory>

#include "fixstep/core/components.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "joints.hpp"

namespace joints {

namespace {

fixstep::ShapeDef shape_def(const Shape& s, int group) {
  fixstep::ShapeDef d;
  switch (s.kind) {
    case ShapeKind::circle:
      d = fixstep::make_circle(s.radius, s.center);
      break;
    case ShapeKind::capsule:
      d = fixstep::make_capsule(s.a, s.b, s.radius);
      break;
    case ShapeKind::box:
      d = fixstep::make_box(s.half.x, s.half.y, s.center);
      break;
  }
  d.density = s.density;
  d.friction = s.friction;
  d.restitution = 0.0;
  d.filter.group = group;
  return d;
}

fixstep::WorldDef world_def(const JointScene& s, int threads) {
  fixstep::WorldSettings ws{.dt = tick, .threads = threads};
  ws.contacts = fixstep::ContactSettings{.restitution = 0.0, .friction = friction};
  fixstep::WorldDef def = fixstep::WorldDef::empty(fixstep::Precision::f64, ws);
  if (s.container) {
    const auto wall = [&](Vec2 normal, double offset) {
      def.planes.push_back(
          {.normal = normal, .offset = offset, .restitution = 0.0, .friction = friction});
    };
    wall({0.0, 1.0}, 0.0);        // the ground, y >= 0
    wall({1.0, 0.0}, 0.0);        // x >= 0
    wall({-1.0, 0.0}, -s.width);  // x <= width
  }
  if (!s.terrain.empty()) def.add_polyline(s.terrain, 0.0, friction);
  std::vector<fixstep::Entity> bodies;
  bodies.reserve(s.bodies.size());
  for (const BodySpec& b : s.bodies) {
    fixstep::BodyDef d;
    d.body = {.position = b.position, .angle = b.angle};
    d.gravity = fixstep::Gravity{{0.0, -gravity}};
    for (const Shape& sh : b.shapes) d.shapes.push_back(shape_def(sh, b.group));
    bodies.push_back(def.add_body(std::move(d)));
  }
  const auto body = [&](int i) { return i < 0 ? fixstep::Entity{} : bodies[std::size_t(i)]; };
  for (const JointSpec& j : s.joints) {
    fixstep::JointDef d{.body_a = body(j.body_a), .body_b = body(j.body_b), .anchor = j.anchor};
    d.lower = j.lower;
    d.upper = j.upper;
    if (j.kind == JointKind::wheel) {
      d.type = fixstep::JointType::wheel;
      d.axis = j.axis;
      d.frequency = j.frequency;
      d.damping_ratio = j.damping_ratio;
      if (j.max_motor_torque > 0.0) {
        d.motor_speed = j.motor_speed;
        d.max_motor_torque = j.max_motor_torque;
      }
    }
    def.joints.push_back(d);
  }
  return def;
}

class FixstepJoints final : public JointStepper {
 public:
  FixstepJoints(const JointScene& s, int threads)
      : world_(world_def(s, threads)), threads_(threads) {}
  void step() override { world_.step(); }
  void poses(std::vector<Pose>& out) const override {
    const auto bodies = world_.defined_bodies();
    out.resize(bodies.size());
    for (std::size_t j = 0; j < bodies.size(); ++j) {
      const fixstep::Body b = world_.body(bodies[j]);
      out[j] = {b.position, b.angle};
    }
  }
  [[nodiscard]] double own_overlap() const override {
    return world_.contact_stats().deepest_shape_overlap;
  }
  [[nodiscard]] int threads() const override { return threads_; }

 private:
  fixstep::World world_;
  int threads_ = 1;
};

}  // namespace

std::unique_ptr<JointStepper> make_fixstep_joints(const JointScene& s, int threads) {
  return std::make_unique<FixstepJoints>(s, threads);
}

}  // namespace joints
