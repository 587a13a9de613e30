// fixstep stepping a box scene: World (f64, semi-implicit Euler, the default) built from a
// WorldDef with one dynamic body per box carrying one box shape (BodyDef::shapes: half-extents
// 0.5 m, density 1 kg/m², so 1 kg, μ and e the scene's), Gravity -10 m/s², the ground and the
// container's walls as static half-planes (PlaneDef, the same μ and e), WorldSettings::contacts
// on (the scene's μ and e) and WorldSettings::threads 1 or 2.
//
// fixstep_shapes_problem() checks that World collides shapes (a dropped box comes to rest on the
// ground) before anything is timed; bench_boxes reports the reason and leaves fixstep's rows out
// when it does not.
//
// The deepest overlap is measured from the poses World::body() gives (position = the box's
// centre: a centred box's centre of mass is its origin; angle) by boxes_scene.cpp's separating
// axis test, as for Box2D; fixstep's own report (ContactStats::deepest_shape_overlap, over the
// manifold points of the last tick) is its own_overlap.
#include <fmt/format.h>

#include <cmath>
#include <exception>
#include <memory>

#include "boxes.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace boxes {

namespace {

fixstep::WorldDef world_def(const BoxScene& s, int threads) {
  fixstep::WorldSettings ws{.dt = tick, .threads = threads};
  ws.contacts = fixstep::ContactSettings{.restitution = restitution, .friction = friction};
  fixstep::WorldDef def = fixstep::WorldDef::empty(fixstep::Precision::f64, ws);
  const auto wall = [&](Vec2 normal, double offset) {
    def.planes.push_back(
        {.normal = normal, .offset = offset, .restitution = restitution, .friction = friction});
  };
  wall({0.0, 1.0}, 0.0);  // the ground, y >= 0
  if (s.width > 0.0) {
    wall({1.0, 0.0}, 0.0);        // x >= 0
    wall({-1.0, 0.0}, -s.width);  // x <= width
  }
  fixstep::ShapeDef box = fixstep::make_box(half, half);
  box.density = density;
  box.friction = friction;
  box.restitution = restitution;
  def.bodies.reserve(s.start.size());
  for (const Pose& p : s.start) {
    fixstep::BodyDef b;
    b.body = {.mass = density * 4.0 * half * half, .position = p.position, .angle = p.angle};
    b.gravity = fixstep::Gravity{{0.0, -gravity}};
    b.shapes = {box};
    def.add_body(std::move(b));
  }
  return def;
}

class FixstepBoxes final : public BoxStepper {
 public:
  FixstepBoxes(const BoxScene& s, int threads) : world_(world_def(s, threads)), threads_(threads) {}
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

std::optional<std::string> fixstep_shapes_problem() {
  // A 1 m box dropped from rest, its bottom 0.5 m above the ground: after 2 s it must rest on
  // the ground (centre at 0.5 m, upright).
  BoxScene drop{.kind = BoxSceneKind::pyramid, .start = {{{0.0, 1.0}, 0.0}}};
  try {
    const auto p = make_fixstep_boxes(drop, 1);
    for (int t = 0; t < 120; ++t) p->step();
    std::vector<Pose> x;
    p->poses(x);
    if (x.size() != 1 || !(std::abs(x[0].position.y - half) < 0.05) ||
        !(std::abs(x[0].angle) < 0.05)) {
      return fmt::format(
          "World accepts BodyDef::shapes but does not collide them: a 1 m box dropped onto "
          "the ground is at y = {:.3g} m, angle {:.3g} rad after 2 s (resting: 0.5 m, 0)",
          x.empty() ? std::nan("") : x[0].position.y, x.empty() ? std::nan("") : x[0].angle);
    }
  } catch (const std::exception& e) {
    return fmt::format("World(def) refuses bodies with shapes: {}", e.what());
  }
  return std::nullopt;
}

std::unique_ptr<BoxStepper> make_fixstep_boxes(const BoxScene& s, int threads) {
  return std::make_unique<FixstepBoxes>(s, threads);
}

}  // namespace boxes
