// Chipmunk2D 7 (Debian 12 libchipmunk-dev 7.0.3, cpFloat = double) stepping a coupled scene.
//
// One cpBody per body (mass m, moment INFINITY: no rotation, no collision shape), one
// cpDampedSpring per link (anchors at the bodies' centres, rest length 0, stiffness k,
// damping b) and per anchored spring (from the space's static body, anchor in world
// coordinates), no gravity, space damping 1, cpSpaceStep(dt) with the default 10 solver
// iterations, sleeping off (Chipmunk's default). The pull is set with cpBodySetForce before
// every step: Chipmunk clears forces after integrating them.
//
// How Chipmunk steps (cpSpaceStep.c, cpDampedSpring.c): positions first, x += v dt; then each
// spring's force -k(|d| - L) along d̂ at the new positions, applied as an impulse; then
// velocities; then the damping, along d̂ only, as `iterations` Gauss–Seidel passes that relax
// each spring's relative normal velocity by the exact factor e^{-b dt (1/m_a + 1/m_b)}. So it
// is symplectic Euler in the position-first order, with the damping exact per spring. On the
// chain, which moves along x only, damping along d̂ is fixstep's damping of the full relative
// velocity; on the cloth it is not (fixstep's L = 0 link damps the whole relative velocity).
#include <chipmunk/chipmunk.h>

#include <cmath>
#include <vector>

#include "coupled.hpp"

namespace coupled {
namespace {

class ChipmunkPeer final : public Peer {
 public:
  ChipmunkPeer(const Scene& s, double dt) : dt_(dt) {
    space_ = cpSpaceNew();
    cpSpaceSetIterations(space_, chipmunk_iterations);
    cpSpaceSetGravity(space_, cpvzero);
    cpBody* ground = cpSpaceGetStaticBody(space_);
    bodies_.reserve(s.bodies.size());
    for (const fixstep::BodyDef& d : s.bodies) {
      cpBody* b = cpSpaceAddBody(space_, cpBodyNew(d.body.mass, INFINITY));
      cpBodySetPosition(b, cpv(d.body.position.x, d.body.position.y));
      cpBodySetVelocity(b, cpv(d.body.velocity.x, d.body.velocity.y));
      bodies_.push_back(b);
      if (d.spring) {
        springs_.push_back(cpSpaceAddConstraint(
            space_,
            cpDampedSpringNew(ground, b, cpv(d.spring->anchor.x, d.spring->anchor.y), cpvzero,
                              d.spring->rest_length, d.spring->stiffness, d.spring->damping)));
      }
      if (d.constant_force) {
        pulled_.push_back({b, cpv(d.constant_force->force.x, d.constant_force->force.y)});
      }
    }
    for (const fixstep::IndexLink& l : s.links) {
      springs_.push_back(cpSpaceAddConstraint(
          space_, cpDampedSpringNew(bodies_[l.body_a], bodies_[l.body_b], cpvzero, cpvzero,
                                    l.spring.rest_length, l.spring.stiffness, l.spring.damping)));
    }
  }
  ~ChipmunkPeer() override {
    // Free the space first (it only drops its arrays), then what it held: removing 10^5 bodies
    // one by one would search its arrays each time.
    cpSpaceFree(space_);
    for (cpConstraint* c : springs_) cpConstraintFree(c);
    for (cpBody* b : bodies_) cpBodyFree(b);
  }
  ChipmunkPeer(const ChipmunkPeer&) = delete;
  ChipmunkPeer& operator=(const ChipmunkPeer&) = delete;

  void step() override {
    for (const Pull& p : pulled_) cpBodySetForce(p.body, p.force);
    cpSpaceStep(space_, dt_);
  }
  void state(std::span<fixstep::Body> out) const override {
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const cpVect p = cpBodyGetPosition(bodies_[j]), v = cpBodyGetVelocity(bodies_[j]);
      out[j] = {cpBodyGetMass(bodies_[j]), {p.x, p.y}, {v.x, v.y}};
    }
  }

 private:
  struct Pull {
    cpBody* body;
    cpVect force;
  };
  double dt_;
  cpSpace* space_ = nullptr;
  std::vector<cpBody*> bodies_;
  std::vector<cpConstraint*> springs_;
  std::vector<Pull> pulled_;
};

}  // namespace

std::unique_ptr<Peer> make_chipmunk(const Scene& s, double dt) {
  return std::make_unique<ChipmunkPeer>(s, dt);
}

std::string chipmunk_version() {
  return cpVersionString;
}

}  // namespace coupled
