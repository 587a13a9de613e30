// fixstep stepping a disc scene: a fixstep::detail::WorldKernel<Real> (semi-implicit Euler, the
// default) with one dynamic body per disc (Collider{radius}, mass 1 kg, Gravity in the pile), the
// box's walls as static half-planes (PlaneDef, the scene's e and μ), and WorldSettings::contacts =
// the scene's e and μ, on 1 or 2 threads (WorldSettings::threads), with the resting solver's
// default iterations or Box2D 2.4's 8 velocity / 3 position ones, and with rolling discs
// (ContactSettings::rolling: uniform discs, I = ½ m r²) or without. The "contacts off" variant is
// the same world without WorldSettings::contacts: the discs meet the walls only (a world that does
// not ask for contacts, for the before/after of the contact code).
#include <limits>
#include <memory>

#include "discs.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace discs {

using fixstep::Vec2;

namespace {

template <class Real>
class FixstepStepper final : public Stepper {
 public:
  FixstepStepper(const Scene& s, int threads, bool contacts, bool box2d_iterations, bool rolling,
                 bool sleep)
      : w_(std::make_unique<fixstep::detail::WorldKernel<Real>>(
            settings(s, threads, contacts, box2d_iterations, rolling, sleep))) {
    w_->reserve(s.position.size());
    add_walls(s);
    for (std::size_t j = 0; j < s.position.size(); ++j) {
      fixstep::BodyDef d;
      d.body = {.mass = mass, .position = s.position[j], .velocity = s.velocity[j]};
      const bool ball = s.ball && j + 1 == s.position.size();
      if (s.gravity != 0.0 && !ball) d.gravity = fixstep::Gravity{{0.0, -s.gravity}};
      d.collider = fixstep::Collider{.radius = s.radius};
      w_->create_body(d);
    }
  }
  void step() override { w_->step(); }
  void state(std::vector<Vec2>& x, std::vector<Vec2>& v) const override {
    const std::size_t n = w_->body_count();
    x.resize(n), v.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      x[j] = {double(w_->x()[j]), double(w_->y()[j])};
      v[j] = {double(w_->vx()[j]), double(w_->vy()[j])};
    }
  }
  [[nodiscard]] Stats stats() const override {
    const fixstep::ContactStats& c = w_->contact_stats();
    const fixstep::StepProfile& p = w_->profile();
    return {.candidate_pairs = double(c.candidate_pairs),
            .touching = double(c.touching),
            .impacts = double(c.impacts),
            .self_overlap = c.max_overlap,
            .broadphase_share = nan(),
            .collide_share = nan(),
            .threads = w_->threads_used(),
            .velocity_sweeps = c.velocity_sweeps,
            .position_sweeps = c.position_sweeps,
            .broadphase_s = p.broadphase,
            .impacts_s = p.impacts,
            .resting_s = p.resting,
            .other_s = p.step - p.broadphase - p.impacts - p.resting};
  }

 private:
  static double nan() { return std::numeric_limits<double>::quiet_NaN(); }
  static fixstep::WorldSettings settings(const Scene& s, int threads, bool contacts,
                                         bool box2d_iterations, bool rolling, bool sleep) {
    fixstep::WorldSettings ws{.dt = tick, .threads = threads};
    if (contacts) {
      ws.contacts = fixstep::ContactSettings{.restitution = s.restitution, .friction = s.friction};
      ws.contacts->rolling = rolling;
      ws.contacts->sleep = sleep;
      if (box2d_iterations) {
        ws.contacts->velocity_iterations = box2d_velocity_iterations;
        ws.contacts->position_iterations = box2d_position_iterations;
      }
    }
    return ws;
  }
  void add_walls(const Scene& s) {
    const auto wall = [&](Vec2 normal, double offset) {
      w_->add_plane({.normal = normal,
                     .offset = offset,
                     .restitution = s.restitution,
                     .friction = s.friction});
    };
    wall({0.0, 1.0}, 0.0);        // ground y >= 0
    wall({1.0, 0.0}, 0.0);        // left wall x >= 0
    wall({-1.0, 0.0}, -s.width);  // right wall x <= width
    if (s.lid) wall({0.0, -1.0}, -s.height);
  }
  std::unique_ptr<fixstep::detail::WorldKernel<Real>> w_;
};

}  // namespace

std::unique_ptr<Stepper> make_fixstep(const Scene& s, bool f32, int threads, bool contacts,
                                      bool box2d_iterations, bool rolling, bool sleep) {
  if (f32) {
    return std::make_unique<FixstepStepper<float>>(s, threads, contacts, box2d_iterations, rolling,
                                                   sleep);
  }
  return std::make_unique<FixstepStepper<double>>(s, threads, contacts, box2d_iterations, rolling,
                                                  sleep);
}

}  // namespace discs
