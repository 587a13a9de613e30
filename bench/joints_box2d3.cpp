// Box2D v3 (compiled once per release, v3.1.1 and v3.2: FIXSTEP_BOX2D3_MINOR) stepping a joint
// scene, on 1 worker or on 2 as its box stepper (boxes_box2d3.cpp: v3.1 Box2d3Tasks, v3.2 its
// own scheduler).
//
// One dynamic body per scene body (b2BodyDef position and rotation) with the scene's shapes
// (b2Circle, b2Capsule, b2MakeOffsetBox polygons; density, friction, restitution 0, the
// collision group as b2Filter::groupIndex), gravity -10 m/s², sleeping off. Revolute joints:
// b2RevoluteJointDef with the local anchors, the reference angle (v3.1 referenceAngle; v3.2 a
// local frame on B turned by minus it, since v3.2 measures the angle between the two local
// frames) and enableLimit with lowerAngle/upperAngle. Wheel joints: b2WheelJointDef with the
// local anchors and axis (v3.1 localAxisA; v3.2 the x axis of the local frame on A), the spring
// (hertz, dampingRatio), the travel (enableLimit, lower/upperTranslation) and the motor
// (enableMotor, maxMotorTorque, motorSpeed). The world is a static body at the origin carrying
// the container (a ground box whose top is y = 0 and walls 1 m thick with inner faces x = 0 and
// x = width) and the terrain (a b2ChainDef through its points right to left, so that its one-
// sided segments face up, with a ghost point beyond each end so that every segment of the
// polyline is a segment of the chain). Everything else at v3's defaults (joint softness, …);
// b2World_Step(dt, 4).
//
// Its own deepest overlap: the largest -separation over the manifold points of every touching
// contact (b2Body_GetContactData), as boxes_box2d3.cpp's.
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "box2d3_release.hpp"
#include "joints.hpp"
#if FIXSTEP_BOX2D3_MINOR == 1
#include "discs_box2d3_tasks.hpp"
#endif

namespace discs::FIXSTEP_BOX2D3_NS {

namespace {

#include "box2d3_contacts.hpp"  // inside the release's namespace: its own copy

using joints::Pose;

/// A body's id in a type of this file only (see discs_box2d3.cpp's BodyRef).
struct JointBodyRef {
  b2BodyId id;
};
/// Chain points in a type of this file only, for the same reason.
struct ChainPoint {
  b2Vec2 p;
};
static_assert(sizeof(ChainPoint) == sizeof(b2Vec2));

b2Vec2 vec(joints::Vec2 v) {
  return {float(v.x), float(v.y)};
}
/// The rotation by `angle` (rad) to float precision: v3.1's b2MakeRot approximates cos and sin
/// (the ragdolls started up to 1.7·10^-3 rad off their angles).
b2Rot rot(double angle) {
  return {float(std::cos(angle)), float(std::sin(angle))};
}

class Box2d3Joints final : public joints::JointStepper {
 public:
  Box2d3Joints(const joints::JointScene& s, int workers) : workers_(workers) {
    b2WorldDef wd = b2DefaultWorldDef();
    wd.gravity = {0.0f, float(-joints::gravity)};
    wd.enableSleep = false;
#if FIXSTEP_BOX2D3_MINOR == 1
    if (workers > 1) {
      tasks_ = std::make_unique<Box2d3Tasks>(workers);
      wd.workerCount = tasks_->workers();
      wd.enqueueTask = &Box2d3Tasks::enqueue;
      wd.finishTask = &Box2d3Tasks::finish;
      wd.userTaskContext = tasks_.get();
    }
#else
    wd.workerCount = workers;  // > 1 without task callbacks: Box2D's own scheduler
#endif
    world_ = b2CreateWorld(&wd);
    add_statics(s);
    bodies_.reserve(s.bodies.size());
    for (const joints::BodySpec& b : s.bodies) {
      b2BodyDef bd = b2DefaultBodyDef();
      bd.type = b2_dynamicBody;
      bd.position = vec(b.position);
      bd.rotation = rot(b.angle);
      const b2BodyId id = b2CreateBody(world_, &bd);
      for (const joints::Shape& sh : b.shapes) add_shape(id, sh, b.group);
      bodies_.push_back({id});
    }
    for (const joints::JointSpec& j : s.joints) add_joint(j);
  }
  // The world goes before the task system (v3.1's tasks_ is destroyed after the destructor).
  ~Box2d3Joints() override {
    b2DestroyWorld(world_);
  }
  Box2d3Joints(const Box2d3Joints&) = delete;
  Box2d3Joints& operator=(const Box2d3Joints&) = delete;

  void step() override {
    b2World_Step(world_, float(joints::tick), box2d3_substeps);
  }
  void poses(std::vector<Pose>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const b2Vec2 p = b2Body_GetPosition(bodies_[j].id);
      const b2Rot q = b2Body_GetRotation(bodies_[j].id);
      out[j] = {{double(p.x), double(p.y)}, std::atan2(double(q.s), double(q.c))};
    }
  }
  [[nodiscard]] double own_overlap() const override {
    return deepest_manifold_overlap(bodies_);
  }
  [[nodiscard]] int threads() const override {
    return workers_;
  }

 private:
  void add_shape(b2BodyId body, const joints::Shape& sh, int group) {
    b2ShapeDef sd = b2DefaultShapeDef();
    sd.density = float(sh.density);
    sd.material.friction = float(sh.friction);
    sd.material.restitution = 0.0f;
    sd.filter.groupIndex = group;
    switch (sh.kind) {
      case joints::ShapeKind::circle: {
        const b2Circle c{vec(sh.center), float(sh.radius)};
        b2CreateCircleShape(body, &sd, &c);
        break;
      }
      case joints::ShapeKind::capsule: {
        const b2Capsule c{vec(sh.a), vec(sh.b), float(sh.radius)};
        b2CreateCapsuleShape(body, &sd, &c);
        break;
      }
      case joints::ShapeKind::box: {
        const b2Polygon p =
            b2MakeOffsetBox(float(sh.half.x), float(sh.half.y), vec(sh.center), b2Rot_identity);
        b2CreatePolygonShape(body, &sd, &p);
        break;
      }
    }
  }
  void add_statics(const joints::JointScene& s) {
    const b2BodyDef bd = b2DefaultBodyDef();  // static, at the origin
    ground_ = b2CreateBody(world_, &bd);
    b2ShapeDef sd = b2DefaultShapeDef();
    sd.material.friction = float(joints::friction);
    sd.material.restitution = 0.0f;
    if (s.container) {
      const auto w = float(s.width), h = float(s.wall_height / 2.0);
      const b2Polygon floor =
          b2MakeOffsetBox(w / 2.0f + 1.0f, 1.0f, {w / 2.0f, -1.0f}, b2Rot_identity);
      b2CreatePolygonShape(ground_, &sd, &floor);
      for (const float x : {-0.5f, w + 0.5f}) {
        const b2Polygon wall = b2MakeOffsetBox(0.5f, h, {x, h}, b2Rot_identity);
        b2CreatePolygonShape(ground_, &sd, &wall);
      }
    }
    if (s.terrain.size() >= 2) {
      // Right to left (the chain's segments face to the right of their direction: up), with a
      // ghost point beyond each end (an open chain's first and last points are ghosts only).
      const std::size_t n = s.terrain.size();
      const auto beyond = [](joints::Vec2 end, joints::Vec2 before) {
        return joints::Vec2{2.0 * end.x - before.x, 2.0 * end.y - before.y};
      };
      std::vector<ChainPoint> points;
      points.push_back({vec(beyond(s.terrain[n - 1], s.terrain[n - 2]))});
      for (std::size_t k = n; k-- > 0;) points.push_back({vec(s.terrain[k])});
      points.push_back({vec(beyond(s.terrain[0], s.terrain[1]))});
      b2SurfaceMaterial material = b2DefaultSurfaceMaterial();
      material.friction = float(joints::friction);
      b2ChainDef cd = b2DefaultChainDef();
      cd.points = &points.data()->p;
      cd.count = int(points.size());
      cd.materials = &material;
      cd.materialCount = 1;
      cd.isLoop = false;
      b2CreateChain(ground_, &cd);
    }
  }
  [[nodiscard]] b2BodyId body(int i) const {
    return i < 0 ? ground_ : bodies_[std::size_t(i)].id;
  }
  void add_joint(const joints::JointSpec& j) {
    const bool limit = j.lower.has_value() || j.upper.has_value();
    if (j.kind == joints::JointKind::revolute) {
      constexpr double pi = std::numbers::pi;
      b2RevoluteJointDef d = b2DefaultRevoluteJointDef();
#if FIXSTEP_BOX2D3_MINOR == 1
      d.bodyIdA = body(j.body_a);
      d.bodyIdB = body(j.body_b);
      d.localAnchorA = vec(j.local_a);
      d.localAnchorB = vec(j.local_b);
      d.referenceAngle = float(j.reference);
#else
      d.base.bodyIdA = body(j.body_a);
      d.base.bodyIdB = body(j.body_b);
      d.base.localFrameA = {vec(j.local_a), b2Rot_identity};
      d.base.localFrameB = {vec(j.local_b), rot(-j.reference)};
#endif
      d.enableLimit = limit;
      d.lowerAngle = float(j.lower.value_or(-pi));
      d.upperAngle = float(j.upper.value_or(pi));
      b2CreateRevoluteJoint(world_, &d);
      return;
    }
    b2WheelJointDef d = b2DefaultWheelJointDef();
#if FIXSTEP_BOX2D3_MINOR == 1
    d.bodyIdA = body(j.body_a);
    d.bodyIdB = body(j.body_b);
    d.localAnchorA = vec(j.local_a);
    d.localAnchorB = vec(j.local_b);
    d.localAxisA = vec(j.local_axis);
#else
    const double axis_angle = std::atan2(j.local_axis.y, j.local_axis.x);
    d.base.bodyIdA = body(j.body_a);
    d.base.bodyIdB = body(j.body_b);
    d.base.localFrameA = {vec(j.local_a), rot(axis_angle)};
    d.base.localFrameB = {vec(j.local_b), rot(axis_angle - j.reference)};
#endif
    d.enableSpring = true;
    d.hertz = float(j.frequency);
    d.dampingRatio = float(j.damping_ratio);
    d.enableLimit = limit;
    d.lowerTranslation = float(j.lower.value_or(-1e6));
    d.upperTranslation = float(j.upper.value_or(1e6));
    d.enableMotor = j.max_motor_torque > 0.0;
    d.maxMotorTorque = float(j.max_motor_torque);
    d.motorSpeed = float(j.motor_speed);
    b2CreateWheelJoint(world_, &d);
  }

  int workers_ = 1;
#if FIXSTEP_BOX2D3_MINOR == 1
  std::unique_ptr<Box2d3Tasks> tasks_;  // destroyed after the world (declared first)
#endif
  b2WorldId world_{};
  b2BodyId ground_{};
  std::vector<JointBodyRef> bodies_;
};

}  // namespace

std::unique_ptr<joints::JointStepper> make_joints(const joints::JointScene& s, int workers) {
  return std::make_unique<Box2d3Joints>(s, workers);
}

}  // namespace discs::FIXSTEP_BOX2D3_NS
