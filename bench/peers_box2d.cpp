// Box2D 2.4 (Debian 12 libbox2d-dev 2.4.1, float) stepping a coupled scene.
//
// One dynamic b2Body per body with fixed rotation, no fixture (so no broad phase work and no
// contacts) and its mass set with SetMassData; one b2DistanceJoint per link and per anchored
// spring (to a static ground body at the origin, local anchor = the anchor point) with
// stiffness k and damping b set directly (N/m, N·s/m), minLength 0 and maxLength FLT_MAX so
// the spring is soft (equal limits would make it rigid), no gravity, sleeping off, warm
// starting and continuous physics at their defaults; Step(dt, 8, 3): 8 velocity and 3
// position iterations, the values Box2D's manual and testbed use. The pull is applied with
// ApplyForceToCenter before every step: Box2D clears forces after each Step.
//
// Rest length: b2DistanceJoint clamps length, minLength and maxLength to at least
// b2_linearSlop = 0.005 m, so "length 0" is a spring of rest length 0.005 m, and a link
// shorter than that is pushed apart by its lower limit. On the chain every spring points the
// same way and stays 0.07-0.13 m long, so a rest length L acts exactly as the scene's
// rest length 0 with body j shifted by (j + 1) L along +x (Scene::rest_shift): the bodies
// start shifted and state() reports them shifted back, and the chain's errors compare with
// the exact solution of the L = 0 chain. On the cloth the springs turn, and Box2D simply runs
// its 5 mm rest length (the cloth is timed only).
//
// How Box2D steps (b2Island::Solve, b2DistanceJoint): v += dt F/m; the spring as a soft
// constraint, an implicit (backward Euler) spring-damper along d̂ solved by 8 Gauss–Seidel
// passes with warm starting; then x += v dt. Damping acts along d̂ only: the same as
// fixstep's on the chain, which moves along x.
#include <box2d/box2d.h>

#include <cfloat>
#include <vector>

#include "coupled.hpp"

namespace coupled {
namespace {

class Box2dPeer final : public Peer {
 public:
  Box2dPeer(const Scene& s, double dt) : world_(b2Vec2(0.0f, 0.0f)), dt_(float(dt)) {
    world_.SetAllowSleeping(false);
    const double slop = box2d_min_length();
    shift_.resize(s.bodies.size());
    if (!s.rest_shift.empty()) {
      for (std::size_t j = 0; j < shift_.size(); ++j) {
        shift_[j] = {slop * s.rest_shift[j].x, slop * s.rest_shift[j].y};
      }
    }
    b2BodyDef ground_def;  // static, at the origin
    b2Body* ground = world_.CreateBody(&ground_def);
    bodies_.reserve(s.bodies.size());
    for (std::size_t j = 0; j < s.bodies.size(); ++j) {
      const fixstep::BodyDef& d = s.bodies[j];
      b2BodyDef bd;
      bd.type = b2_dynamicBody;
      bd.fixedRotation = true;
      bd.allowSleep = false;
      bd.position.Set(float(d.body.position.x + shift_[j].x),
                      float(d.body.position.y + shift_[j].y));
      bd.linearVelocity.Set(float(d.body.velocity.x), float(d.body.velocity.y));
      b2Body* b = world_.CreateBody(&bd);
      b2MassData mass;
      mass.mass = float(d.body.mass);
      mass.center.SetZero();
      mass.I = 0.0f;
      b->SetMassData(&mass);
      bodies_.push_back(b);
      if (d.spring) {
        spring(ground, b, b2Vec2(float(d.spring->anchor.x), float(d.spring->anchor.y)),
               d.spring->rest_length, d.spring->stiffness, d.spring->damping);
      }
      if (d.constant_force) {
        pulled_.push_back(
            {b, b2Vec2(float(d.constant_force->force.x), float(d.constant_force->force.y))});
      }
    }
    for (const fixstep::IndexLink& l : s.links) {
      spring(bodies_[l.body_a], bodies_[l.body_b], b2Vec2(0.0f, 0.0f), l.spring.rest_length,
             l.spring.stiffness, l.spring.damping);
    }
  }

  void step() override {
    for (const Pull& p : pulled_) p.body->ApplyForceToCenter(p.force, true);
    world_.Step(dt_, box2d_velocity_iterations, box2d_position_iterations);
  }
  void state(std::span<fixstep::Body> out) const override {
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const b2Vec2 p = bodies_[j]->GetPosition(), v = bodies_[j]->GetLinearVelocity();
      out[j] = {double(bodies_[j]->GetMass()),
                {double(p.x) - shift_[j].x, double(p.y) - shift_[j].y},
                {double(v.x), double(v.y)}};
    }
  }

 private:
  void spring(b2Body* a, b2Body* b, b2Vec2 anchor_a, double rest, double k, double damping) {
    b2DistanceJointDef j;
    j.bodyA = a, j.bodyB = b;
    j.localAnchorA = anchor_a;
    j.localAnchorB.SetZero();
    j.length = float(rest);  // clamped to b2_linearSlop
    j.minLength = 0.0f;      // clamped to b2_linearSlop
    j.maxLength = FLT_MAX;
    j.stiffness = float(k);
    j.damping = float(damping);
    world_.CreateJoint(&j);
  }
  struct Pull {
    b2Body* body;
    b2Vec2 force;
  };
  b2World world_;
  float dt_;
  std::vector<b2Body*> bodies_;
  std::vector<fixstep::Vec2> shift_;
  std::vector<Pull> pulled_;
};

}  // namespace

std::unique_ptr<Peer> make_box2d(const Scene& s, double dt) {
  return std::make_unique<Box2dPeer>(s, dt);
}

// The package's version (from its CMake config): Box2D 2.4.1's own b2_version still says 2.4.0.
std::string box2d_version() {
  return BOX2D_PACKAGE_VERSION;
}

double box2d_min_length() {
  return double(b2_linearSlop);
}

}  // namespace coupled
