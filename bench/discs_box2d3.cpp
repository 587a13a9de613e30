// Box2D v3 (built from its source by bench/box2d3.cmake, float, its default SSE2; this file is
// compiled once per release, v3.1.1 and v3.2, FIXSTEP_BOX2D3_MINOR) stepping a disc scene, on 1
// worker (Box2D's own serial task functions) or on 2: v3.1, Box2d3Tasks (the caller and one
// helper thread); v3.2, its own scheduler (b2WorldDef::workerCount = 2 and no task callbacks:
// Box2D starts one thread of its own, physics_world.c).
//
// As for Box2D 2.4 (discs_box2d.cpp): one dynamic body per disc (it rotates: Box2D's normal
// circle) with one b2Circle of the scene's radius, density m / (π r²) so its mass is 1 kg; the
// box's walls are b2Segments (two-sided) on one static body; every shape has the scene's
// friction and restitution (v3 mixes a pair as √(μ_a μ_b) and max(e_a, e_b), as 2.4 does: the
// scene's values again) and the world's restitution threshold is 0 (its default, 1 m/s, makes
// slower impacts perfectly inelastic and would cool the elastic gas; 2.4 sets it per fixture).
// Gravity as the scene's, sleeping off (b2WorldDef::enableSleep; its default is on) except for
// the asleep steppers (box2d32_sleep_w1/_w2: its defaults, b2_timeToSleep 0.5 s),
// continuous collision, contact softness (30 Hz, damping ratio 10, push speed 3 m/s) and
// everything else at v3's defaults; b2World_Step(world, dt, 4): its default 4 substeps
// (types.h, b2World_Step's documentation; its samples' default). b2World_GetProfile() splits
// each step; its `pairs` (broadphase: new pairs from moved boxes) and `collide` (narrow phase)
// are summed here like 2.4's broadphase and collide.
#include <box2d/box2d.h>
#include <fmt/format.h>

#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "box2d3_release.hpp"
#include "discs.hpp"
#if FIXSTEP_BOX2D3_MINOR == 1
#include "discs_box2d3_tasks.hpp"
#endif

namespace discs::FIXSTEP_BOX2D3_NS {

using fixstep::Vec2;

namespace {

/// A body's id in a type of this file only: the releases' b2BodyId may differ, and a std::vector
/// of it would be one template instance (with external linkage) for both.
struct BodyRef {
  b2BodyId id;
};

class Box2d3Stepper final : public Stepper {
 public:
  Box2d3Stepper(const Scene& s, int workers, bool sleep) : workers_(workers) {
    b2WorldDef wd = b2DefaultWorldDef();
    wd.gravity = {0.0f, float(-s.gravity)};
    wd.enableSleep = sleep;
    wd.restitutionThreshold = 0.0f;
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
    add_walls(s);
    b2ShapeDef sd = shape_def(s);
    sd.density = float(mass / (std::numbers::pi * s.radius * s.radius));
    const b2Circle circle{{0.0f, 0.0f}, float(s.radius)};
    bodies_.reserve(s.position.size());
    for (std::size_t j = 0; j < s.position.size(); ++j) {
      b2BodyDef bd = b2DefaultBodyDef();
      bd.type = b2_dynamicBody;
      bd.position = {float(s.position[j].x), float(s.position[j].y)};
      bd.linearVelocity = {float(s.velocity[j].x), float(s.velocity[j].y)};
      if (s.ball && j + 1 == s.position.size()) bd.gravityScale = 0.0f;
      const b2BodyId b = b2CreateBody(world_, &bd);
      b2CreateCircleShape(b, &sd, &circle);
      bodies_.push_back({b});
    }
  }
  // The world goes before the task system (v3.1's tasks_ is destroyed after the destructor).
  ~Box2d3Stepper() override {
    b2DestroyWorld(world_);
  }
  Box2d3Stepper(const Box2d3Stepper&) = delete;
  Box2d3Stepper& operator=(const Box2d3Stepper&) = delete;

  void step() override {
    b2World_Step(world_, float(tick), box2d3_substeps);
    const b2Profile p = b2World_GetProfile(world_);
    step_ms_ += p.step, pairs_ms_ += p.pairs, collide_ms_ += p.collide;
  }
  void state(std::vector<Vec2>& x, std::vector<Vec2>& v) const override {
    x.resize(bodies_.size()), v.resize(bodies_.size());
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const b2Vec2 p = b2Body_GetPosition(bodies_[j].id);
      const b2Vec2 u = b2Body_GetLinearVelocity(bodies_[j].id);
      x[j] = {double(p.x), double(p.y)}, v[j] = {double(u.x), double(u.y)};
    }
  }
  [[nodiscard]] Stats stats() const override {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, pairs_ms_ / step_ms_, collide_ms_ / step_ms_, workers_};
  }

 private:
  static b2ShapeDef shape_def(const Scene& s) {
    b2ShapeDef sd = b2DefaultShapeDef();
    sd.material.friction = float(s.friction);
    sd.material.restitution = float(s.restitution);
    return sd;
  }
  void add_walls(const Scene& s) {
    b2BodyDef bd = b2DefaultBodyDef();  // static, at the origin
    const b2BodyId walls = b2CreateBody(world_, &bd);
    const b2ShapeDef sd = shape_def(s);
    const auto w = float(s.width), h = float(s.height);
    const b2Vec2 corner[4] = {{0.0f, 0.0f}, {w, 0.0f}, {w, h}, {0.0f, h}};
    for (int k = 0; k < 4; ++k) {
      if (k == 2 && !s.lid) continue;  // the segment from (w, h) to (0, h)
      const b2Segment segment{corner[k], corner[(k + 1) % 4]};
      b2CreateSegmentShape(walls, &sd, &segment);
    }
  }
  int workers_ = 1;
#if FIXSTEP_BOX2D3_MINOR == 1
  std::unique_ptr<Box2d3Tasks> tasks_;  // destroyed after the world (declared first)
#endif
  b2WorldId world_{};
  std::vector<BodyRef> bodies_;
  double step_ms_ = 0.0, pairs_ms_ = 0.0, collide_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<Stepper> make_discs(const Scene& s, int workers, bool sleep) {
  return std::make_unique<Box2d3Stepper>(s, workers, sleep);
}

std::string version() {
  const b2Version v = b2GetVersion();
  return fmt::format("{}.{}.{}", v.major, v.minor, v.revision);
}

double linear_slop() {
  // B2_LINEAR_SLOP (v3.1: src/constants.h, internal; v3.2: include/box2d/constants.h): 0.005
  // length units per metre.
  return 0.005 * double(b2GetLengthUnitsPerMeter());
}

}  // namespace discs::FIXSTEP_BOX2D3_NS
