// Box2D v3 (compiled once per release, v3.1.1 and v3.2: FIXSTEP_BOX2D3_MINOR) stepping a box
// scene, on 1 worker or on 2 as its disc stepper (discs_box2d3.cpp: v3.1 Box2d3Tasks, v3.2 its
// own scheduler).
//
// As Box2D's own benchmark pyramid (shared/benchmarks.c, CreateLargePyramid): one dynamic body
// per box with a b2MakeBox(0.5, 0.5) polygon of density 1 (1 kg), friction and restitution at
// b2DefaultShapeDef's (0.6, 0), gravity at b2DefaultWorldDef's (-10 m/s²), sleeping off; the
// ground a static body with a b2MakeBox(100, 1) polygon at (0, -1) (its top at y = 0), widened
// to the container for the pile, whose walls are static boxes 1 m thick with their inner faces
// at x = 0 and x = width. Everything else at v3's defaults; b2World_Step(dt, 4).
//
// Its own deepest overlap: the largest -separation over the manifold points of every touching
// contact (b2Body_GetContactData of each box), which Box2D computes in its collide phase at the
// start of a step.
#include <box2d/box2d.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

#include "box2d3_release.hpp"
#include "boxes.hpp"
#if FIXSTEP_BOX2D3_MINOR == 1
#include "discs_box2d3_tasks.hpp"
#endif

namespace discs::FIXSTEP_BOX2D3_NS {

namespace {

#include "box2d3_contacts.hpp"  // inside the release's namespace: its own copy

using boxes::Pose;

/// A body's id in a type of this file only (see discs_box2d3.cpp's BodyRef).
struct BoxRef {
  b2BodyId id;
};

class Box2d3Boxes final : public boxes::BoxStepper {
 public:
  Box2d3Boxes(const boxes::BoxScene& s, int workers) : workers_(workers) {
    b2WorldDef wd = b2DefaultWorldDef();
    wd.gravity = {0.0f, float(-boxes::gravity)};
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
    b2ShapeDef sd = shape_def();
    sd.density = float(boxes::density);
    const b2Polygon box = b2MakeBox(float(boxes::half), float(boxes::half));
    bodies_.reserve(s.start.size());
    for (const Pose& p : s.start) {
      b2BodyDef bd = b2DefaultBodyDef();
      bd.type = b2_dynamicBody;
      bd.position = {float(p.position.x), float(p.position.y)};
      bd.rotation = b2MakeRot(float(p.angle));
      const b2BodyId b = b2CreateBody(world_, &bd);
      b2CreatePolygonShape(b, &sd, &box);
      bodies_.push_back({b});
    }
  }
  // The world goes before the task system (v3.1's tasks_ is destroyed after the destructor).
  ~Box2d3Boxes() override {
    b2DestroyWorld(world_);
  }
  Box2d3Boxes(const Box2d3Boxes&) = delete;
  Box2d3Boxes& operator=(const Box2d3Boxes&) = delete;

  void step() override {
    b2World_Step(world_, float(boxes::tick), box2d3_substeps);
  }
  void poses(std::vector<Pose>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const b2Vec2 p = b2Body_GetPosition(bodies_[j].id);
      const b2Rot q = b2Body_GetRotation(bodies_[j].id);
      out[j] = {{double(p.x), double(p.y)}, double(b2Rot_GetAngle(q))};
    }
  }
  [[nodiscard]] double own_overlap() const override {
    return deepest_manifold_overlap(bodies_);
  }
  [[nodiscard]] int threads() const override {
    return workers_;
  }

 private:
  static b2ShapeDef shape_def() {
    b2ShapeDef sd = b2DefaultShapeDef();
    sd.material.friction = float(boxes::friction);
    sd.material.restitution = float(boxes::restitution);
    return sd;
  }
  void add_statics(const boxes::BoxScene& s) {
    b2BodyDef bd = b2DefaultBodyDef();  // static
    bd.position = {float(s.width / 2.0), -1.0f};
    const b2BodyId ground = b2CreateBody(world_, &bd);
    const b2ShapeDef sd = shape_def();
    // The pyramid's ground as Box2D's (100 m half-width); the container's as wide as it is.
    const float ground_half = s.width > 0.0 ? float(s.width / 2.0 + 1.0) : 100.0f;
    const b2Polygon floor = b2MakeBox(ground_half, 1.0f);
    b2CreatePolygonShape(ground, &sd, &floor);
    if (s.width <= 0.0) return;
    const auto h = float(s.wall_height / 2.0);
    for (const float x : {-float(s.width / 2.0) - 0.5f, float(s.width / 2.0) + 0.5f}) {
      // Relative to the ground body at (width / 2, -1): from y = 0 up to wall_height.
      const b2Polygon wall = b2MakeOffsetBox(0.5f, h, {x, 1.0f + h}, b2MakeRot(0.0f));
      b2CreatePolygonShape(ground, &sd, &wall);
    }
  }
  int workers_ = 1;
#if FIXSTEP_BOX2D3_MINOR == 1
  std::unique_ptr<Box2d3Tasks> tasks_;  // destroyed after the world (declared first)
#endif
  b2WorldId world_{};
  std::vector<BoxRef> bodies_;
};

}  // namespace

std::unique_ptr<boxes::BoxStepper> make_boxes(const boxes::BoxScene& s, int workers) {
  return std::make_unique<Box2d3Boxes>(s, workers);
}

}  // namespace discs::FIXSTEP_BOX2D3_NS
