// Box2D 2.4 (Debian 12 libbox2d-dev 2.4.1, float) stepping a disc scene.
//
// One dynamic b2Body per disc (it rotates) with one b2CircleShape fixture of the scene's
// radius, density m / (π r²) so its mass is 1 kg; the box's walls are two-sided b2EdgeShapes on
// one static body. Every fixture has the scene's friction and restitution (Box2D mixes a pair
// as √(μ_a μ_b) and max(e_a, e_b): the scene's values again) and restitutionThreshold 0 (its
// default, 1 m/s, makes slower impacts perfectly inelastic, which would cool the elastic gas).
// Gravity as the scene's, sleeping off (its default is on: a settled pile would fall asleep
// and cost next to nothing; fixstep and Chipmunk here do not sleep), continuous physics and
// warm starting at their defaults (on), Step(dt, 8, 3): the iterations of Box2D's manual and
// testbed. b2World::GetProfile() splits each step; its broadphase (pairs of moved boxes in
// the dynamic tree) and collide (narrow phase of the contacts kept) times are summed here.
#include <box2d/box2d.h>

#include <limits>
#include <numbers>
#include <vector>

#include "discs.hpp"

namespace discs {

using fixstep::Vec2;

namespace {

class Box2dStepper final : public Stepper {
 public:
  explicit Box2dStepper(const Scene& s) : world_(b2Vec2(0.0f, float(-s.gravity))) {
    world_.SetAllowSleeping(false);
    add_walls(s);
    b2CircleShape circle;
    circle.m_radius = float(s.radius);
    b2FixtureDef fd = fixture(s, &circle);
    fd.density = float(mass / (std::numbers::pi * s.radius * s.radius));
    bodies_.reserve(s.position.size());
    for (std::size_t j = 0; j < s.position.size(); ++j) {
      b2BodyDef bd;
      bd.type = b2_dynamicBody;
      bd.position.Set(float(s.position[j].x), float(s.position[j].y));
      bd.linearVelocity.Set(float(s.velocity[j].x), float(s.velocity[j].y));
      b2Body* b = world_.CreateBody(&bd);
      b->CreateFixture(&fd);
      bodies_.push_back(b);
    }
  }

  void step() override {
    world_.Step(float(tick), box2d_velocity_iterations, box2d_position_iterations);
    const b2Profile& p = world_.GetProfile();
    step_ms_ += p.step, broadphase_ms_ += p.broadphase, collide_ms_ += p.collide;
  }
  void state(std::vector<Vec2>& x, std::vector<Vec2>& v) const override {
    x.resize(bodies_.size()), v.resize(bodies_.size());
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const b2Vec2 p = bodies_[j]->GetPosition(), u = bodies_[j]->GetLinearVelocity();
      x[j] = {double(p.x), double(p.y)}, v[j] = {double(u.x), double(u.y)};
    }
  }
  [[nodiscard]] Stats stats() const override {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, broadphase_ms_ / step_ms_, collide_ms_ / step_ms_, 1};
  }

 private:
  static b2FixtureDef fixture(const Scene& s, const b2Shape* shape) {
    b2FixtureDef fd;
    fd.shape = shape;
    fd.friction = float(s.friction);
    fd.restitution = float(s.restitution);
    fd.restitutionThreshold = 0.0f;
    return fd;
  }
  void add_walls(const Scene& s) {
    b2BodyDef bd;  // static, at the origin
    b2Body* walls = world_.CreateBody(&bd);
    const auto w = float(s.width), h = float(s.height);
    const b2Vec2 corner[4] = {{0.0f, 0.0f}, {w, 0.0f}, {w, h}, {0.0f, h}};
    for (int k = 0; k < 4; ++k) {
      if (k == 2 && !s.lid) continue;  // the edge from (w, h) to (0, h)
      b2EdgeShape edge;
      edge.SetTwoSided(corner[k], corner[(k + 1) % 4]);
      const b2FixtureDef fd = fixture(s, &edge);
      walls->CreateFixture(&fd);
    }
  }
  b2World world_;
  std::vector<b2Body*> bodies_;
  double step_ms_ = 0.0, broadphase_ms_ = 0.0, collide_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<Stepper> make_box2d(const Scene& s) {
  return std::make_unique<Box2dStepper>(s);
}

// The package's version (from its CMake config): Box2D 2.4.1's own b2_version still says 2.4.0.
std::string box2d_version() {
  return BOX2D_PACKAGE_VERSION;
}

double box2d_linear_slop() {
  return double(b2_linearSlop);
}

}  // namespace discs
