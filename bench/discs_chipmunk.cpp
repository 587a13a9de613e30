// Chipmunk2D 7 (Debian 12 libchipmunk-dev 7.0.3, cpFloat = double) stepping a disc scene.
//
// One cpBody per disc (mass 1 kg, moment cpMomentForCircle: it rotates) with one cpCircleShape
// of the scene's radius; the box's walls are cpSegmentShapes on the space's static body, 10 r
// thick (segment radius) with their surface on the box's lines. Chipmunk combines a pair's
// elasticity and friction as the product of the two shapes' (cpArbiter), so every shape carries √e
// and √μ and each pair gets the scene's e and μ. Gravity as the scene's, the default 10 solver
// iterations, sleeping off (its default), the collision slop set to Box2D's b2_linearSlop, 0.005 m
// (Chipmunk's default, 0.1, is meant for pixels: it would let these 5 cm discs sink 10 cm into each
// other), the default collision bias (10 % of an overlap removed per 1/60 s). Its spatial index is
// one of:
//   hash   cpSpaceUseSpatialHash(space, 2r, N): a spatial hash of cell 2r and N cells;
//   tree   the default bounding-box tree (with its temporal coherence);
//   hasty  cpHastySpace (the default tree) with cpHastySpaceSetThreads(2): its solver on two
//          threads.
#include <chipmunk/chipmunk.h>
// cpHastySpace.h, unlike chipmunk.h, declares its functions without extern "C".
extern "C" {
#include <chipmunk/cpHastySpace.h>
}

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "discs.hpp"

namespace discs {

using fixstep::Vec2;

namespace {

class ChipmunkStepper final : public Stepper {
 public:
  ChipmunkStepper(const Scene& s, ChipmunkIndex index) : hasty_(index == ChipmunkIndex::hasty) {
    space_ = hasty_ ? cpHastySpaceNew() : cpSpaceNew();
    if (hasty_) cpHastySpaceSetThreads(space_, 2);
    cpSpaceSetIterations(space_, chipmunk_iterations);
    cpSpaceSetGravity(space_, cpv(0.0, -s.gravity));
    cpSpaceSetCollisionSlop(space_, chipmunk_slop);
    if (index == ChipmunkIndex::hash) {
      cpSpaceUseSpatialHash(space_, 2.0 * s.radius, int(s.position.size()));
    }
    const double e = std::sqrt(s.restitution), mu = std::sqrt(s.friction);
    add_walls(s, e, mu);
    bodies_.reserve(s.position.size());
    for (std::size_t j = 0; j < s.position.size(); ++j) {
      cpBody* b =
          cpSpaceAddBody(space_, cpBodyNew(mass, cpMomentForCircle(mass, 0.0, s.radius, cpvzero)));
      cpBodySetPosition(b, cpv(s.position[j].x, s.position[j].y));
      cpBodySetVelocity(b, cpv(s.velocity[j].x, s.velocity[j].y));
      bodies_.push_back(b);
      add_shape(cpCircleShapeNew(b, s.radius, cpvzero), e, mu);
    }
  }
  ~ChipmunkStepper() override {
    // The space first (it only drops its arrays), then what it held: removing 10^5 bodies one
    // by one would search its arrays each time.
    if (hasty_)
      cpHastySpaceFree(space_);
    else
      cpSpaceFree(space_);
    for (cpShape* sh : shapes_) cpShapeFree(sh);
    for (cpBody* b : bodies_) cpBodyFree(b);
  }
  ChipmunkStepper(const ChipmunkStepper&) = delete;
  ChipmunkStepper& operator=(const ChipmunkStepper&) = delete;

  void step() override {
    if (hasty_)
      cpHastySpaceStep(space_, tick);
    else
      cpSpaceStep(space_, tick);
  }
  void state(std::vector<Vec2>& x, std::vector<Vec2>& v) const override {
    x.resize(bodies_.size()), v.resize(bodies_.size());
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const cpVect p = cpBodyGetPosition(bodies_[j]), u = cpBodyGetVelocity(bodies_[j]);
      x[j] = {p.x, p.y}, v[j] = {u.x, u.y};
    }
  }
  [[nodiscard]] Stats stats() const override {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, nan, nan, hasty_ ? int(cpHastySpaceGetThreads(space_)) : 1};
  }

 private:
  void add_shape(cpShape* sh, double e, double mu) {
    cpShapeSetElasticity(sh, e);
    cpShapeSetFriction(sh, mu);
    cpSpaceAddShape(space_, sh);
    shapes_.push_back(sh);
  }
  /// Thick walls: segments of radius 10 r moved out by it, so their surface is the
  /// box's line; thin ones (radius 0) let fast gas discs through (Chipmunk has no continuous
  /// collision), which the checks caught.
  void add_walls(const Scene& s, double e, double mu) {
    cpBody* ground = cpSpaceGetStaticBody(space_);
    const double t = 10.0 * s.radius, w = s.width, h = s.height;
    const auto wall = [&](cpVect a, cpVect b) {
      add_shape(cpSegmentShapeNew(ground, a, b, t), e, mu);
    };
    wall(cpv(-t, -t), cpv(w + t, -t));        // ground
    wall(cpv(-t, -t), cpv(-t, h + t));        // left
    wall(cpv(w + t, -t), cpv(w + t, h + t));  // right
    if (s.lid) wall(cpv(-t, h + t), cpv(w + t, h + t));
  }
  bool hasty_;
  cpSpace* space_ = nullptr;
  std::vector<cpBody*> bodies_;
  std::vector<cpShape*> shapes_;
};

}  // namespace

std::unique_ptr<Stepper> make_chipmunk(const Scene& s, ChipmunkIndex index) {
  return std::make_unique<ChipmunkStepper>(s, index);
}

std::string chipmunk_version() {
  return cpVersionString;
}

}  // namespace discs
